#pragma once
/* Full fine-scale simulation (-mode fine): the whole tissue as particles kept in a DMSwarm,
   integrated with PETSc TS on the run skeleton (time_run.h). The TS state is one Vec
   [x (2n) | v (2n)] of each rank's own particles; the DMSwarm is the particle record (fields
   position, velocity, mass, kind, cell; DMSwarm_pid is the global id) and is synchronised from the
   state whenever output is written. On several ranks every particle lives on the rank of its cell
   and the model sees a halo of the neighbouring ranks' particles (tissue_distribution.h).

   Integrators (options only): -ts_type rk -ts_rk_type 5dp (default, adaptive, rtol = atol = 1e-3)
   or -ts_type basicsymplectic (PETSc's velocity Verlet, fixed step from the stability limits). */
#include <turgor/fine/controls.h>
#include <turgor/fine/energy_balance.h>
#include <turgor/io/particle_snapshots.h>
#include <turgor/parallel/cell_partition.h>
#include <turgor/parallel/tissue_distribution.h>
#include <turgor/particles/local_numbering.h>
#include <turgor/physics/force_model.h>
#include <turgor/run/time_run.h>
#include <turgor/tissue/tissue_generator.h>
#include <petscdmswarm.h>

namespace turgor {

/* -fine_ options besides the outputs. */
struct FineRunSpec {
  std::vector<std::string> clamp       = {"left"}; /* sides whose wall particles are fixed */
  PetscReal                dt_safety   = 0.5;      /* fixed steps: this fraction of the stability limit */
  PetscReal                dt          = 0;        /* API only (the option is -ts_dt): the initial or fixed step [µs]; 0: dt_safety x the limit */
  bool                     energy      = false;    /* energy.csv (-fine_energy) */
  PetscInt                 partition   = 0;        /* -fine_partition_report N: METIS partition of the cells into N parts, reported only; 0: none */
  bool                     distribute  = true;     /* -fine_distribute: on several ranks, every particle on the rank of its cell (false: all on rank 0) */
  PetscReal                halo_margin = -1;       /* -fine_halo_margin [µm]: the halo's width beyond the interactions' reach; < 0: the reach */

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

