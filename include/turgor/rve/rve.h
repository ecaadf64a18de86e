#pragma once
/* Representative volume element (TW 562 §3.2): one period of the tissue, k x k cells, deformed by
   the coarse F and Fdot. Particles sit at x = F X + u1 and move with v = Fdot X (the seed's v1 = 0);
   the corner particle (the four RVE corners are one particle under periodicity) is held at F X;
   every interaction sees the deformed periodic lattice a_i = F A_i (minimum image through
   Spring::image and the neighbour search's images).

   Relaxation solves G(u1) = 0 (eq 27), the forces on the free particles, by pseudo-transient
   continuation (eq 28) with PETSc TSPSEUDO: one linear solve per pseudo-step with the Jacobian of G
   by MatFDColoring on the interaction graph; the seed's schedule delta_0 = 1e-2, delta <- 10 delta,
   stop at ||step|| < 1e-12 or ||G|| < 1e-12, in units scaled by the cell size and k_w x cell size.
   Stress by the virial (eq 30) over all pairs, including periodic images; rho = mass / area. */
#include <turgor/physics/force_model.h>
#include <turgor/material/material_point.h>
#include <turgor/tissue/square_grid.h>
#include <petscts.h>

namespace turgor {

struct RVECounters {
  PetscInt solves = 0, failures = 0, iterations = 0, snes_its = 0, ksp_its = 0, jacobians = 0, force_evals = 0;
  PetscInt tangent_solves = 0; /* perturbed solves (eqs 46-53), included in solves */
};

class RVE : public MaterialPoint {
public:
  explicit RVE(MPI_Comm comm) : comm_(comm) { }
  ~RVE() override;
  RVE(const RVE &)            = delete;
  RVE &operator=(const RVE &) = delete;

  const char    *Name() const override { return "rve"; }
  /* -rve_* options, the tissue geometry (-tissue_*, cells per side from -rve_cells) and the
     physics (-physics without body_force, -wall_*, -repulsion_*, -sph_*). */
  PetscErrorCode SetFromOptions();
  PetscErrorCode SetUp();
  PetscErrorCode Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out) override;
  PetscErrorCode Commit() override;
  PetscErrorCode Revert() override;
  PetscReal      StressUncertainty() const override { return atol_; }

  const RVECounters &Counters() const { return counters_; }
  const Tissue      &GetTissue() const { return tissue_; }
  PetscInt           NumUnknowns() const { return 2 * (PetscInt)free_.size(); }
  PetscReal          Area() const { return tissue_.period[0] * tissue_.period[1]; }
  /* relaxed: solve eq 27; cauchy_born: u1 = 0 (the seed's Taylor-Voigt / Cauchy-Born
     approximation); frozen: u1 held at the last committed state (Cauchy-Born about a relaxed
     reference, e.g. the turgid state at F = I). */
  enum class Relaxation { Relaxed, CauchyBorn, Frozen };
  Relaxation         Mode() const { return relax_; }
  void               SetMode(Relaxation m) { relax_ = m; }
  /* The particle positions of the last evaluation (all particles, x = F X + u1), for output. */
  const std::vector<PetscReal> &Positions() const { return x_; }

private:
  static PetscErrorCode IFunction(TS ts, PetscReal t, Vec W, Vec Wdot, Vec F, void *ctx);
  static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec W, Vec Wdot, PetscReal shift, Mat A, Mat B, void *ctx);
  static PetscErrorCode ColoringResidual(void *unused, Vec W, Vec R, void *ctx);
  static PetscErrorCode PseudoStep(TS ts, PetscReal *dt, void *ctx);
  static PetscErrorCode PreStep(TS ts);
  static PetscErrorCode PostStep(TS ts);

  PetscErrorCode SetDeformation(const Tensor2 &F, const Tensor2 &Fdot);
  PetscErrorCode Residual(const PetscScalar *w, PetscScalar *r, PetscReal *virial);
  PetscErrorCode ResidualNorm(Vec W, PetscReal *norm);
  PetscErrorCode BuildJacobianPattern();
  PetscErrorCode PatternStale(PetscBool *stale);
  PetscErrorCode PatternColumns(std::vector<std::vector<PetscInt>> &cols) const;
  PetscErrorCode Relax(MaterialResponse *out);
  PetscErrorCode WarmRelax(MaterialResponse *out, bool *converged);
  PetscErrorCode FluidInsideCells(bool *inside);

  MPI_Comm               comm_;
  PetscMPIInt            rank_ = 0;
  SquareGridSpec         spec_;
  Tissue                 tissue_;
  PhysicsSpec            physics_;
  ForceModel             model_;
  std::vector<PetscInt>  free_;      /* free particle of each unknown pair */
  std::vector<PetscReal> x_, v_, f_; /* all particles */
  Tensor2                F_, Fdot_;
  PetscReal              length_scale_ = 25, force_scale_ = 1e5;

  TS            ts_ = nullptr;
  Vec           W_ = nullptr, Wprev_ = nullptr, R_ = nullptr;
  std::vector<PetscScalar> cache_w_, cache_r_; /* the last residual evaluation */
  PetscReal                cache_virial_[4] = {0, 0, 0, 0};
  bool                     cache_valid_     = false;
  Mat           J_ = nullptr, K_ = nullptr; /* J = K + shift I; K = G' by colouring */
  MatFDColoring coloring_ = nullptr;
  PetscInt      pattern_rebuilds_ = -1;
  std::vector<std::vector<PetscInt>> pattern_cols_; /* columns of each unknown pair in J_ */
  bool          have_K_ = false; /* K_ holds G' of a recent state (warm solves reuse it) */
  Vec           D_ = nullptr;
  std::vector<PetscScalar> current_, committed_; /* u1 / L of the current and last accepted state */
  bool                     have_current_ = false, have_committed_ = false;

  /* options */
  PetscInt  cells_ = 1, max_it_ = 50;
  Relaxation relax_ = Relaxation::Relaxed;
  PetscReal dt0_ = 1e-2, increment_ = 10, atol_ = 1e-12, steptol_ = 1e-12, warm_dt0_ = 1e4, dt_max_ = 1e12;

  RVECounters   counters_;
  PetscLogEvent ev_solve_ = 0, ev_jacobian_ = 0;
};

} // namespace turgor
