#pragma once
/* Full fine-scale simulation (-mode fine): the whole tissue as particles kept in a DMSwarm,
   integrated with PETSc TS. The TS state is one Vec [x (2n) | v (2n)] per rank; the DMSwarm is
   the particle record (fields position, velocity, mass, kind, cell; DMSwarm_pid is the global id)
   and is synchronised from the state whenever output is written.

   Integrators (options only): -ts_type rk -ts_rk_type 5dp (default, adaptive, rtol = atol = 1e-3)
   or -ts_type basicsymplectic (PETSc's velocity Verlet, fixed step from the stability limits). */
#include <turgor/physics/force_model.h>
#include <turgor/io/output.h>
#include <turgor/io/particle_snapshots.h>
#include <turgor/tissue/tissue_generator.h>
#include <turgor/io/time_sampler.h>
#include <petscts.h>
#include <petscdmswarm.h>

namespace turgor {

/* Default final time of the bending bar [µs], fine and FE^2 alike (both answer the same question;
   docs/model.md, "final time"). */
inline constexpr PetscReal kBendingBarFinalTime = 300.0;

class FineRun {
public:
  explicit FineRun(MPI_Comm comm) : comm_(comm) { }
  ~FineRun();
  FineRun(const FineRun &)            = delete;
  FineRun &operator=(const FineRun &) = delete;

  PetscErrorCode SetFromOptions();
  /* Use this tissue instead of generating one from the -tissue_ options (tests, custom scenes);
     call between SetFromOptions() and SetUp(). Clamps from -fine_clamp are still applied. */
  void           SetTissue(const Tissue &tissue)
  {
    tissue_      = tissue;
    have_tissue_ = true;
  }
  PetscErrorCode SetUp();
  PetscErrorCode Solve();
  /* summary.json and the final report; call after Solve */
  PetscErrorCode WriteSummary();

  const TissueSpec &Tissues() const { return spec_; }
  TS           GetTS() const { return ts_; }
  /* The integrator state [x (2n) | v (2n)] of this rank's particles. */
  Vec          GetState() const { return U_; }
  PetscInt     RHSEvaluations() const { return rhs_evals_; }
  ForceModel  &Model() { return model_; }
  const Tissue &GetTissue() const { return tissue_; }
  PetscReal    TipDisplacement() const { return tip_final_; }

private:
  static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx);
  static PetscErrorCode RHSPosition(TS ts, PetscReal t, Vec V, Vec Xdot, void *ctx);
  static PetscErrorCode RHSMomentum(TS ts, PetscReal t, Vec X, Vec Vdot, void *ctx);
  static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx);
  static PetscErrorCode CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept);

  PetscErrorCode CreateSwarm();
  PetscErrorCode SyncSwarm(Vec U);
  PetscErrorCode Observe(PetscReal t, Vec U); /* tip sample row */
  PetscErrorCode ChooseTimeStep();

  MPI_Comm   comm_;
  TissueSpec spec_;
  Tissue     tissue_;
  bool       have_tissue_ = false;
  LoadSpec   load_;
  PhysicsSpec physics_;
  ForceModel model_;
  DM         swarm_ = nullptr;
  TS         ts_    = nullptr;
  Vec        U_ = nullptr;
  IS         is_x_ = nullptr, is_v_ = nullptr;
  PetscInt   n_local_ = 0;
  std::vector<PetscReal> v_stale_; /* velocities seen by the last position update (Verlet) */

  /* options */
  std::vector<std::string> clamp_ = {"left"};
  PetscInt                 tip_samples_ = 1000, snapshots_ = 20;
  PetscReal                progress_interval_ = 10.0, dt_safety_ = 0.5, t_final_ = 0;
  std::string              output_dir_;
  std::vector<TimeStepLimit> limits_;
  PetscReal                dt_stable_ = 0;

  /* observation */
  PetscInt               tip_ = -1; /* local index of the tip particle on rank 0 */
  PetscReal              tip_y0_ = 0, tip_final_ = 0;
  CsvWriter              tip_csv_;
  ParticleSnapshotWriter snapshots_writer_;
  TimeSampler            sampler_;
  PetscLogDouble         wall_ = 0;
  PetscInt               rhs_evals_ = 0;
  PetscLogEvent          ev_output_ = 0;
  PetscLogStage          stage_setup_ = 0, stage_solve_ = 0;
};

} // namespace turgor