  PetscInt      RHSEvaluations() const { return rhs_evals_; }
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
  std::vector<Series>      ObservedSeries() const override;
  PetscErrorCode           ObserveSeries(PetscReal t, Vec U, std::vector<std::vector<PetscReal>> &rows) override;
  PetscErrorCode           OpenSnapshots() override;
  PetscErrorCode           OpenOutputs() override;
  PetscErrorCode           WriteSnapshot(PetscReal t, Vec U) override;
  PetscInt                 SnapshotCount() const override { return snapshots_writer_.Count(); }
  const char              *SnapshotFiles() const override { return "particles.h5 + particles.xmf"; }
  PetscInt                 FunctionEvaluations() const override { return rhs_evals_; }
  PetscErrorCode           AddSummary(JsonObject &js) override;
  PetscErrorCode           DoneDetails(std::string *details) override;
  const char              *FailureAdvice() const override
  {
    return "the step was rejected repeatedly; for fixed steps lower -ts_dt or -fine_dt_safety, for adaptive ones check the scene's parameters";
  }
  /* Checkpoints: the scene's fingerprint (particles, cells, physics, clamps, controls, a hash of
     the reference positions) and the declared state (DeclareState: the drift velocities of the
     split integrators, the force model's, the energy balance's); particles, bars and cells are
     numbered by the tissue (gid, SpringGid, PolygonGid), the state [x | v] in the tissue's particle
     order (StateOrder). The references the terms take lazily (hinge angles, cell areas, bonds at
     -glue_start_time 0) are taken again from the initial state before the state is read
     (BeforeStateRead), where the uninterrupted run took them. */
  bool           Checkpointable() const override { return true; }
  PetscErrorCode CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp) override;
  PetscErrorCode DeclareState(std::deque<StateDeclaration> &decls) override;
  std::uint64_t  EntityId(StateEntity e, PetscInt local) const override;
  PetscInt       EntityLocal(StateEntity e, std::uint64_t id) const override;
  bool           EntityOwned(StateEntity e, PetscInt local) const override;
  std::uint64_t  LayoutHash() const override;
  PetscErrorCode BeforeStateRead() override { return PrimeReferences(); }
  PetscErrorCode AfterStateRead(PetscReal t, Vec U, bool own_layout) override;
  PetscErrorCode StateOrder(IS *order) override;
  bool           RestartsOnOtherRanks(std::string *why) const override { return true; }
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
  static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx);
  static PetscErrorCode RHSPosition(TS ts, PetscReal t, Vec V, Vec Xdot, void *ctx);
  static PetscErrorCode RHSMomentum(TS ts, PetscReal t, Vec X, Vec Vdot, void *ctx);
  static PetscErrorCode CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept);
  PetscErrorCode        AfterStep(PetscReal t, Vec U) override; /* the terms' internal state at the accepted state */

  /* The DMSwarm of this rank's owned particles: their ids (and ranks), kinds and cells (snapshots).
     Not their positions and velocities: those live once, in the state Vec U_ (a copy in the swarm
     was 32 B a particle that nothing read but the snapshots, which now take them from the state);
     nor their masses, which the force model holds (ParticleSet) and nothing read from the swarm. */
  PetscErrorCode CreateSwarm();
  /* The model's view of a state (x, v of this rank's particles): every local particle's x and v,
     the halo's from their owners, with the controlled components imposed at t (work arrays); a
     serial run without controls gets the state's own arrays. Collective in a distributed run. */
  PetscErrorCode LocalState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc);
  /* f[2 n_all] = the forces at the local state (x, v); on the owned particles whole (the halo's
     shares returned by the other ranks). */
  PetscErrorCode TotalForces(const PetscReal *x, const PetscReal *v, PetscReal *f);
  /* a[2 n] of the owned particles at the local state (x, v); a_has_halo_room: a has 2 n_all entries
     (TSVerletSetAccelerationRoom), the halo's forces pass through its tail instead of fw_ */
  PetscErrorCode Accelerations(const PetscReal *x, const PetscReal *v, PetscScalar *a, bool a_has_halo_room = false);
  PetscErrorCode Distribute();      /* -fine_distribute on several ranks: partition, halo, this rank's tissue */
  PetscErrorCode PrimeReferences(); /* a restart: the terms' lazily taken references, from the initial state */
  PetscErrorCode ChooseTimeStep();
  PetscErrorCode PartitionCellsReport(); /* -fine_partition_report: before the tissue leaves the ranks other than 0 */

  FineRunSpec                spec_;
  LoadSpec                   load_;
  PhysicsSpec                physics_;
  TissueSpec                 tissues_;
  Tissue                     tissue_;
  bool                       have_tissue_ = false;
  ForceModel                 model_;
  DM                         swarm_ = nullptr;
  IS                         is_x_ = nullptr, is_v_ = nullptr;
  PetscInt                   n_local_     = 0; /* this rank's particles (the state's) */
  PetscInt                   n_all_       = 0; /* with the halo copies: the model's particles */
  bool                       distributed_ = false;
  TissueDistribution         dist_;
  std::vector<PetscReal>     fw_;              /* forces of the local particles */
  PetscReal                  halo_reach_  = 0; /* the interactions' reach (with the skin) and the margin, µm */
  PetscReal                  halo_margin_ = 0;
  std::vector<PetscReal>     v_stale_;                   /* velocities seen by the last position update (Verlet; room for the halo's: LocalState) */
  bool                       split_             = false; /* a splitting integrator (v_stale_ is used; on every rank, empty or not) */
  bool                       acceleration_room_ = false; /* TSVERLET's accelerations have room for the halo's forces */
  Controls                   controls_;
  std::vector<PetscReal>     xw_, vw_;            /* controls or a distributed run: the local state (halo, constraints imposed) */
  PetscReal                  drift_fraction_ = 0; /* splitting integrators: a position update's share of the step */
  std::vector<TimeStepLimit> limits_;
  PetscReal                  dt_stable_ = 0, dt_initial_ = 0;

  /* energy balance (-fine_energy) and the terms' logs (breaks.csv) */
  EnergyBalance                           energy_;
  CsvWriter                               energy_csv_;
  PetscReal                               energy_next_ = 0, energy_every_ = 0;
  std::vector<std::string>                record_names_;
  std::vector<std::unique_ptr<CsvWriter>> record_csv_;
  PetscErrorCode                          EnergyRow(PetscReal t, const PetscReal *x, const PetscReal *v);

  /* -fine_partition_report (a report): the partition and the part of each owned particle
     (snapshots); on every rank the edge cut (walls), its length (µm), the
     imbalance, the METIS time (s), the smallest and largest part (particles) */
  CellPartition          partition_;
  std::vector<PetscReal> particle_part_;
  PetscReal              partition_stats_[6] = {0, 0, 0, 0, 0, 0};

  /* observation */
  PetscInt               tip_    = -1; /* local index of the tip particle on its owner, -1 elsewhere */
  PetscReal              tip_y0_ = 0;
  ParticleSnapshotWriter snapshots_writer_;
  PetscInt               rhs_evals_ = 0;

  /* checkpoints: the fingerprint's hash of the reference positions; the tissue's numbers translated
     while a checkpoint is read */
  std::string                     reference_hash_;
  std::unique_ptr<LocalNumbering> numbering_;
};

} // namespace turgor
