#pragma once
/* The skeleton every time-dependent mode shares (-mode fine, -mode fe2): a PETSc TS with common
   defaults set through the API before TSSetFromOptions (so the user's -ts_* options win), an
   observable sampled at fixed times (tip.csv), snapshots, progress lines, the solve with its
   converged-reason check, and the common summary keys. A mode supplies its equations, its
   observable and its writers through the hooks below.

   Order: SetFromOptions() creates the TS with the defaults and reads the options; programs may
   then adjust the TS or the specs through the API; SetUp() builds the model, calls
   TSSetFromOptions() and opens the outputs. */
#include <turgor/core/state_blob.h>
#include <turgor/io/output.h>
#include <turgor/io/time_sampler.h>
#include <turgor/modes/simulation.h>
#include <petscts.h>
#include <memory>
#include <string>
#include <vector>

namespace turgor {

/* Outputs of a time-dependent run: -output_dir, and with the mode's prefix -<mode>_tip_samples,
   -<mode>_snapshots, -<mode>_progress_interval. */
struct RunOutputSpec {
  std::string dir               = "./out";
  PetscInt    samples           = 1000;  /* samples of the observable over [0, ts_max_time] */
  PetscInt    snapshots         = 20;    /* field snapshots over [0, ts_max_time]; 0 = none */
  PetscReal   progress_interval = 10;    /* seconds of wall time between progress lines; 0 = none */
  bool        overwrite         = false; /* -output_overwrite: replace an earlier run's outputs */
  bool        ready             = false; /* the directory is this run's, and written (not under -help) */

  PetscErrorCode SetFromOptions(MPI_Comm comm, const std::string &prefix);
};

class TimeRun : public Simulation {
public:
  ~TimeRun() override;
  TimeRun(const TimeRun &)            = delete;
  TimeRun &operator=(const TimeRun &) = delete;

  PetscErrorCode SetFromOptions() final;
  PetscErrorCode SetUp() final;
  PetscErrorCode Solve() final;
  PetscErrorCode WriteSummary() final;
  PetscErrorCode WriteFailure(const std::string &reason) final;
  bool           Interrupted() const final { return interrupted_; }

  TS             GetTS() const { return ts_; }
  Vec            GetState() const { return U_; }
  RunOutputSpec &Output() { return out_; }
  /* The observable (the tip displacement) at the last sample. */
  PetscReal TipDisplacement() const { return observed_; }

protected:
  TimeRun(MPI_Comm comm, const char *mode) : comm_(comm), mode_(mode) { }

  /* The mode's integrator defaults (type, step size, solvers), on a TS that has the common ones. */
  virtual PetscErrorCode SetTSDefaults() = 0;
  /* The mode's own options (its specs). */
  virtual PetscErrorCode ModeSetFromOptions() = 0;
  /* The model and the initial state U_ (created here), the TS callbacks, model-dependent TS
     defaults (a step from the stability limit). */
  virtual PetscErrorCode SetUpModel() = 0;
  /* Choices that depend on the integrator the user picked (after TSSetFromOptions). */
  virtual PetscErrorCode AfterTSSetFromOptions() { return PETSC_SUCCESS; }
  /* The end of SetUp (a restart's state read, the outputs open): what only set-up needed can go. */
  virtual PetscErrorCode AfterSetUp() { return PETSC_SUCCESS; }
  /* The start-up report. */
  virtual PetscErrorCode Report() = 0;
  /* tip.csv: the columns after "time"; the first is the tip displacement. */
  virtual std::vector<std::string> ObservedColumns() const = 0;
  /* Collective; row gets one value per column (all ranks). */
  virtual PetscErrorCode Observe(PetscReal t, Vec U, std::vector<PetscReal> &row) = 0;
  /* Further CSV files in the output directory sampled at the same times as tip.csv (one sampler
     for all): each file's name and columns after "time", and (collective) one row per file. */
  struct Series {
    std::string              file;
    std::vector<std::string> columns;
  };
  virtual std::vector<Series> ObservedSeries() const { return {}; }
  virtual PetscErrorCode      ObserveSeries(PetscReal t, Vec U, std::vector<std::vector<PetscReal>> &rows) { return PETSC_SUCCESS; }
  virtual PetscErrorCode      OpenSnapshots() = 0;
  /* The mode's own further output files (after tip.csv; only when the directory is ready). */
  virtual PetscErrorCode OpenOutputs() { return PETSC_SUCCESS; }
  virtual PetscErrorCode WriteSnapshot(PetscReal t, Vec U) = 0;
  virtual PetscInt       SnapshotCount() const             = 0;
  virtual const char    *SnapshotFiles() const             = 0; /* for the final report */
  /* The right-hand-side / residual evaluations so far (this rank). */
  virtual PetscInt FunctionEvaluations() const = 0;
  /* After every accepted step, at the accepted state (internal state committed, RVE states kept). */
  virtual PetscErrorCode AfterStep(PetscReal t, Vec U) { return PETSC_SUCCESS; }
  /* After a successful TSSolve (e.g. the particle record brought up to date). */
  virtual PetscErrorCode AfterSolve() { return PETSC_SUCCESS; }
  /* The mode's summary keys (collective), and the details of the final report line. */
  virtual PetscErrorCode AddSummary(JsonObject &js)        = 0;
  virtual PetscErrorCode DoneDetails(std::string *details) = 0; /* collective */
  /* What a user should try when the integration fails. */
  virtual const char *FailureAdvice() const = 0;
  /* Refuse integrators the mode cannot use (after TSSetFromOptions; the message says why). */
  virtual PetscErrorCode CheckIntegrator() { return PETSC_SUCCESS; }

