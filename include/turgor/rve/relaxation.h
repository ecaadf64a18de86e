#pragma once
/* The relaxation of an RVE, G(w) = 0 (TW 562 eq 27), two ways:
   - cold: the seed's pseudo-transient continuation (eq 28) with PETSc TSPSEUDO, one linear solve per
     pseudo step, delta_0, delta <- increment x delta, stop at ||step|| < steptol or ||G|| < atol;
   - warm (from a previous solution): the limit delta -> infinity of eq 28, i.e. Newton, with G'
     and its LU factors kept from the last solve (modified Newton), backtracking on a fresh G'.
   G' comes from MatFDColoring on the interaction graph, rebuilt only when new neighbours couple
   unknowns the pattern does not cover. Both solves use one LU factorisation of G' + shift I kept
   here (the TSPSEUDO linear solve through a shell PC), so -rve_pc_* options do not apply.

   The same factor serves the exact tangents (SolveLinearized): the linearised relaxation
   G_w z = b at a relaxed state, by GMRES preconditioned with it. */
#include <turgor/material/material_point.h>
#include <turgor/rve/rve_equations.h>
#include <turgor/rve/rve_spec.h>
#include <petscts.h>

namespace turgor {

class RVERelaxation {
public:
  RVERelaxation()                                 = default;
  RVERelaxation(const RVERelaxation &)            = delete;
  RVERelaxation &operator=(const RVERelaxation &) = delete;
  ~RVERelaxation();

  PetscErrorCode SetUp(MPI_Comm comm, RVEEquations &eq, const RVESpec &spec);
  /* From the content of W; out gets the iteration counts, the residual and, on failure, ok = false
     and the reason. */
  PetscErrorCode Cold(Vec W, MaterialResponse *out);
  /* *converged = false sends the caller to a cold solve. */
  PetscErrorCode Warm(Vec W, MaterialResponse *out, bool *converged);
  PetscInt       Jacobians() const { return jacobians_; }
  /* z = G_w(W)^-1 b at the current deformation (implicit differentiation of the relaxed state):
     GMRES (prefix rve_tangent_: rtol 1e-8 of |b| by default, right preconditioning so that the
     test is on the true residual) on the central-difference action of G_w, preconditioned by the
     kept LU factor (computed at W first if there is none). The factor is usually of an older G'
     (modified Newton), hence the Krylov iterations, each one residual pair; where GMRES does not
     converge with it, G' and its factor are taken at W and the solve is tried once more (a factor
     of a state far from W can precondition too badly: the K = 16, seed-5 tissue at its released
     state). *its: iterations of both tries; *ok = false when GMRES did not converge. */
  PetscErrorCode SolveLinearized(Vec W, Vec b, Vec z, PetscInt *its, bool *ok);
  /* Checkpoints: the Jacobian pattern (rebuilt with the neighbour lists), the kept G' and J = G' +
     shift I whose LU factor the next warm solve reuses (modified Newton; the factor is recomputed
     from J, bit for bit), and the Jacobian count. Collective on the RVE's communicator. */
  void           DeclareState(StateDeclaration &d);
  PetscErrorCode AfterStateRead(); /* collective on the group */

private:
  static PetscErrorCode IFunction(TS ts, PetscReal t, Vec W, Vec Wdot, Vec F, void *ctx);
  static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec W, Vec Wdot, PetscReal shift, Mat A, Mat B, void *ctx);
  static PetscErrorCode ColoringResidual(void *unused, Vec W, Vec R, void *ctx);
  static PetscErrorCode PseudoStep(TS ts, PetscReal *dt, void *ctx);
  static PetscErrorCode PreStep(TS ts);
  static PetscErrorCode PostStep(TS ts);
  static PetscErrorCode VerifyStep(TS ts, Vec W, void *ctx, PetscReal *dt, PetscBool *ok);
  static PetscErrorCode StartFromAccepted(SNES snes, Vec W, void *ctx);

  PetscErrorCode        BuildJacobianPattern(const std::vector<std::vector<PetscInt>> *given = nullptr); /* given: these columns, not the lists' */
  PetscErrorCode        PatternStale(PetscBool *stale);
  PetscErrorCode        Refresh(Vec W);                                     /* K = G'(W) by colouring */
  PetscErrorCode        AndersonStep(Vec W, bool refresh, bool *have_prev); /* W += dW_, from D_ (Warm) */
  PetscErrorCode        Factor(bool *ok);                                   /* J's LU factors, up to date (collective on the group) */
  PetscErrorCode        FactorHere(bool *ok);                               /* the same, on the group's first rank */
  PetscErrorCode        ApplyFactor(Vec x, Vec y);                          /* y = J^-1 x */
  PetscErrorCode        FactorAsPC(PC pc);                                  /* pc applies factor_ (a shell) */
  static PetscErrorCode FactorSetUp(PC pc);
  static PetscErrorCode FactorApply(PC pc, Vec x, Vec y);
  static PetscErrorCode LinearizedMult(Mat A, Vec x, Vec y); /* y = G_w(lin_W_) x, central differences */

  MPI_Comm                           comm_  = MPI_COMM_NULL;
  PetscMPIInt                        size_  = 1;
  RVEEquations                      *eq_    = nullptr;
  const RVESpec                     *spec_  = nullptr;
  TS                                 ts_    = nullptr;
  Vec                                Wprev_ = nullptr, R_ = nullptr, D_ = nullptr;
  Vec                                Dprev_ = nullptr, dW_ = nullptr; /* AndersonStep's last step and last update */
  Mat                                J_ = nullptr, K_ = nullptr;      /* J = K + shift I; K = G' by colouring */
  MatFDColoring                      coloring_ = nullptr;
  Mat                                factor_   = nullptr;                /* LU of J, for the pseudo steps and the warm solves (the group's first rank's) */
  Vec                                seq_x_ = nullptr, seq_y_ = nullptr; /* ApplyFactor's views of the first rank's entries (groups of several ranks) */
  PetscObjectState                   factor_state_     = -1;             /* J's state when factor_ was computed */
  PetscInt                           pattern_rebuilds_ = -1;
  std::vector<std::vector<PetscInt>> pattern_cols_;                 /* columns of each unknown pair in J_ */
  bool                               have_K_     = false;           /* K_ holds G' of a recent state */
  PetscReal                          res_before_ = 0, res_now_ = 0; /* ||G|| of the cold solve's last two states (PseudoStepRule::SER) */
  PetscInt                           jacobians_ = 0;
  /* DeclareState's view of the pattern and of G' and J's values (this rank's rows, in row order) */
  std::vector<std::vector<PetscInt>> saved_pattern_;
  std::vector<PetscReal>             saved_K_, saved_J_;
  PetscLogEvent                      ev_jacobian_ = 0, ev_linearized_ = 0;
  KSP                                tangent_ksp_ = nullptr;                                 /* SolveLinearized's GMRES, made on first use */
  Mat                                tangent_op_  = nullptr;                                 /* its operator, a shell */
  Vec                                lin_W_ = nullptr, lin_Wp_ = nullptr, lin_Rp_ = nullptr; /* the base state and work vectors */
};

} // namespace turgor
