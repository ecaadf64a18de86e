#pragma once
/* Representative volume element (TW 562 §3.2) as a material point: the periodic cell deformed by
   the coarse (F, Fdot) (periodic_cell.h), relaxed (relaxation.h) from its current state, and the
   stress by the virial over all pairs, including periodic images (eq 30); rho = mass / area.

   RVEMaterial is the material "rve": the cell geometry (tissue_ options without the layout), the
   physics (-physics without loads) and the relaxation settings (rve_), read once; it creates every
   material point from them. */
#include <turgor/material/material_point.h>
#include <turgor/rve/relaxation.h>
#include <functional>
#include <memory>

namespace turgor {

class RVE;

/* The relaxed state at the reference (F = I, Fdot = 0) of a material's points, shared by them: every
   point starts as a copy of one prototype cell with the same history, and all are first evaluated
   there (the coarse model's reference), so one cold solve is every point's. It is made on a scratch
   point (`make`: a fresh point of the material, without this cache), and every point then takes it
   the same way -- the state set, a warm solve that finds it converged, no kept Jacobian -- so that a
   point's state does not depend on which point of which rank came first (1 and 2 ranks agree bit
   for bit). Kept by the material; on rank 0 of a group the state. */
struct ReferenceRelaxedState {
  bool                                                                             tried = false, have = false;
  std::vector<PetscScalar>                                                         w;
  std::function<PetscErrorCode(MPI_Comm, const RVESpec &, std::unique_ptr<RVE> *)> make;
};

class RVE : public MaterialPoint {
public:
  RVE(MPI_Comm comm, const RVESpec &spec, std::shared_ptr<ReferenceRelaxedState> first = nullptr) : comm_(comm), spec_(spec), first_(std::move(first)) { }
  RVE(const RVE &)            = delete;
  RVE &operator=(const RVE &) = delete;
  ~RVE() override;

  /* A copy of `cell`, the physics' terms (copies too) and the force scale from the fluid density. */
  PetscErrorCode SetUp(const PeriodicCell &cell, const PhysicsSpec &physics, PetscReal fluid_density);
  PetscErrorCode Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out) override;
  PetscErrorCode Commit() override;
  PetscErrorCode Revert() override;
  PetscReal      StressUncertainty() const override { return spec_.psi_atol; }
  /* Implicit differentiation of the relaxed state (TW 562 eq 27, G(w; F, Fdot) = 0):
       d sigma = sigma_p dp + sigma_w dw,   G_w dw = -G_p dp,   p = (F, Fdot),
     G_p dp by central differences of the explicit G at fixed w (a step of 1e-6), dw by
     RVERelaxation::SolveLinearized with the relaxation's LU factor, and the total derivative as one
     central difference of the virial stress along (dp, dw). Cauchy-Born and frozen RVEs hold w:
     only sigma_p. No perturbed RVE solve. */
  PetscErrorCode StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                   Tensor2 *dsigma, MaterialResponse *status) override;
  void           AddCounters(MaterialCounters &c) const override;
  /* Declared state: the warm start (current and committed fine state and their flags), the
     relaxation's kept Jacobian and pattern, the equations' neighbour lists and the counters (rank 0
     of the group holds the unknowns; the other ranks their flags and their empty parts). */
  void           DeclareState(StateDeclaration &d) override;
  PetscErrorCode AfterStateRead() override;

  const PeriodicCell &Cell() const { return cell_; }
  PetscInt            NumUnknowns() const { return cell_.NumUnknowns(); }
  RelaxationMode      Mode() const { return spec_.relax; }
  void                SetMode(RelaxationMode m) { spec_.relax = m; }
  /* The relaxed state w = u1 / L of the last trial evaluation (rank 0 of the group). */
  const std::vector<PetscScalar> &CurrentState() const { return current_; }
  /* The first-order prediction of the relaxed state at (F, Fdot) from the state w0 at (F0, Fdot0)
     and the last exact tangent's derivatives (rank 0 of the group): w0 + sum_c alpha_c z_c +
     alpha_r Omega w0, the z_c = dw along the tangent's directions D_c = (dF_c, dFdot_c), Omega w0
     that along a rigid spin (objectivity: spinning F spins w), alpha the least-squares fit of
     (F - F0, Fdot - Fdot0) by the D_c and the spin. false when there is none or the directions do
     not determine alpha. */
  bool Predict(const Tensor2 &F, const Tensor2 &Fdot, const std::vector<PetscScalar> &w0, const Tensor2 &F0, const Tensor2 &Fdot0, PetscScalar *w) const;
  /* The particle positions of the last evaluation (all particles, x = F X + u1), for output. */
  const std::vector<PetscReal> &Positions() const { return eq_.Positions(); }

