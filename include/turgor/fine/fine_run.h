#pragma once
/* Full fine-scale simulation (-mode fine): the whole tissue as particles kept in a DMSwarm,
   integrated with PETSc TS on the run skeleton (time_run.h). The run is assembled from:
   - the tissue and where its particles live (parallel/tissue_placement.h: one rank, or every
     particle on the rank of its cell with a halo of its neighbours');
   - the equations for TS (fine_equations.h: the state [x | v] of each rank's own particles, the
     right-hand sides, the halo's exchange);
   - the records beside the samples (fine_records.h: energy.csv, breaks.csv);
   - the per-particle fields, declared once (particles/particle_fields.h), which decide what the
     halo carries, what the snapshots show and what the checkpoints keep.
   The DMSwarm is the particle record (kind, cell; DMSwarm_pid is the particle id).

   Integrators (options only): -ts_type rk -ts_rk_type 5dp (default, adaptive, rtol = atol = 1e-3)
   or -ts_type basicsymplectic / verlet (velocity Verlet, fixed step from the stability limits). */
#include <turgor/fine/controls.h>
#include <turgor/fine/fine_equations.h>
#include <turgor/fine/fine_records.h>
#include <turgor/io/particle_snapshots.h>
#include <turgor/parallel/tissue_placement.h>
#include <turgor/particles/local_numbering.h>
#include <turgor/particles/particle_fields.h>
#include <turgor/physics/force_model.h>
#include <turgor/run/time_run.h>
#include <turgor/tissue/tissue_generator.h>
#include <petscdmswarm.h>

namespace turgor {

/* -fine_ options besides the outputs. */
struct FineRunSpec {
  std::vector<std::string> clamp            = {"left"};    /* sides whose wall particles are fixed */
  PetscReal                dt_safety        = 0.5;         /* fixed steps: this fraction of the stability limit */
  PetscReal                dt               = 0;           /* API only (the option is -ts_dt): the initial or fixed step [µs]; 0: dt_safety x the limit */
  PetscBool                energy           = PETSC_FALSE; /* energy.csv (-fine_energy) */
  PetscBool                predict_velocity = PETSC_FALSE; /* -fine_predict_velocity: TS verlet's forces see v_n + h a_n (FineEquations::ConfigureIntegrator) */
  PetscReal                energy_tolerance = 1e-2;        /* -fine_energy_tolerance: a larger relative residual fails the run; 0: no check */
  PetscInt                 partition        = 0;           /* -fine_partition_report N: METIS partition of the cells into N parts, reported only; 0: none */
  PetscBool                distribute  = PETSC_TRUE; /* -fine_distribute: on several ranks, every particle on the rank of its cell (false: all on rank 0) */
  PetscReal                halo_margin = -1;         /* -fine_halo_margin [µm]: the halo's width beyond the interactions' reach; < 0: the reach */
  PetscInt                 partitioner = 0;          /* -fine_partitioner: 0 metis, 1 ranges (TissuePlacement) */
  PetscBool                reproducible_sums = PETSC_FALSE; /* -fine_reproducible_sums: the forces' sums the same bits on any number of ranks */
  PetscBool                setup_in_parts    = PETSC_TRUE;  /* -fine_setup_in_parts: with ranges, each rank builds only its part where the generator can */

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
};

class FineRun : public TimeRun {
public:
  explicit FineRun(MPI_Comm comm) : TimeRun(comm, "fine") { }
  ~FineRun() override;

  /* API configuration, before SetFromOptions (options win) or between it and SetUp. */
  FineRunSpec &Spec() { return spec_; }
  PhysicsSpec &Physics() { return physics_; }
  LoadSpec    &Load() { return load_; }
  TissueSpec  &Tissues() { return tissues_; }
  /* Load controls (-controls): add groups through the API before SetUp. */
  Controls &GetControls() { return controls_; }
  /* Use this tissue instead of generating one from the -tissue_ options (tests, custom scenes);
     call between SetFromOptions() and SetUp(). Clamps from -fine_clamp are still applied. */
  void SetTissue(const Tissue &tissue)
  {
    tissue_      = tissue;
    have_tissue_ = true;
  }