  /* Checkpoints (-checkpoint_interval, -checkpoint_wall_interval, -restart). TimeRun writes the
     state Vec, time, step, next step size, the integrator's carried derivative and step-size
     controller history (ts_checkpoint.h) and the outputs' sampling position; a mode that supports them returns true and adds its own
     state and the fingerprint of its scene (name, value: a restart on another scene is refused,
     naming the part that differs). */
  virtual bool           Checkpointable() const { return false; }
  virtual PetscErrorCode CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp) { return PETSC_SUCCESS; }
  virtual PetscErrorCode SaveState(PetscReal t, Vec U, StateBlob &state) { return PETSC_SUCCESS; }
  /* At the restored state U of time t (after TSSetUp, before the outputs are opened). */
  virtual PetscErrorCode LoadState(PetscReal t, Vec U, StateBlob &state) { return PETSC_SUCCESS; }
  /* Restarts on another number of ranks: StateOrder gives each local entry of the state its index
     in an order that does not depend on the ranks (NULL: the state's own order), in which the state
     (and a carried derivative of the state's layout) is written; RestartsOnOtherRanks says whether
     this run can continue from a checkpoint of another rank count (else why not), and
     LoadStateOtherRanks then replaces LoadState: the per-rank run_state is not read, but every
     writing rank's SaveGlobalState blob (global_state: the mode's state in a numbering that does
     not depend on the ranks), handed to every rank in rank order. */
  virtual PetscErrorCode StateOrder(IS *order)
  {
    *order = NULL;
    return PETSC_SUCCESS;
  }
  virtual bool RestartsOnOtherRanks(std::string *why) const
  {
    *why = "this mode's checkpoint holds per-rank state";
    return false;
  }
  virtual PetscErrorCode SaveGlobalState(PetscReal t, Vec U, StateBlob &state) { return PETSC_SUCCESS; }
  virtual PetscErrorCode LoadStateOtherRanks(PetscReal t, Vec U, std::vector<StateBlob> &states) { return PETSC_SUCCESS; }
  /* -checkpoint_interval, -checkpoint_wall_interval or -restart was given (after SetFromOptions). */
  bool CheckpointsRequested() const { return ckpt_interval_ > 0 || ckpt_wall_ > 0 || !restart_file_.empty(); }
  /* The checkpoint a run continues from ("" when none), and its step. */
  const std::string &RestartFile() const { return restart_file_; }
  PetscInt           RestartStep() const { return restart_step_; }

  /* Seconds of wall time in TSSolve. */
  PetscReal WallTime() const { return (PetscReal)wall_; }

  MPI_Comm      comm_;
  TS            ts_ = nullptr;
  Vec           U_  = nullptr;
  RunOutputSpec out_;
  PetscReal     t_final_ = 0;

private:
  static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx);
  static PetscErrorCode PostStep(TS ts);
  PetscErrorCode        Sample(PetscReal t, Vec U);
  PetscErrorCode        CheckTSOptions(); /* step, final time, tolerances: finite, positive, error control on */
  PetscErrorCode        CommonSummary(JsonObject &js, const char *status);
  static PetscErrorCode PreStep(TS ts);
  PetscErrorCode        WriteCheckpoint(PetscReal t, PetscInt step);
  PetscErrorCode        ReadCheckpoint(); /* -restart: every check, then the state restored */
  PetscErrorCode        ReadCheckpointFile(PetscViewer v, std::string *problem);
  PetscErrorCode        CheckpointDue(PetscReal t, PetscBool *due);

  std::string                             mode_;
  CsvWriter                               tip_csv_;
  std::vector<std::unique_ptr<CsvWriter>> series_csv_;
  std::vector<std::string>                series_files_;
  TimeSampler                             sampler_;
  PetscLogDouble                          wall_        = 0;
  PetscReal                               observed_    = 0;
  PetscLogStage                           stage_setup_ = 0, stage_solve_ = 0;
  PetscLogEvent                           ev_output_   = 0;
  bool                                    interrupted_ = false, solving_ = false;
  PetscReal                               t_last_ = 0, stalled_ = -1, dt_min_ = 0; /* stalled_: the accepted step below dt_min_ (>= 0) */
  static constexpr PetscReal              kMinStepFraction = 1e-10;                /* default -ts_adapt_dt_min / -ts_max_time */

  /* checkpoints */
  PetscReal             ckpt_interval_ = 0, ckpt_wall_ = 0, ckpt_next_ = 0; /* -checkpoint_interval [µs], -checkpoint_wall_interval [s]; the next due time */
  PetscLogDouble        ckpt_wall_last_ = 0;
  PetscInt              ckpt_last_step_ = -1, ckpt_count_ = 0, restart_step_ = -1;
  PetscReal             ckpt_bytes_ = 0, ckpt_seconds_ = 0;
  std::string           restart_file_;
  std::vector<PetscInt> restart_series_rows_;
  PetscInt              restart_tip_rows_ = 0;
  PetscLogEvent         ev_ckpt_write_ = 0, ev_ckpt_read_ = 0;
};

} // namespace turgor
