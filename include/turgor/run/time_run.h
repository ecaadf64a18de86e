#pragma once
/* The skeleton every time-dependent mode shares (-mode fine, -mode fe2): a PETSc TS with common
   defaults set through the API before TSSetFromOptions (so the user's -ts_* options win), an
   observable sampled at fixed times (tip.csv), snapshots, progress lines, the solve with its
   converged-reason check, and the common summary keys. A mode supplies its equations, its
   observable and its writers through the hooks below.

   Order: SetFromOptions() creates the TS with the defaults and reads the options; programs may
   then adjust the TS or the specs through the API; SetUp() builds the model, calls
   TSSetFromOptions() and opens the outputs. */
#include <cstdint>
#include <turgor/core/parameters.h>
#include <turgor/io/declared_state.h>
#include <turgor/io/output.h>
#include <turgor/io/time_sampler.h>
#include <turgor/modes/simulation.h>
#include <turgor/ts/integrator_state.h>
#include <petscts.h>
#include <deque>
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
  PetscErrorCode WriteFailure(const std::string &reason, const char status[]) final;
  bool           Interrupted() const final { return interrupted_; }
  bool           Checkpoints() const final { return Checkpointable(); }

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
  /* Before the summary: the mode's own files that OpenSeries did not open, closed, a write that
     failed an error naming the file (collective). */
  virtual PetscErrorCode CloseOutputs() { return PETSC_SUCCESS; }
  virtual PetscErrorCode WriteSnapshot(PetscReal t, Vec U) = 0;
  virtual PetscInt       SnapshotCount() const             = 0;
  virtual const char    *SnapshotFiles() const             = 0; /* for the final report */
  /* The right-hand-side / residual evaluations so far (this rank). */
  virtual PetscInt FunctionEvaluations() const = 0;
  /* After every accepted step, at the accepted state (internal state committed, RVE states kept). */
  virtual PetscErrorCode AfterStep(PetscReal t, Vec U) { return PETSC_SUCCESS; }
  /* From AfterStep: the run ends after this step, before its end time, for a reason of its own (FE²
     at localisation): summary.json's status is `status` and its reason `reason`; collective. */
  PetscErrorCode StopAfterThisStep(const std::string &status, const std::string &reason);
  /* After a successful TSSolve (e.g. the particle record brought up to date). */
  virtual PetscErrorCode AfterSolve() { return PETSC_SUCCESS; }
  /* The integrator cannot pass the state at t: its steps were rejected repeatedly, or (crawled) the
     step it accepted last fell below -ts_adapt_dt_min. A mode may end the run there with a status of
     its own (*status, *reason) instead of failing; an empty status (the default) fails the run.
     Collective. */
  virtual PetscErrorCode EndWhereStuck(PetscReal t, bool crawled, std::string *status, std::string *reason) { return PETSC_SUCCESS; }
  /* Keys a failed run's summary still carries (WriteFailure): values this rank holds, no collective
     (rank 0 alone calls it, after the failure). */
  virtual void AddFailureSummary(JsonObject &js) const { }
  /* The mode's summary keys (collective), and the details of the final report line. */
  virtual PetscErrorCode AddSummary(JsonObject &js)        = 0;
  virtual PetscErrorCode DoneDetails(std::string *details) = 0; /* collective */
  /* What a user should try when the integration fails. */
  virtual const char *FailureAdvice() const = 0;
  /* Refuse integrators the mode cannot use (after TSSetFromOptions; the message says why). */
  virtual PetscErrorCode CheckIntegrator() { return PETSC_SUCCESS; }

  /* Checkpoints (-checkpoint_interval, -checkpoint_wall_interval, -restart), written and read from
     declared state (io/declared_state.h, io/checkpoint_file.h). TimeRun declares the time, step,
     next step size and the samplers' positions ("run"), the solution as entries of the state in
     StateOrder's numbering ("solution") and the integrator's history ("integrator"); a mode that
     supports checkpoints returns true, declares its own state (DeclareState), numbers the entities
     its tables name (EntityId, EntityLocal, EntityOwned; LayoutHash: which entities this rank holds,
     in which order), and gives the fingerprint of its scene (name, value: a restart on another
     scene is refused, naming the part that differs). */
  virtual bool Checkpointable() const { return false; }
  /* The mode declares the solution's values itself (through SolutionView: U's local values, filled
     before a checkpoint is written, copied into U after one is read), not as "solution" entries. */
  virtual bool DeclaresSolution() const { return false; }
  /* ... and may keep a vector in its state's layout (the integrator's history: `values`, of
     `global_size` entries in all) with its own entities' state (true), declared in DeclareState. */
  virtual bool KeepStateVector(std::vector<PetscReal> &values, PetscInt global_size) { return false; }
  /* U's local values while a checkpoint is written (U's own array, read only) or read (a buffer,
     copied into U once the record is checked) */
  struct SolutionSpan {
    PetscReal *data = nullptr;
    size_t     size = 0;
  };
  SolutionSpan           SolutionView() const { return solution_view_; }
  virtual PetscErrorCode CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp) { return PETSC_SUCCESS; }
  virtual PetscErrorCode DeclareState(std::deque<StateDeclaration> &decls) { return PETSC_SUCCESS; }
  virtual std::uint64_t  EntityId(StateEntity e, PetscInt local) const { return (std::uint64_t)local; }
  virtual PetscInt       EntityLocal(StateEntity e, std::uint64_t id) const { return -1; }
  virtual bool           EntityOwned(StateEntity e, PetscInt local) const { return true; }
  virtual std::uint64_t  LayoutHash() const;
  /* A restart: before the checkpoint's state is read into the declarations (references the model
     takes lazily), and after (what the mode derives from its state), at the restored state U of
     time t; `own_layout`: this rank holds what the rank that wrote its rows held. */
  virtual PetscErrorCode BeforeStateRead() { return PETSC_SUCCESS; }
  virtual PetscErrorCode AfterStateRead(PetscReal t, Vec U, bool own_layout) { return PETSC_SUCCESS; }
  /* StateOrder gives each local entry of the state its index in an order that does not depend on
     the ranks (NULL: the state's own order): the ids of the "solution" entries (and of the
     integrator's history), and the order final_state_hash hashes in. RestartsOnOtherRanks says
     whether this run can continue from a checkpoint of another layout (else why not). */
  virtual PetscErrorCode StateOrder(IS *order)
  {
    *order = NULL;
    return PETSC_SUCCESS;
  }
  /* Adds this rank's share of final_state_hash for the state U to *h: ChecksumTerm of each local
     entry at its StateOrder place. The default makes StateOrder's IS; a mode whose order is a
     formula may compute it entry by entry instead (no IS at the run's end, its memory peak). */
  virtual PetscErrorCode StateChecksum(Vec U, std::uint64_t *h);
  virtual bool           RestartsOnOtherRanks(std::string *why) const
  {
    *why = "this mode's checkpoint holds per-rank state";
    return false;
  }
  /* The mode's right-hand side asks first (a restarted run's first derivative, the FSAL stage):
     *answered: F holds the derivative, the evaluation is not done. */
  PetscErrorCode ObserveRHS(PetscReal t, Vec U, Vec F, PetscBool *answered) { return integrator_.ObserveRHS(ts_, t, U, F, answered); }
  /* A CSV time series of the mode (groups.csv, energy.csv, breaks.csv; rank 0): opened here so that
     checkpoints hold what it has written and a restart writes the checkpoint's rows again and goes
     on after them. */
  PetscErrorCode OpenSeries(CsvWriter &csv, const std::string &file, const std::vector<std::string> &columns);
  /* -checkpoint_interval, -checkpoint_wall_interval or -restart was given (after SetFromOptions). */
  bool CheckpointsRequested() const { return ckpt_interval_ > 0 || ckpt_wall_ > 0 || !restart_file_.empty(); }
  /* The checkpoint a run continues from ("" when none), and its step. */
  const std::string &RestartFile() const { return restart_file_; }
  PetscInt           RestartStep() const { return restart_step_; }

  /* The run's physics parameters: the mode's objects record every option they read that changes the
     physics (core/parameters.h); TimeRun adds the integrator's. A checkpoint keeps them, a restart
     refuses any that differs unless -restart_allow names it. */
  ParameterList &PhysicsParameters() { return params_; }

  /* A fixed step, which TS does not clip at the final time: shortened so that whole steps from (t,
     step) end there, and the steps counted to the end (round-off must not add one) unless
     -ts_max_steps was given. A restart whose step or end time differs from the checkpoint's run
     fits them again from its own start. */
  PetscErrorCode FitFixedSteps(PetscReal t, PetscInt step);

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
  PetscErrorCode        Summarize(JsonObject &js);                         /* the summary of a run that ended (collective) */
  PetscErrorCode        InterruptWhileWriting(const std::string &pending); /* SIGINT/SIGTERM during a checkpoint: summary.json says so at once */
  enum class SeriesStep {
    Check,
    Flush,
    Close
  };
  PetscErrorCode CheckOutputs(SeriesStep step); /* the time series (rank 0's) written so far, or flushed, or closed (collective) */
  PetscErrorCode WriteCheckpoint(PetscReal t, PetscInt step);
  PetscErrorCode ReadCheckpoint(); /* -restart: every check, then the state restored */
  PetscErrorCode ReadCheckpointFile(class CheckpointReader &file, std::string *problem);
  PetscErrorCode CheckpointDue(PetscReal t, PetscBool *due);
  class Numbering;
  PetscErrorCode DeclareAll(std::deque<StateDeclaration> &decls); /* TimeRun's and the mode's */

  std::string                             mode_;
  CsvWriter                               tip_csv_;
  std::vector<std::unique_ptr<CsvWriter>> series_csv_;
  TimeSampler                             sampler_;
  PetscLogDouble                          wall_           = 0;
  PetscReal                               peak_rss_setup_ = 0; /* this rank's peak resident set at the end of the set-up [bytes] */
  PetscReal                               observed_       = 0;
  PetscLogStage                           stage_setup_ = 0, stage_solve_ = 0;
  PetscLogEvent                           ev_output_   = 0;
  bool                                    interrupted_ = false, solving_ = false, stopped_ = false; /* stopped_: at -ts_max_steps, before the end */
  std::string                             stop_status_, stop_reason_;                               /* StopAfterThisStep's */
  PetscReal                               t_last_ = 0, stalled_ = -1, dt_min_ = 0;                  /* stalled_: the accepted step below dt_min_ (>= 0) */
  static constexpr PetscReal              kMinStepFraction = 1e-10;                                 /* default -ts_adapt_dt_min / -ts_max_time */

  /* checkpoints */
  PetscReal               ckpt_interval_ = 0, ckpt_wall_ = 0, ckpt_next_ = 0; /* -checkpoint_interval [µs], -checkpoint_wall_interval [s]; the next due time */
  PetscLogDouble          ckpt_wall_last_ = 0;
  PetscInt                ckpt_last_step_ = -1, ckpt_count_ = 0, restart_step_ = -1;
  PetscInt                ckpt_keep_         = 2;       /* -checkpoint_keep: the numbered checkpoints kept (0: all) */
  PetscInt                restart_read_rows_ = 1 << 16; /* -restart_read_rows: a table's rows a restart reads at once */
  std::deque<std::string> ckpt_kept_;                   /* this run's numbered checkpoints, oldest first (rank 0) */
  bool                    ckpt_every_step_warned_ = false;
  std::string             ckpt_last_file_;         /* the last complete checkpoint (this run's, or the one it continues) */
  std::string             writing_;                /* the snapshot or checkpoint being written: a failure's summary names it */
  bool                    interrupt_said_ = false; /* summary.json says "interrupted" already (InterruptWhileWriting) */
  PetscReal               ckpt_bytes_ = 0, ckpt_seconds_ = 0;
  std::string             restart_file_;
  PetscLogEvent           ev_ckpt_write_ = 0, ev_ckpt_read_ = 0;
  IntegratorState         integrator_;
  ParameterList           params_;
  std::vector<std::string> restart_allow_, restart_changed_;            /* -restart_allow; the allowed differences found */
  PetscReal                dt_start_  = 0;                              /* the first (or fixed) step, from the options */
  bool                     fit_fixed_ = false, auto_max_steps_ = false; /* FitFixedSteps was used; it set the steps */
  struct RunRecord {                                                    /* the "run" declaration: where the run is */
    PetscReal time = 0, dt = 0, t_final = 0, first_step = 0;            /* first_step: the run's first (or fixed) step, from its options */
    PetscInt  step = 0, sample = 0, snapshot = 0, samples = 0, snapshots = 0;
  } record_;
  std::vector<PetscReal>                           solution_;      /* a checkpoint's values of U, read before they are checked */
  SolutionSpan                                     solution_view_; /* the declarations' view of U (SolutionView) */
  std::vector<std::pair<std::string, CsvWriter *>> series_;        /* every CSV time series (rank 0), in the order opened */
  std::vector<std::pair<std::string, std::string>> restart_text_;  /* a restart: each series' text at the checkpoint */
};

} // namespace turgor