  PetscInt      RHSEvaluations() const { return equations_.RHSEvaluations(); }
  ForceModel   &Model() { return model_; }
  const Tissue &GetTissue() const { return tissue_; }

protected:
  PetscErrorCode           SetTSDefaults() override;
  PetscErrorCode           ModeSetFromOptions() override;
  PetscErrorCode           SetUpModel() override;
  PetscErrorCode           AfterTSSetFromOptions() override;
  PetscErrorCode           CheckIntegrator() override;
  PetscErrorCode           Report() override;
  std::vector<std::string> ObservedColumns() const override { return {"tip_displacement_y", "kinetic_energy"}; }
  PetscErrorCode           Observe(PetscReal t, Vec U, std::vector<PetscReal> &row) override;
  /* Collective: an error naming the first inverted cell (its signed area through zero) at time t. */
  PetscErrorCode      CheckCellsInverted(PetscReal t, const PetscReal *x, PetscInt inverted);
  PetscErrorCode      LimitControlSteps();
  PetscInt            CountCellsInverted(const PetscReal *x) const;
  std::vector<Series> ObservedSeries() const override;
  PetscErrorCode      ObserveSeries(PetscReal t, Vec U, std::vector<std::vector<PetscReal>> &rows) override;
  PetscErrorCode      OpenSnapshots() override;
  PetscErrorCode      OpenOutputs() override;
  PetscErrorCode      WriteSnapshot(PetscReal t, Vec U) override;
  PetscInt            SnapshotCount() const override { return snapshots_writer_.Count(); }
  const char         *SnapshotFiles() const override { return "particles.h5 + particles.xmf"; }
  PetscInt            FunctionEvaluations() const override { return equations_.RHSEvaluations(); }
  PetscErrorCode      AddSummary(JsonObject &js) override;
  PetscErrorCode      DoneDetails(std::string *details) override;
  const char         *FailureAdvice() const override
  {
    return "the step was rejected repeatedly; for fixed steps lower -ts_dt or -fine_dt_safety, for adaptive ones check the scene's parameters";
  }
  /* Checkpoints: the scene's fingerprint (particles, cells, a hash of the reference positions) and
     the declared state: the particle fields declared for the checkpoints (position, velocity, the
     split integrators' drift velocity) as the "particles" table, the force model's, the records'.
     Particles, bars and cells are numbered by the tissue (gid, SpringGid, PolygonGid); StateOrder
     numbers the state [x | v] in the tissue's particle order (the integrator's history,
     final_state_hash). The references the terms take lazily (hinge angles, cell areas, bonds at
     -glue_start_time 0) are taken again from the initial state before the state is read
     (BeforeStateRead), where the uninterrupted run took them. */
  bool           Checkpointable() const override { return true; }
  bool           DeclaresSolution() const override { return true; }
  bool           KeepStateVector(std::vector<PetscReal> &values, PetscInt global_size) override;
  PetscErrorCode CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp) override;
  PetscErrorCode DeclareState(std::deque<StateDeclaration> &decls) override;
  std::uint64_t  EntityId(StateEntity e, PetscInt local) const override;
  PetscInt       EntityLocal(StateEntity e, std::uint64_t id) const override;
  bool           EntityOwned(StateEntity e, PetscInt local) const override;
  std::uint64_t  LayoutHash() const override;
  PetscErrorCode BeforeStateRead() override { return PrimeReferences(); }
  PetscErrorCode AfterStateRead(PetscReal t, Vec U, bool own_layout) override;
  PetscErrorCode StateOrder(IS *order) override;
  PetscErrorCode StateChecksum(Vec U, std::uint64_t *h) override;
  /* the rank-free place of local state entry k ([x | v], each in the tissue's particle order), of N
     particles in all: StateOrder's entries and the checksum's */
  PetscInt StateIndex(PetscInt k, PetscInt N) const
  {
    const PetscInt n2 = 2 * n_local_, part = k / n2, r = k % n2;
    return part * 2 * N + 2 * tissue_.particles.gid[r / 2] + r % 2;
  }
  bool RestartsOnOtherRanks(std::string *why) const override { return true; }
  /* The tissue's reference positions and initial velocities are read only at set-up (the initial
     state, the swarm, the controls' groups, a restart's PrimeReferences): released once the state
     holds them (a restart: after its checkpoint is read), before the set-up's first force
     evaluation: 32 B a particle off the peak memory. */
  PetscErrorCode AfterSetUp() override
  {
    ReleaseReferences();
    return PETSC_SUCCESS;
  }
  void ReleaseReferences()
  {
    std::vector<PetscReal>().swap(tissue_.X);
    std::vector<PetscReal>().swap(tissue_.V);
  }

private:
  PetscErrorCode AfterStep(PetscReal t, Vec U) override; /* the terms' internal state at the accepted state, the records */
  /* The DMSwarm of this rank's owned particles: their ids (and ranks), kinds and cells (snapshots).
     Not their positions and velocities: those live once, in the state Vec U_; nor their masses,
     which the force model holds (ParticleSet). */
  PetscErrorCode CreateSwarm();
  PetscErrorCode PrimeReferences(); /* a restart: the terms' lazily taken references, from the initial state */

  FineRunSpec     spec_;
  LoadSpec        load_;
  PhysicsSpec     physics_;
  TissueSpec      tissues_;
  Tissue          tissue_; /* this rank's particles (owned, then the halo's) */
  bool            have_tissue_ = false;
  ForceModel      model_;
  Controls        controls_;
  TissuePlacement placement_;
  ParticleFields  fields_;
  FineEquations   equations_;
  FineRecords     records_;
  DM              swarm_ = nullptr;
  IS              is_x_ = nullptr, is_v_ = nullptr;
  PetscInt        n_local_ = 0; /* this rank's particles (the state's) */
  /* vectors in the state's layout kept in the checkpoint's particle table (KeepStateVector): values,
     and parts (2: [x | v] as the state, 1: one half, Verlet's dv/dt) */
  std::vector<std::pair<std::vector<PetscReal> *, int>> kept_vectors_;
  PetscInt                                              n_all_ = 0; /* with the halo copies: the model's particles */
  std::vector<TimeStepLimit>                            limits_;
  PetscReal                                             dt_stable_ = 0, dt_initial_ = 0;

  /* observation */
  PetscInt               tip_    = -1; /* local index of the tip particle on its owner, -1 elsewhere */
  PetscReal              tip_y0_ = 0;
  std::vector<PetscReal> cell_area0_; /* this rank's closed cells' reference signed areas (the inversion check) */
  ParticleSnapshotWriter snapshots_writer_;
  std::vector<PetscReal> force_;   /* the snapshots' force field (every local particle) */
  std::vector<PetscReal> rank_of_; /* the snapshots' rank field (a distributed run) */

  /* checkpoints: the fingerprint's hash of the reference positions; the tissue's numbers translated
     while a checkpoint is read (made by the first EntityLocal, released by AfterStateRead) */
  std::string                             reference_hash_;
  mutable std::unique_ptr<LocalNumbering> numbering_;
};

} // namespace turgor