private:
  /* Is the state of the last evaluation admissible (PeriodicCell::Admissible)? collective; *why on
     every rank. */
  PetscErrorCode Admissible(bool *ok, std::string *why);
  /* The force terms' history (eq_.HasHistory()): made at the reference (glue bonds) in SetUp, kept
     as committed at every Commit, restored by Revert. */
  PetscErrorCode KeepCommittedHistory();
  /* The virial stress [4] at (F, Fdot, W) and, when R, G there (rank 0 of the group; zero elsewhere) */
  PetscErrorCode StressAt(const Tensor2 &F, const Tensor2 &Fdot, Vec W, Vec R, PetscReal sigma[4]);

  MPI_Comm                 comm_;
  PetscMPIInt              rank_ = 0;
  RVESpec                  spec_;
  PeriodicCell             cell_;
  RVEEquations             eq_;
  RVERelaxation            relax_;
  Vec                      W_  = nullptr;
  Vec                      Wd_ = nullptr, Rp_ = nullptr, Rm_ = nullptr, B_ = nullptr, Z_ = nullptr; /* StressDerivatives' work */
  Tensor2                  last_F_, last_Fdot_;                                                     /* the last evaluation, at W_ */
  bool                     last_ok_ = false;
  Tensor2                  trial_F_, trial_Fdot_;         /* current_'s (the last trial evaluation's, whose state Commit accepts) */
  Tensor2                  committed_F_, committed_Fdot_; /* committed_'s */
  std::vector<PetscReal>   committed_history_;            /* the terms' state at the last Commit, packed */
  std::vector<PetscScalar> current_, committed_;          /* u1 / L of the current and last accepted state */
  bool                     have_current_ = false, have_committed_ = false;
  /* the predictor: the last exact tangent's derivatives of the relaxed state z_c (column after
     column) and their directions (8 values each: dF, dFdot) */
  std::vector<PetscScalar>               pred_z_;
  std::vector<PetscReal>                 pred_dirs_;
  MaterialCounters                       counters_;
  PetscLogEvent                          ev_solve_ = 0;
  std::shared_ptr<ReferenceRelaxedState> first_; /* the material's, or none */
};

/* What every periodic-RVE material shares: the relaxation settings and the physics read once, the
   prototype cell every point copies, points made from them. A material derives and builds the cell
   (prototype_) in its SetFromOptions. */
class RVEMaterialBase : public MaterialModel {
public:
  void                     SetDefaultTolerance(PetscReal tol) override { spec.psi_atol = spec.psi_steptol = tol; }
  PetscErrorCode           CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const override;
  std::vector<std::string> Physics() const override { return physics.ActiveTerms(); }
  bool                     HasStressDerivatives() const override { return true; }
  PetscReal                BytesPerPoint() const override { return BytesPerRVE((PetscReal)prototype_.GetTissue().particles.n); }
  /* Measured max RSS per RVE of 1, 2^2 and 4^2 cells (19, 76, 304 particles): its TSPSEUDO, the
     Jacobian pattern, colouring and LU factors grow with the particles (a polygon RVE's images
     included: the equations hold them). */
  static PetscReal    BytesPerRVE(PetscReal particles) { return 250e3 + 19.5e3 * PetscMax(particles - 19, 0); }
  const PeriodicCell &Cell() const { return prototype_; }

  RVESpec     spec;
  PhysicsSpec physics;

protected:
  /* Do its points take their relaxed state at the reference from one solve (ReferenceRelaxedState)?
     Where a cold solve is dear (a polygon RVE's: 10 LU factorisations of G'). The one-cell SPH RVE's
     costs 1 ms, and with the shared state its bending bar restarted on another rank count drifted
     from the uninterrupted run by 5e-10 instead of 8e-13 (the same round-off at the restart,
     amplified along another warm-solve path): it keeps its own. */
  virtual bool ShareReferenceState() const { return false; }
  /* the fluid's density (the force scale of an SPH cell); 0: none */
  virtual PetscReal                      FluidDensity() const { return 0; }
  PeriodicCell                           prototype_;                                         /* the cell every point copies */
  std::shared_ptr<ReferenceRelaxedState> first_ = std::make_shared<ReferenceRelaxedState>(); /* its points' state at the reference */
};

class RVEMaterial : public RVEMaterialBase {
public:
  const char    *Name() const override { return "rve"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) override;
  void           ParticlesPerPoint(PetscInt *wall, PetscInt *fluid) const override;
  PetscErrorCode View(PetscViewer viewer) const override;

  SquareGridSpec cell;

protected:
  PetscReal FluidDensity() const override { return cell.fluid_density; }
};

} // namespace turgor
