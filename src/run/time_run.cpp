#include <turgor/core/errors.h>
#include <turgor/core/log.h>
#include <turgor/core/memory.h>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <turgor/io/checkpoint_file.h>
#include <turgor/run/time_run.h>
#include <petscviewerhdf5.h>

namespace turgor {

PetscErrorCode SimulationRegister(const char name[], SimulationCreator create)
{
  return Registry<Simulation>::Instance().Add(name, create);
}

PetscErrorCode SimulationCreate(MPI_Comm comm, const std::string &mode, std::unique_ptr<Simulation> *sim)
{
  return Registry<Simulation>::Instance().Create(comm, mode, "-mode", "mode", sim);
}

std::string SimulationNames()
{
  return Registry<Simulation>::Instance().Names();
}

/* Default final time [µs]: the seed's bending bar (docs/model.md, "final time"), fine and FE^2 alike. */
static const PetscReal kDefaultFinalTime = 300.0;

PetscErrorCode RunOutputSpec::SetFromOptions(MPI_Comm comm, const std::string &prefix)
{
  PetscFunctionBeginUser;
  PetscCall(OutputDirectory(comm, &dir, &overwrite, &ready));
  PetscOptionsBegin(comm, prefix.c_str(), "Outputs of the run", "turgor");
  PetscCall(PetscOptionsInt("-tip_samples", "Samples of the tip displacement in tip.csv over [0, ts_max_time] (by TS interpolation)", "RunOutputSpec", samples,
                            &samples, NULL));
  PetscCall(PetscOptionsInt("-snapshots", "Field snapshots (HDF5 + XDMF) over [0, ts_max_time]; 0 = none", "RunOutputSpec", snapshots, &snapshots, NULL));
  PetscCall(PetscOptionsReal("-progress_interval", "Seconds of wall time between progress lines; 0 = none", "RunOutputSpec", progress_interval,
                             &progress_interval, NULL));
  PetscOptionsEnd();
  PetscCheck(samples >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -%stip_samples = %" PetscInt_FMT ": must be >= 1", prefix.c_str(), samples);
  PetscCheck(snapshots >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -%ssnapshots = %" PetscInt_FMT ": must be >= 0", prefix.c_str(), snapshots);
  PetscCheck(std::isfinite(progress_interval) && progress_interval >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -%sprogress_interval = %g: must be finite and >= 0", prefix.c_str(), (double)progress_interval);
  PetscFunctionReturn(PETSC_SUCCESS);
}

TimeRun::~TimeRun()
{
  PetscCallVoid(TSDestroy(&ts_));
  PetscCallVoid(VecDestroy(&U_));
}

PetscErrorCode TimeRun::SetFromOptions()
{
  PetscFunctionBeginUser;
  if (!ts_) {
    PetscCall(TSCreate(comm_, &ts_));
    PetscCall(TSSetApplicationContext(ts_, this));
    PetscCall(TSSetProblemType(ts_, TS_NONLINEAR));
    PetscCall(TSSetTolerances(ts_, 1e-3, NULL, 1e-3, NULL));
    PetscCall(TSSetMaxTime(ts_, kDefaultFinalTime));
    PetscCall(TSSetMaxSteps(ts_, PETSC_MAX_INT));
    PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_MATCHSTEP));
    PetscCall(TSSetErrorIfStepFails(ts_, PETSC_FALSE)); /* a failed solve is reported by Solve() */
    PetscCall(SetTSDefaults());
  }
  /* the output directory first: a mode option refused below then leaves a summary.json that says
     so, not the previous run's files (with -output_overwrite) */
  PetscCall(out_.SetFromOptions(comm_, mode_ + "_"));
  {
    char      file[PETSC_MAX_PATH_LEN] = "";
    PetscBool set;
    PetscOptionsBegin(comm_, NULL, "Checkpoint and restart", "turgor");
    PetscCall(PetscOptionsReal("-checkpoint_interval",
                               "Write a checkpoint (checkpoint_<step>.h5, and checkpoint.h5: the latest) in -output_dir every T µs of simulated time, and "
                               "at the end or on an interrupt; 0 = off",
                               "TimeRun", ckpt_interval_, &ckpt_interval_, NULL));
    PetscCall(PetscOptionsReal("-checkpoint_wall_interval", "Write a checkpoint every S seconds of wall time (at the next accepted step); 0 = off", "TimeRun",
                               ckpt_wall_, &ckpt_wall_, NULL));
    PetscCall(PetscOptionsInt("-checkpoint_keep",
                              "Keep only the last K numbered checkpoints this run writes (checkpoint_<step>.h5; checkpoint.h5 is the latest); 0 = keep all",
                              "TimeRun", ckpt_keep_, &ckpt_keep_, NULL));
    PetscCall(PetscOptionsString("-restart",
                                 "Continue from this checkpoint file (-mode fine, or -mode fe2 with its RVE states): the same scene options, integrator and "
                                 "number of ranks; checkpoints need a one-step explicit integrator (-ts_type rk, lsrk, euler, ssp; -mode fine also "
                                 "basicsymplectic, verlet)",
                                 "TimeRun", file, file, sizeof file, &set));
    PetscCall(PetscOptionsInt("-restart_read_rows",
                              "Rows of a checkpoint's table that a restart reads at once (each rank reads only its own entities' rows, in pieces of "
                              "this many: the read's memory beyond the run's)",
                              "TimeRun", restart_read_rows_, &restart_read_rows_, NULL));
    {
      char     *allow[64];
      PetscInt  na = 64;
      PetscBool aset;
      PetscCall(PetscOptionsStringArray("-restart_allow",
                                        "Options whose value may differ from the checkpoint's run (comma-separated, e.g. contact_friction,ts_dt): a restart "
                                        "with changed physics is refused unless the changed options are named here; summary.json records them",
                                        "TimeRun", allow, &na, &aset));
      restart_allow_.clear();
      for (PetscInt k = 0; aset && k < na; k++) {
        restart_allow_.push_back(allow[k][0] == '-' ? allow[k] + 1 : allow[k]);
        PetscCall(PetscFree(allow[k]));
      }
    }
    PetscOptionsEnd();
    PetscCheck(std::isfinite(ckpt_interval_) && ckpt_interval_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -checkpoint_interval = %g: must be finite and >= 0", (double)ckpt_interval_);
    PetscCheck(std::isfinite(ckpt_wall_) && ckpt_wall_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -checkpoint_wall_interval = %g: must be finite and >= 0",
               (double)ckpt_wall_);
    PetscCheck(ckpt_keep_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -checkpoint_keep = %" PetscInt_FMT ": must be >= 0 (0 keeps all)", ckpt_keep_);
    PetscCheck(!set || file[0], comm_, PETSC_ERR_ARG_WRONG, "Option -restart: empty (give the checkpoint file to continue from)");
    PetscCheck(restart_read_rows_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -restart_read_rows = %" PetscInt_FMT ": must be >= 1", restart_read_rows_);
    restart_file_ = set ? file : "";
    PetscCheck(restart_allow_.empty() || set, comm_, PETSC_ERR_ARG_WRONG, "Option -restart_allow: only with -restart");
    PetscCheck(Checkpointable() || (ckpt_interval_ == 0 && ckpt_wall_ == 0 && !set), comm_, PETSC_ERR_SUP,
               "Option %s: -mode %s has no checkpoints (-mode fine and -mode fe2 have)",
               set                  ? "-restart"
               : ckpt_interval_ > 0 ? "-checkpoint_interval"
                                    : "-checkpoint_wall_interval",
               mode_.c_str());
  }
  PetscCall(ModeSetFromOptions());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::SetUp()
{
  PetscFunctionBeginUser;
  PetscCall(RegisterLogStage((mode_ + " setup").c_str(), &stage_setup_));
  PetscCall(RegisterLogStage((mode_ + " solve").c_str(), &stage_solve_));
  PetscCall(PetscLogEventRegister("TgOutput", PETSC_OBJECT_CLASSID, &ev_output_));
  PetscCall(PetscLogEventRegister("TgCheckpointWrite", PETSC_OBJECT_CLASSID, &ev_ckpt_write_));
  PetscCall(PetscLogEventRegister("TgCheckpointRead", PETSC_OBJECT_CLASSID, &ev_ckpt_read_));
  PetscCall(PetscLogStagePush(stage_setup_));
  PetscCheck(ts_, comm_, PETSC_ERR_ORDER, "SetFromOptions() must be called before SetUp()");
  PetscCall(SetUpModel());
  PetscCall(TSMonitorSet(ts_, Monitor, this, NULL));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSSetFromOptions(ts_));
  PetscCall(CheckIntegrator());
  PetscCall(CheckTSOptions());
  PetscCall(AfterTSSetFromOptions());
  /* set up now, not at the first step: the integrator's own solvers read their options before the
     unused ones are reported */
  PetscCall(TSSetSolution(ts_, U_));
  PetscCall(TSSetUp(ts_));
  sampler_.Configure(t_final_, out_.samples, out_.snapshots, out_.progress_interval);
  if (ckpt_interval_ > 0 || ckpt_wall_ > 0 || !restart_file_.empty()) {
    PetscBool   ok;
    const char *why;
    PetscCall(TSCheckpointSupported(ts_, &ok, &why));
    const std::string option = restart_file_.empty() ? (ckpt_interval_ > 0 ? "-checkpoint_interval" : "-checkpoint_wall_interval")
                                                     : "-restart " + restart_file_;
    PetscCheck(ok, comm_, PETSC_ERR_SUP,
               "Option %s: %s, which a checkpoint does not hold; checkpoints support the one-step explicit integrators (-ts_type rk, lsrk, euler, ssp%s)",
               option.c_str(), why, mode_ == "fine" ? ", basicsymplectic, verlet" : "");
  }
  if (!restart_file_.empty()) {
    PetscCall(ReadCheckpoint());
    ckpt_last_file_ = restart_file_;
  }
  {
    PetscReal t0;
    PetscCall(TSGetTime(ts_, &t0));
    ckpt_next_ = ckpt_interval_ > 0 ? ckpt_interval_ * (std::floor(t0 / ckpt_interval_ * (1 + 1e-12)) + 1) : 0;
  }
  PetscCall(Report());
  /* the summary's place, kept while the run writes (a full disk later still takes it), and what a
     killed run leaves: status "running" */
  if (out_.ready) PetscCall(ReserveSummary(comm_, out_.dir + "/summary.json", mode_));
  series_.clear();
  {
    std::vector<std::string> columns = {"time"};
    for (const std::string &c : ObservedColumns()) columns.push_back(c);
    PetscCall(OpenSeries(tip_csv_, "tip.csv", columns));
  }
  series_csv_.clear();
  for (const Series &s : ObservedSeries()) {
    series_csv_.push_back(std::make_unique<CsvWriter>());
    std::vector<std::string> columns = {"time"};
    for (const std::string &c : s.columns) columns.push_back(c);
    PetscCall(OpenSeries(*series_csv_.back(), s.file, columns));
  }
  if (out_.snapshots > 0 && out_.ready) PetscCall(OpenSnapshots());
  if (out_.ready) PetscCall(OpenOutputs());
  PetscCall(CheckOutputs(SeriesStep::Check));
  PetscCall(AfterSetUp());
  PetscCall(StopIfInterrupted(comm_, ("the set-up of the " + mode_ + " run: no step was taken").c_str()));
  peak_rss_setup_ = PeakResidentBytes();
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Before any step: a step, a final time and tolerances that would hang the run, fill its outputs
   with NaN or switch its error control off are refused, naming the option. */
PetscErrorCode TimeRun::CheckTSOptions()
{
  PetscReal dt, atol, rtol;
  PetscInt  max_steps;
  Vec       vatol, vrtol;
  TSAdapt   adapt;
  PetscBool fixed;
  PetscFunctionBeginUser;
  PetscCall(TSGetMaxTime(ts_, &t_final_));
  PetscCheck(std::isfinite(t_final_) && t_final_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_max_time = %g: must be finite and > 0", (double)t_final_);
  PetscCall(TSGetTimeStep(ts_, &dt));
  PetscCheck(std::isfinite(dt) && dt > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_dt = %g: the time step must be finite and > 0", (double)dt);
  PetscCall(TSGetMaxSteps(ts_, &max_steps));
  PetscCheck(max_steps >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_max_steps = %" PetscInt_FMT ": must be >= 1", max_steps);
  PetscCall(TSGetTolerances(ts_, &atol, &vatol, &rtol, &vrtol));
  PetscCheck(std::isfinite(atol) && atol >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_atol = %g: must be finite and >= 0", (double)atol);
  PetscCheck(std::isfinite(rtol) && rtol >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_rtol = %g: must be finite and >= 0", (double)rtol);
  PetscCall(TSGetAdapt(ts_, &adapt));
  {
    /* the smallest step an adaptive integrator may take (default 1e-10 of the run): below it the
       run fails instead of crawling on (or not advancing at all: a step below the round-off of t)
       at a state it cannot pass -- e.g. an RVE that fails for every step size */
    PetscReal   dt_min, dt_max;
    PetscBool   set;
    const char *prefix;
    PetscCall(TSGetOptionsPrefix(ts_, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_adapt_dt_min", &set));
    PetscCall(TSAdaptGetStepLimits(adapt, &dt_min, &dt_max));
    if (!set) PetscCall(TSAdaptSetStepLimits(adapt, kMinStepFraction * t_final_, dt_max));
    PetscCall(TSAdaptGetStepLimits(adapt, &dt_min_, NULL));
    PetscCheck(std::isfinite(dt_min_) && dt_min_ >= 0 && dt_min_ < t_final_, comm_, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -ts_adapt_dt_min = %g: must be >= 0 and below -ts_max_time = %g", (double)dt_min_, (double)t_final_);
  }
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTNONE, &fixed));
  PetscCheck(fixed || vatol || vrtol || atol > 0 || rtol > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE,
             "Options -ts_rtol = %g and -ts_atol = %g: an adaptive integrator with both tolerances 0 has no error control (its steps grow without bound); give "
             "a tolerance > 0, or a fixed step with -ts_adapt_type none",
             (double)rtol, (double)atol);
  {
    /* the integrator is part of the physics a restart must not change: its type, tolerances, step
       controller and (first or fixed) step */
    TSType      type;
    TSAdaptType adapt_type;
    PetscBool   is_rk;
    PetscCall(TSGetType(ts_, &type));
    PetscCall(TSAdaptGetType(adapt, &adapt_type));
    params_.Set("-ts_type", type ? type : "");
    PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSRK, &is_rk));
    if (is_rk) {
      TSRKType rk;
      PetscCall(TSRKGetType(ts_, &rk));
      params_.Set("-ts_rk_type", rk);
    }
    params_.Set("-ts_adapt_type", adapt_type ? adapt_type : "");
    params_.Set("-ts_rtol", ParameterValue(rtol));
    params_.Set("-ts_atol", ParameterValue(atol));
    /* a step the user gave; one the mode derives (from the stability limits) follows the parameters it
       derives from */
    PetscBool   given;
    const char *prefix;
    PetscCall(TSGetOptionsPrefix(ts_, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_dt", &given));
    if (given) params_.Set("-ts_dt", ParameterValue(dt));
    dt_start_ = dt;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::Sample(PetscReal t, Vec U)
{
  std::vector<PetscReal> row;
  PetscFunctionBeginUser;
  PetscCall(Observe(t, U, row));
  observed_ = row.empty() ? 0 : row[0];
  row.insert(row.begin(), t);
  if (tip_csv_.IsOpen()) PetscCall(tip_csv_.Row(row));
  if (!series_csv_.empty()) {
    std::vector<std::vector<PetscReal>> rows(series_csv_.size());
    PetscCall(ObserveSeries(t, U, rows));
    for (size_t k = 0; k < series_csv_.size(); k++) {
      rows[k].insert(rows[k].begin(), t);
      if (series_csv_[k]->IsOpen()) PetscCall(series_csv_[k]->Row(rows[k]));
    }
  }
  PetscCall(CheckOutputs(SeriesStep::Check)); /* a failed write stops the run at the sample after it */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::CheckOutputs(SeriesStep step)
{
  std::string error;
  PetscFunctionBeginUser;
  for (auto &fc : series_) { /* rank 0's */
    if (step == SeriesStep::Flush) fc.second->Flush();
    if (step == SeriesStep::Close) fc.second->Finish();
    if (error.empty()) error = fc.second->Error();
  }
  PetscCall(CheckOutputError(comm_, error));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After every accepted step: the mode's own work (internal state committed), then the decisions to
   stop. They are taken here, not in the monitor: TSSolve monitors before TSStep, which resets the
   converged reason, so a reason set by a monitor is lost and the run goes on. */
PetscErrorCode TimeRun::PostStep(TS ts)
{
  return TURGOR_GUARDED({
    TimeRun  *run;
    PetscReal t;
    PetscInt  step;
    Vec       U;
    PetscBool stop;
    PetscFunctionBeginUser;
    PetscCall(TSGetApplicationContext(ts, &run));
    PetscCall(TSGetTime(ts, &t));
    PetscCall(TSGetStepNumber(ts, &step));
    PetscCall(TSGetSolution(ts, &U));
    PetscCall(run->AfterStep(t, U));
    /* an accepted step below -ts_adapt_dt_min, or one that does not advance the time at all (below
       the round-off of t), before the final time: the integrator is cutting its step at a state
       it cannot pass, and would crawl on (or repeat) forever */
    const PetscReal h = t - run->t_last_;
    if (t < run->t_final_ && !(h >= run->dt_min_ && h > 64 * PETSC_MACHINE_EPSILON * PetscMax(PetscAbsReal(t), run->t_final_))) {
      run->stalled_ = h;
      PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_STEP_REJECTED));
    }
    run->t_last_ = t;
    PetscCall(InterruptRequestedAll(run->comm_, &stop));
    if (stop && !run->interrupted_) { /* after this step: the outputs hold every sample up to here */
      run->interrupted_ = true;
      PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
      PetscCall(PetscPrintf(run->comm_, "Interrupted at t = %g µs (step %" PetscInt_FMT "): stopping after this step (a second signal stops inside it)\n",
                            (double)t, step));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode TimeRun::StopAfterThisStep(const std::string &status, const std::string &reason)
{
  PetscFunctionBeginUser;
  if (!stop_status_.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  stop_status_ = status;
  stop_reason_ = reason;
  PetscCall(TSSetConvergedReason(ts_, TS_CONVERGED_USER));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  return TURGOR_GUARDED({
    TimeRun *run = (TimeRun *)ctx;
    PetscFunctionBeginUser;
    PetscCall(PetscLogEventBegin(run->ev_output_, 0, 0, 0, 0));
    const auto snapshot = [run](PetscReal tk, Vec X) {
      run->writing_             = "the snapshot at t = " + std::to_string((double)tk) + " µs to " + run->SnapshotFiles();
      const PetscErrorCode ierr = run->WriteSnapshot(tk, X);
      if (!ierr) run->writing_.clear();
      return ierr;
    };
    PetscCall(run->sampler_.Monitor(
      ts, step, t, U, [run](PetscReal tk, Vec X) { return run->Sample(tk, X); }, snapshot, run->FunctionEvaluations()));
    PetscCall(PetscLogEventEnd(run->ev_output_, 0, 0, 0, 0));
    /* after the samples of this step: a restart continues with the next ones */
    if (step > run->ckpt_last_step_ && step > 0 && (run->ckpt_interval_ > 0 || run->ckpt_wall_ > 0) && !run->interrupted_) { /* Solve() writes an interrupt's */
      PetscBool due;
      PetscCall(run->CheckpointDue(t, &due));
      if (due) PetscCall(run->WriteCheckpoint(t, step));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode TimeRun::Solve()
{
  TSConvergedReason reason;
  PetscReal         t;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(stage_solve_));
  solving_ = true;
  PetscCall(TSGetTime(ts_, &t_last_));
  PetscCall(TSSolve(ts_, U_));
  wall_ = sampler_.Elapsed();
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetSolveTime(ts_, &t));
  if (stalled_ >= 0 || reason < 0) { /* stuck at t: the mode may know why and end the run there */
    std::string status, why;
    PetscCall(EndWhereStuck(t, stalled_ >= 0, &status, &why));
    if (!status.empty()) {
      stop_status_ = status;
      stop_reason_ = why;
      stalled_     = -1;
      reason       = TS_CONVERGED_USER;
    }
  }
  PetscCheck(stalled_ < 0, comm_, PETSC_ERR_NOT_CONVERGED,
             "The %s run failed at t = %g µs: the time step fell to %g µs, below -ts_adapt_dt_min = %g µs (default 1e-10 of -ts_max_time): the "
             "integrator cannot pass this state with any step: %s",
             mode_.c_str(), (double)t, (double)stalled_, (double)dt_min_, FailureAdvice());
  PetscCheck(reason >= 0, comm_, PETSC_ERR_NOT_CONVERGED, "The %s run failed at t = %g µs (%s): %s", mode_.c_str(), (double)t, TSConvergedReasons[reason],
             FailureAdvice());
  /* a run that ends before its end time without an interrupt stopped at -ts_max_steps: not completed */
  stopped_ = !interrupted_ && stop_status_.empty() && t < t_final_ * (1 - 1e-12);
  if ((ckpt_interval_ > 0 || ckpt_wall_ > 0) && out_.ready) { /* the end of the run (or its interrupt) */
    PetscInt  step;
    PetscReal tn;
    PetscCall(TSGetStepNumber(ts_, &step));
    PetscCall(TSGetTime(ts_, &tn));
    if (step != ckpt_last_step_) PetscCall(WriteCheckpoint(tn, step)); /* an interrupt's: its summary first (InterruptWhileWriting) */
  }
  PetscCall(AfterSolve());
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::FitFixedSteps(PetscReal t, PetscInt step)
{
  PetscReal dt;
  PetscInt  max_steps;
  PetscFunctionBeginUser;
  PetscCall(TSGetTimeStep(ts_, &dt));
  PetscCall(TSGetMaxSteps(ts_, &max_steps));
  if (!fit_fixed_) auto_max_steps_ = max_steps == PETSC_MAX_INT;
  fit_fixed_ = true;
  if (t_final_ - t < 1e12 * dt) {
    const PetscReal n = std::ceil((t_final_ - t) / dt * (1 - 1e-12));
    PetscCall(TSSetTimeStep(ts_, (t_final_ - t) / n));
    if (auto_max_steps_) PetscCall(TSSetMaxSteps(ts_, step + (PetscInt)n));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The keys every time-dependent run reports, completed or not; not collective (rank-local counts). */
PetscErrorCode TimeRun::CommonSummary(JsonObject &js, const char *status)
{
  TSType      type;
  PetscReal   rtol = 0, atol = 0, t = 0;
  PetscInt    steps = 0, rej = 0;
  PetscMPIInt size;
  PetscBool   is_rk, is_arkimex;
  PetscFunctionBeginUser;
  js.Set("mode", mode_);
  js.Set("status", status);
  if (ts_) {
    PetscCall(TSGetType(ts_, &type));
    std::string ts_type = type ? type : "";
    PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSRK, &is_rk));
    PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSARKIMEX, &is_arkimex));
    if (is_rk) {
      TSRKType rk;
      PetscCall(TSRKGetType(ts_, &rk));
      ts_type += std::string(" ") + rk;
    } else if (is_arkimex) {
      TSARKIMEXType ark;
      PetscCall(TSARKIMEXGetType(ts_, &ark));
      ts_type += std::string(" ") + ark;
    }
    PetscCall(TSGetTolerances(ts_, &atol, NULL, &rtol, NULL));
    PetscCall(TSGetTime(ts_, &t));
    PetscCall(TSGetStepNumber(ts_, &steps));
    PetscCall(TSGetStepRejections(ts_, &rej));
    js.Set("ts_type", ts_type);
  }
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  js.Set("rtol", rtol);
  js.Set("atol", atol);
  js.Set("t_final", t);
  js.Set("t_requested", t_final_);
  js.Set("steps", steps);
  js.Set("rejected_steps", rej);
  js.Set("rhs_evals", FunctionEvaluations());
  js.Set("wall_time_s", (PetscReal)wall_);
  js.Set("mpi_ranks", (PetscInt)size);
  if (ckpt_interval_ > 0 || ckpt_wall_ > 0 || !restart_file_.empty()) js.Set("checkpoint_last", ckpt_last_file_);
  if (ckpt_interval_ > 0 || ckpt_wall_ > 0) {
    js.Set("checkpoints_written", ckpt_count_);
    js.Set("checkpoint_bytes", ckpt_bytes_);
    js.Set("checkpoint_write_s", ckpt_seconds_);
  }
  if (!restart_file_.empty()) {
    js.Set("restarted_from", restart_file_);
    js.Set("restart_step", restart_step_);
    js.Set("restart_allowed", restart_allow_);
    js.Set("restart_changed", restart_changed_);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A batch system's TERM is followed by KILL soon (mpiexec's: about a second later), maybe before a
   checkpoint is written whole: once SIGINT/SIGTERM is seen while one is written (at its start and
   between its declarations; collective), the run stops after this step and says so at once in
   summary.json, "interrupted", naming the last complete checkpoint and the one being written
   (`pending`). The final summary replaces it when the run ends. */
PetscErrorCode TimeRun::InterruptWhileWriting(const std::string &pending)
{
  PetscBool stop = interrupted_ ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  if (interrupt_said_ || !out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  if (!stop) PetscCall(InterruptRequestedAll(comm_, &stop));
  if (!stop) PetscFunctionReturn(PETSC_SUCCESS);
  if (!interrupted_) {
    PetscReal t;
    PetscInt  step;
    PetscCall(TSGetTime(ts_, &t));
    PetscCall(TSGetStepNumber(ts_, &step));
    interrupted_ = true;
    PetscCall(TSSetConvergedReason(ts_, TS_CONVERGED_USER));
    PetscCall(
      PetscPrintf(comm_, "Interrupted at t = %g µs (step %" PetscInt_FMT ") while writing a checkpoint: stopping once it is written\n", (double)t, step));
  }
  JsonObject js;
  PetscCall(CheckOutputs(SeriesStep::Flush));
  PetscCall(Summarize(js));
  js.Set("checkpoint_pending", pending);
  PetscCall(js.Write(comm_, out_.dir + "/summary.json"));
  interrupt_said_ = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* This rank's share of final_state_hash: each local entry at its StateOrder place. */
PetscErrorCode TimeRun::StateChecksum(Vec U, std::uint64_t *h)
{
  const PetscScalar *u;
  PetscInt           n, first;
  const PetscInt    *order = NULL;
  IS                 is;
  PetscFunctionBeginUser;
  PetscCall(StateOrder(&is));
  PetscCall(VecGetLocalSize(U, &n));
  PetscCall(VecGetOwnershipRange(U, &first, NULL));
  if (is) PetscCall(ISGetIndices(is, &order));
  PetscCall(VecGetArrayRead(U, &u));
  for (PetscInt l = 0; l < n; l++) *h += ChecksumTerm((std::uint64_t)(order ? order[l] : first + l), (PetscReal)PetscRealPart(u[l]));
  PetscCall(VecRestoreArrayRead(U, &u));
  if (is) PetscCall(ISRestoreIndices(is, &order));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The summary of a run that ended (completed, stopped or interrupted); collective. */
PetscErrorCode TimeRun::Summarize(JsonObject &js)
{
  PetscInt    evals = FunctionEvaluations();
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(CommonSummary(js, interrupted_ ? "interrupted" : !stop_status_.empty() ? stop_status_.c_str() : stopped_ ? "stopped" : "completed"));
  if (!stop_status_.empty() && !interrupted_) js.Set("reason", stop_reason_);
  if (stopped_) {
    PetscInt max_steps;
    PetscCall(TSGetMaxSteps(ts_, &max_steps));
    js.Set("reason", "stopped after -ts_max_steps " + std::to_string((long long)max_steps) + " steps, before -ts_max_time");
  }
  if (interrupted_) {
    js.Set("reason", "interrupted (SIGINT/SIGTERM): the time series end at t_final, before t_requested");
    if (rank == 0) js.Set("partial_outputs", OutputFilesIn(out_.dir, false));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &evals, 1, MPIU_INT, MPI_MAX, comm_));
  js.Set("rhs_evals", evals);
  PetscCall(AddSummary(js));
  js.Set("tip_displacement_final", observed_);
  {
    /* a checksum of the final state's bits, each entry at its rank-free place (StateOrder): equal
       hashes are (all but surely) equal states bit for bit, whatever the ranks and the distribution
       (restart tests; 1 rank against -fine_distribute 0 on 2) */
    std::uint64_t h = 0;
    PetscCall(StateChecksum(U_, &h));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &h, 1, MPI_UINT64_T, MPI_SUM, comm_));
    char hex[24];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h);
    js.Set("final_state_hash", std::string(hex));
  }
  js.Set("snapshots", SnapshotCount());
  {
    /* the largest rank's peak resident set by the end of the set-up and by now (what the
       operating system counts: libraries and MPI included); collective, so not in CommonSummary,
       which a failure writes from rank 0 alone */
    PetscReal peak[2] = {peak_rss_setup_, PeakResidentBytes()};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, peak, 2, MPIU_REAL, MPI_MAX, comm_));
    js.Set("peak_rss_setup_bytes", peak[0]);
    js.Set("peak_rss_bytes", peak[1]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every output closed and checked first: a summary that says completed has them all written. */
PetscErrorCode TimeRun::WriteSummary()
{
  JsonObject  js;
  PetscReal   t;
  PetscInt    steps, rej;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCall(CheckOutputs(SeriesStep::Close));
  PetscCall(CloseOutputs());
  PetscCall(Summarize(js));
  PetscCall(js.Write(comm_, out_.dir + "/summary.json"));
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetStepRejections(ts_, &rej));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::string details, files = rank == 0 ? OutputFileList(out_.dir) : std::string(); /* rank 0 prints */
  PetscCall(DoneDetails(&details));
  PetscCall(PetscPrintf(comm_,
                        "%s: t = %g µs, %" PetscInt_FMT " steps (%" PetscInt_FMT
                        " rejected), %s, %.3f s wall; final tip displacement %.6g µm\nOutputs in %s: %s\n",
                        interrupted_            ? "Interrupted"
                        : !stop_status_.empty() ? ("Stopped (" + stop_status_ + ")").c_str()
                        : stopped_              ? "Stopped (-ts_max_steps)"
                                                : "Done",
                        (double)t, steps, rej, details.c_str(), (double)wall_, (double)observed_, out_.dir.c_str(), files.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::WriteFailure(const std::string &reason, const char status[])
{
  JsonObject  js;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank != 0 || !out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  if (solving_) wall_ = sampler_.Elapsed();
  PetscCall(CommonSummary(js, status));
  js.Set("reason", writing_.empty() ? reason : "while writing " + writing_ + ": " + reason);
  AddFailureSummary(js);
  for (auto &fc : series_) fc.second->Finish(); /* what they hold; a failure to write one is the reason already */
  if (solving_) {
    js.Set("tip_displacement_last_sample", observed_);
    js.Set("partial_outputs", OutputFilesIn(out_.dir, false));
  }
  PetscCall(js.Write(PETSC_COMM_SELF, out_.dir + "/summary.json"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
