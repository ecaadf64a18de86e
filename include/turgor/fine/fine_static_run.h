#pragma once
/* -mode fine_static: a polygonal tissue in static equilibrium, f(x) = 0 on every free node component,
   at the scene's load times (-fine_static_times): the quasi-static limit of the same scene under
   -mode fine. At time t the velocity controls hold their components at X + v S(t), the force controls
   push F s(t), the clamped sides stay at X, the body force and the turgor (its ramp at t) act, and
   the velocities are zero (dashpots and viscosity exert nothing). Pseudo-transient continuation
   growing into Newton (or PETSc SNES, prefix fine_static_) on the scaled forces, the Jacobian by
   finite differences coloured on the interaction graph (particles/polygon_couplings.h: a cell's
   nodes, and each node with the bars within reach), and a direct solve (MUMPS where PETSc has it).
   Between two load times the controls move in -fine_static_substeps increments, each halved on a
   failed solve (-fine_static_max_cutbacks), the free nodes first moved by their linear response to
   the held ones' move; a converged increment commits the terms' history (plastic hinges, friction
   springs, glue damage and breaks), so a path is followed, not jumped.

   Where dynamic relaxation needs ω_max / ω_1 steps (10^5 to 10^6 for a bending tissue: the walls'
   axial vibration against the organ's bending), this needs tens of factorisations per increment.
   All particles are on rank 0 (an empty rank is a valid rank: the others join the collective
   solves with no rows). Outputs: groups.csv (the controls' displacements and reactions at every
   load time), static.csv (per load time: the tip's vertical displacement -- the node in the middle
   of the right side, as -mode fine's tip.csv --, increments, iterations, residual), particles.h5/xmf
   (every load time: the equilibrium, the force on every node -- the reactions where it is
   constrained), summary.json. */
#include <turgor/fine/controls.h>
#include <turgor/io/output.h>
#include <turgor/io/particle_snapshots.h>
#include <turgor/modes/single_shot_run.h>
#include <turgor/physics/force_model.h>
#include <turgor/tissue/tissue_generator.h>
#include <petscsnes.h>

namespace turgor {

enum class FineStaticSolver {
  PSITC,
  NEWTON
};

/* Options -fine_static_times, -fine_static_substeps, -fine_static_max_cutbacks,
   -fine_static_snapshots, -fine_static_max_step, -fine_static_solver, -fine_static_psi_max_steps, -fine_static_monitor, and the scene's -fine_clamp (as -mode fine reads it). */
struct FineStaticSpec {
  std::vector<PetscReal>   times         = {0};      /* [µs], increasing: the scene's times whose equilibria are found */
  PetscInt                 substeps      = 1;        /* increments from one load time to the next */
  PetscInt                 max_cutbacks  = 8;        /* halvings of a failed increment */
  std::vector<std::string> clamp         = {"left"}; /* -fine_clamp: sides whose wall particles are fixed */
  PetscBool                snapshots     = PETSC_TRUE;
  PetscReal                max_step      = 0; /* [µm]: the largest node move of a Newton step; 0: a tenth of the mean bar */
  FineStaticSolver         solver        = FineStaticSolver::PSITC;
  PetscInt                 psi_max_steps = 200;
  PetscBool                monitor       = PETSC_FALSE;

  PetscErrorCode SetFromOptions(MPI_Comm comm);
};

class FineStaticRun : public SingleShotRun {
public:
  explicit FineStaticRun(MPI_Comm comm) : SingleShotRun(comm, "fine_static") { }
  ~FineStaticRun() override;

  PetscErrorCode SetFromOptions() override;
  PetscErrorCode SetUp() override;
  PetscErrorCode Solve() override;
  PetscErrorCode WriteSummary() override;
  bool           Interrupted() const override { return interrupted_; }

protected:
  PetscErrorCode AddSummary(JsonObject &js) override;
  PetscErrorCode AddFailure(const std::string &reason, JsonObject &js) override;

private:
  static PetscErrorCode Residual(SNES snes, Vec W, Vec R, void *ctx);
  static PetscErrorCode ColoringResidual(void *snes, Vec W, Vec R, void *ctx);
  static PetscErrorCode CapStep(SNESLineSearch ls, Vec W, Vec Y, PetscBool *changed, void *ctx);
  /* x_ from the unknowns W (rank 0's: the free components' displacements) and the constraints at time t_ */
  PetscErrorCode Place(Vec W);
  /* f_ = the forces of the terms and the force controls at x_ (rank 0); false: a cell is inverted */
  PetscErrorCode Forces(bool *ok);
  PetscInt       FirstInvertedCell() const; /* rank 0: the first closed cell of x_ with no positive area, -1 if none */
  PetscErrorCode BuildJacobian();           /* the pattern at x_, the colouring, the matrix (collective) */
  PetscErrorCode Predict();                 /* W_ moved by the linear response to the held nodes' move since the last equilibrium */
  PetscErrorCode PseudoTransient(PetscReal tol, bool *converged, PetscInt *steps); /* from W_ to |R| <= tol */
  /* the nonlinear solve at time t from the last converged state; *converged, *why */
  PetscErrorCode SolveAt(PetscReal t, bool *converged, std::string *why);
  PetscErrorCode Record(PetscReal t, PetscInt increments, PetscInt cutbacks, PetscInt iterations); /* the outputs of a converged load time */

  FineStaticSpec spec_;
  LoadSpec       load_;
  PhysicsSpec    physics_;
  TissueSpec     tissues_;
  Tissue         tissue_;
  Controls       controls_;
  ForceModel     model_;
  PetscMPIInt    rank_   = 0;
  PetscInt       tip_    = -1; /* rank 0: the wall particle in the middle of the right side */
  PetscReal      tip_uy_ = 0;  /* its vertical displacement at the last equilibrium */

  std::vector<PetscInt>  dof_;            /* rank 0: the state index 2 i + d of each unknown */
  std::vector<PetscReal> X_, x_, v0_, f_; /* reference, current positions, zero velocities, forces */
  std::vector<PetscReal> push_;           /* Forces' work: the control forces (only the force groups' are used) */
  std::vector<PetscReal> held_before_;    /* Predict: every position with the held components where the last equilibrium had them */
  std::vector<PetscReal> w_conv_;         /* rank 0: the unknowns (displacements of the free components) of the last converged increment */
  PetscReal              held_blend_ = 1; /* Place: the held components this fraction of the way from t_conv_'s positions to t_'s */
  PetscReal              t_ = 0, t_conv_ = 0, force_scale_ = 1, coordinate_scale_ = 1, cell_size_ = 1; /* rank 0's */
  SNES                   snes_     = nullptr;
  Mat                    J_        = nullptr;
  MatFDColoring          coloring_ = nullptr;
  Vec                    W_        = nullptr;
  DM                     swarm_    = nullptr;

  CsvWriter              groups_csv_, static_csv_;
  ParticleSnapshotWriter snapshots_;
  std::vector<PetscReal> last_groups_;
  PetscInt               capped_steps_ = 0, increments_ = 0, cutbacks_ = 0, iterations_ = 0, failed_solves_ = 0, jacobians_ = 0, evaluations_ = 0;
  PetscInt               load_times_done_ = 0;
  PetscReal              wall_ = 0, residual_ = 0;
  std::string            last_failure_;
  bool                   interrupted_ = false, solving_ = false;
};

} // namespace turgor
