#include <turgor/core/errors.h>
#include <turgor/core/log.h>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <turgor/run/time_run.h>
#include <turgor/ts/ts_checkpoint.h>
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
    PetscCall(PetscOptionsString("-restart",
                                 "Continue from this checkpoint file (-mode fine, or -mode fe2 with its RVE states): the same scene options, integrator and "
                                 "number of ranks; checkpoints need a one-step explicit integrator (-ts_type rk, euler, ssp)",
                                 "TimeRun", file, file, sizeof file, &set));
    PetscOptionsEnd();
    PetscCheck(std::isfinite(ckpt_interval_) && ckpt_interval_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -checkpoint_interval = %g: must be finite and >= 0", (double)ckpt_interval_);
    PetscCheck(std::isfinite(ckpt_wall_) && ckpt_wall_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -checkpoint_wall_interval = %g: must be finite and >= 0",
               (double)ckpt_wall_);
    PetscCheck(!set || file[0], comm_, PETSC_ERR_ARG_WRONG, "Option -restart: empty (give the checkpoint file to continue from)");
    restart_file_ = set ? file : "";
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
  PetscMPIInt rank;
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
               "Option %s: %s, which a checkpoint does not hold; checkpoints support the one-step explicit integrators (-ts_type rk, euler, ssp%s)",
               option.c_str(), why, mode_ == "fine" ? ", basicsymplectic, verlet" : "");
  }
  if (!restart_file_.empty()) {
    PetscCall(ReadCheckpoint());
    PetscCall(TSSetPreStep(ts_, PreStep));
  }
  {
    PetscReal t0;
    PetscCall(TSGetTime(ts_, &t0));
    ckpt_next_ = ckpt_interval_ > 0 ? ckpt_interval_ * (std::floor(t0 / ckpt_interval_ * (1 + 1e-12)) + 1) : 0;
  }
  PetscCall(Report());
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0 && out_.ready) {
    std::vector<std::string> columns = {"time"};
    for (const std::string &c : ObservedColumns()) columns.push_back(c);
    if (restart_file_.empty()) PetscCall(tip_csv_.Open(PETSC_COMM_SELF, out_.dir + "/tip.csv", columns));
    else PetscCall(tip_csv_.Continue(PETSC_COMM_SELF, out_.dir + "/tip.csv", columns, restart_tip_rows_));
  }
  series_csv_.clear();
  series_files_.clear();
  for (const Series &s : ObservedSeries()) {
    series_csv_.push_back(std::make_unique<CsvWriter>());
    series_files_.push_back(s.file);
    if (rank == 0 && out_.ready) {
      std::vector<std::string> columns = {"time"};
      for (const std::string &c : s.columns) columns.push_back(c);
      if (restart_file_.empty()) PetscCall(series_csv_.back()->Open(PETSC_COMM_SELF, out_.dir + "/" + s.file, columns));
      else PetscCall(series_csv_.back()->Continue(PETSC_COMM_SELF, out_.dir + "/" + s.file, columns, restart_tip_rows_)); /* sampled with tip.csv */
    }
  }
  if (out_.snapshots > 0 && out_.ready) PetscCall(OpenSnapshots());
  if (out_.ready) PetscCall(OpenOutputs());
  PetscCall(AfterSetUp());
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

PetscErrorCode TimeRun::Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  return TURGOR_GUARDED({
    TimeRun *run = (TimeRun *)ctx;
    PetscFunctionBeginUser;
    PetscCall(PetscLogEventBegin(run->ev_output_, 0, 0, 0, 0));
    PetscCall(run->sampler_.Monitor(
      ts, step, t, U, [run](PetscReal tk, Vec X) { return run->Sample(tk, X); }, [run](PetscReal tk, Vec X) { return run->WriteSnapshot(tk, X); },
      run->FunctionEvaluations()));
    PetscCall(PetscLogEventEnd(run->ev_output_, 0, 0, 0, 0));
    /* after the samples of this step: a restart continues with the next ones */
    if (step > run->ckpt_last_step_ && step > 0 && (run->ckpt_interval_ > 0 || run->ckpt_wall_ > 0)) {
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
  PetscCheck(stalled_ < 0, comm_, PETSC_ERR_NOT_CONVERGED,
             "The %s run failed at t = %g µs: the time step fell to %g µs, below -ts_adapt_dt_min = %g µs (default 1e-10 of -ts_max_time): the "
             "integrator cannot pass this state with any step: %s",
             mode_.c_str(), (double)t, (double)stalled_, (double)dt_min_, FailureAdvice());
  PetscCheck(reason >= 0, comm_, PETSC_ERR_NOT_CONVERGED, "The %s run failed at t = %g µs (%s): %s", mode_.c_str(), (double)t, TSConvergedReasons[reason],
             FailureAdvice());
  if ((ckpt_interval_ > 0 || ckpt_wall_ > 0) && out_.ready) { /* the end of the run (or its interrupt) */
    PetscInt  step;
    PetscReal tn;
    PetscCall(TSGetStepNumber(ts_, &step));
    PetscCall(TSGetTime(ts_, &tn));
    if (step != ckpt_last_step_) PetscCall(WriteCheckpoint(tn, step));
  }
  PetscCall(AfterSolve());
  PetscCall(PetscLogStagePop());
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
  if (ckpt_interval_ > 0 || ckpt_wall_ > 0) {
    js.Set("checkpoints_written", ckpt_count_);
    js.Set("checkpoint_bytes", ckpt_bytes_);
    js.Set("checkpoint_write_s", ckpt_seconds_);
  }
  if (!restart_file_.empty()) {
    js.Set("restarted_from", restart_file_);
    js.Set("restart_step", restart_step_);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::WriteSummary()
{
  JsonObject js;
  PetscInt   evals = FunctionEvaluations();
  PetscReal  t;
  PetscInt   steps, rej;
  PetscFunctionBeginUser;
  PetscCall(CommonSummary(js, interrupted_ ? "interrupted" : "completed"));
  if (interrupted_) {
    js.Set("reason", "interrupted (SIGINT/SIGTERM): the time series end at t_final, before t_requested");
    std::vector<std::string> partial = {"tip.csv", std::string(SnapshotFiles())};
    partial.insert(partial.end(), series_files_.begin(), series_files_.end());
    js.Set("partial_outputs", partial);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &evals, 1, MPIU_INT, MPI_MAX, comm_));
  js.Set("rhs_evals", evals);
  PetscCall(AddSummary(js));
  js.Set("tip_displacement_final", observed_);
  {
    /* FNV-1a over the final state's bytes, rank by rank: equal hashes are (all but surely) equal
       states bit for bit (restart tests) */
    const PetscScalar *u;
    PetscInt           n;
    std::uint64_t      h = 1469598103934665603ull;
    PetscCall(VecGetLocalSize(U_, &n));
    PetscCall(VecGetArrayRead(U_, &u));
    const unsigned char *b = (const unsigned char *)u;
    for (size_t k = 0; k < (size_t)n * sizeof(PetscScalar); k++) h = (h ^ b[k]) * 1099511628211ull;
    PetscCall(VecRestoreArrayRead(U_, &u));
    PetscMPIInt size, rank;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    std::vector<std::uint64_t> all(size);
    PetscCallMPI(MPI_Gather(&h, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, 0, comm_));
    std::uint64_t g = 1469598103934665603ull;
    for (std::uint64_t x : all) g = (g ^ x) * 1099511628211ull;
    char hex[24];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)g);
    js.Set("final_state_hash", std::string(hex));
  }
  js.Set("snapshots", SnapshotCount());
  PetscCall(js.Write(comm_, out_.dir + "/summary.json"));
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetStepRejections(ts_, &rej));
  std::string details, files = "tip.csv, summary.json";
  PetscCall(DoneDetails(&details));
  for (const Series &s : ObservedSeries()) files += ", " + s.file;
  if (out_.snapshots > 0) files += std::string(", ") + SnapshotFiles();
  PetscCall(PetscPrintf(comm_,
                        "%s: t = %g µs, %" PetscInt_FMT " steps (%" PetscInt_FMT
                        " rejected), %s, %.3f s wall; final tip displacement %.6g µm\nOutputs in %s: %s\n",
                        interrupted_ ? "Interrupted" : "Done", (double)t, steps, rej, details.c_str(), (double)wall_, (double)observed_, out_.dir.c_str(),
                        files.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::WriteFailure(const std::string &reason)
{
  JsonObject  js;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank != 0 || !out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  if (solving_) wall_ = sampler_.Elapsed();
  PetscCall(CommonSummary(js, "failed"));
  js.Set("reason", reason);
  if (solving_) {
    js.Set("tip_displacement_last_sample", observed_);
    std::vector<std::string> partial = {"tip.csv", std::string(SnapshotFiles())};
    partial.insert(partial.end(), series_files_.begin(), series_files_.end());
    js.Set("partial_outputs", partial);
  }
  PetscCall(tip_csv_.Close());
  for (auto &csv : series_csv_) PetscCall(csv->Close());
  PetscCall(js.Write(PETSC_COMM_SELF, out_.dir + "/summary.json"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- checkpoints ---- */

static const PetscInt kCheckpointVersion = 3; /* 2: the state in the mode's StateOrder; 3: Verlet's acceleration too, and global_state */

/* The integrator as a checkpoint names it: type, and the RK or ARKIMEX scheme. */
static PetscErrorCode IntegratorName(TS ts, std::string *name)
{
  TSType    type;
  PetscBool is_rk;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts, &type));
  *name = type ? type : "";
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is_rk));
  if (is_rk) {
    TSRKType rk;
    PetscCall(TSRKGetType(ts, &rk));
    *name += std::string(" ") + rk;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A Vec of U's parallel layout without its DM, holding U's values, named `name`. */
static PetscErrorCode PlainCopy(Vec U, Vec *S, const char *name = "state")
{
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(U, &n));
  PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)U), n, PETSC_DETERMINE, S));
  PetscCall(VecCopy(U, *S));
  PetscCall(PetscObjectSetName((PetscObject)*S, name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* canonical[order[k]] = local[k] (SCATTER_FORWARD), or back (SCATTER_REVERSE) */
static PetscErrorCode Permute(Vec local, Vec canonical, IS order, ScatterMode mode)
{
  VecScatter sc;
  PetscFunctionBeginUser;
  PetscCall(VecScatterCreate(local, NULL, canonical, order, &sc));
  if (mode == SCATTER_FORWARD) {
    PetscCall(VecScatterBegin(sc, local, canonical, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, local, canonical, INSERT_VALUES, SCATTER_FORWARD));
  } else {
    PetscCall(VecScatterBegin(sc, canonical, local, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(sc, canonical, local, INSERT_VALUES, SCATTER_REVERSE));
  }
  PetscCall(VecScatterDestroy(&sc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One number per rank as the dataset `name` (in rank order). */
static PetscErrorCode WriteRankValue(MPI_Comm comm, PetscViewer v, const std::string &name, PetscInt value)
{
  Vec         L;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, 1, PETSC_DETERMINE, &L));
  PetscCall(PetscObjectSetName((PetscObject)L, name.c_str()));
  PetscCall(VecSetValue(L, rank, (PetscScalar)value, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(L));
  PetscCall(VecAssemblyEnd(L));
  PetscCall(VecView(L, v));
  PetscCall(VecDestroy(&L));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Each rank's blob as the dataset `name` (per rank: its length, then the numbers) and its layout
   `name`_layout (per rank, the length). */
static PetscErrorCode WriteRankBlobs(MPI_Comm comm, PetscViewer v, const std::string &name, const StateBlob &blob)
{
  Vec          B;
  PetscScalar *b;
  PetscFunctionBeginUser;
  const PetscInt n = (PetscInt)blob.data.size();
  PetscCall(WriteRankValue(comm, v, name + "_layout", n));
  PetscCall(VecCreateMPI(comm, n + 1, PETSC_DETERMINE, &B));
  PetscCall(PetscObjectSetName((PetscObject)B, name.c_str()));
  PetscCall(VecGetArray(B, &b));
  b[0] = (PetscScalar)n;
  for (PetscInt k = 0; k < n; k++) b[k + 1] = blob.data[k];
  PetscCall(VecRestoreArray(B, &b));
  PetscCall(VecView(B, v));
  PetscCall(VecDestroy(&B));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* This rank's blob of the dataset `name` (written on as many ranks). */
static PetscErrorCode ReadRankBlob(MPI_Comm comm, PetscViewer v, const std::string &name, StateBlob &blob)
{
  Vec                L, B;
  const PetscScalar *l, *b;
  PetscInt           n;
  PetscMPIInt        rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecCreateMPI(comm, 1, PETSC_DETERMINE, &L));
  PetscCall(PetscObjectSetName((PetscObject)L, (name + "_layout").c_str()));
  PetscCall(VecLoad(L, v));
  PetscCall(VecGetArrayRead(L, &l));
  n = (PetscInt)PetscRealPart(l[0]);
  PetscCall(VecRestoreArrayRead(L, &l));
  PetscCall(VecDestroy(&L));
  PetscCall(VecCreateMPI(comm, n + 1, PETSC_DETERMINE, &B));
  PetscCall(PetscObjectSetName((PetscObject)B, name.c_str()));
  PetscCall(VecLoad(B, v));
  PetscCall(VecGetArrayRead(B, &b));
  PetscCheck((PetscInt)PetscRealPart(b[0]) == n, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s of rank %d: length %g, layout says %" PetscInt_FMT,
             name.c_str(), rank, (double)PetscRealPart(b[0]), n);
  blob.data.assign(b + 1, b + 1 + n);
  PetscCall(VecRestoreArrayRead(B, &b));
  PetscCall(VecDestroy(&B));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A Vec of `size` entries read from dataset `name`, whole on every rank. */
static PetscErrorCode ReadWhole(MPI_Comm comm, PetscViewer v, const std::string &name, PetscInt size, std::vector<PetscReal> &all)
{
  Vec                X, Y;
  VecScatter         sc;
  const PetscScalar *y;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, PETSC_DECIDE, size, &X));
  PetscCall(PetscObjectSetName((PetscObject)X, name.c_str()));
  PetscCall(VecLoad(X, v));
  PetscCall(VecScatterCreateToAll(X, &sc, &Y));
  PetscCall(VecScatterBegin(sc, X, Y, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, X, Y, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(Y, &y));
  all.resize((size_t)size);
  for (PetscInt k = 0; k < size; k++) all[k] = PetscRealPart(y[k]);
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&X));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every one of the `writers` ranks' blobs of the dataset `name`, on every rank (another rank count). */
static PetscErrorCode ReadAllRankBlobs(MPI_Comm comm, PetscViewer v, const std::string &name, PetscInt writers, std::vector<StateBlob> &blobs)
{
  std::vector<PetscReal> len, all;
  PetscInt               total = 0;
  PetscFunctionBeginUser;
  PetscCall(ReadWhole(comm, v, name + "_layout", writers, len));
  for (PetscReal l : len) total += (PetscInt)l + 1;
  PetscCall(ReadWhole(comm, v, name, total, all));
  blobs.assign((size_t)writers, StateBlob());
  size_t off = 0;
  for (PetscInt r = 0; r < writers; r++) {
    const size_t n = (size_t)len[r];
    PetscCheck(all[off] == len[r], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s of rank %" PetscInt_FMT ": length %g, layout says %g", name.c_str(), r,
               (double)all[off], (double)len[r]);
    blobs[r].data.assign(all.begin() + off + 1, all.begin() + off + 1 + n);
    off += n + 1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The order of the integrator's carried derivative H (layout of H) in the layout of the state U:
   the state's order for a derivative of the whole state (DOPRI's FSAL stage), its first half's for
   one of half the state (Verlet's acceleration: dv/dt, laid out as the positions; every rank's
   half); NULL (the writer's layout) otherwise. Decided on the global sizes: a rank without
   particles (-fine_distribute 0) takes the same branch as the others (the IS is collective). */
static PetscErrorCode HistoryOrder(IS order, Vec H, Vec U, IS *horder)
{
  const PetscInt *idx;
  PetscInt        NH, NU, nh;
  PetscFunctionBeginUser;
  *horder = NULL;
  if (!order) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetSize(H, &NH));
  PetscCall(VecGetSize(U, &NU));
  PetscCall(VecGetLocalSize(H, &nh));
  if (NH == NU) {
    PetscCall(PetscObjectReference((PetscObject)order));
    *horder = order;
  } else if (2 * NH == NU) {
    PetscCall(ISGetIndices(order, &idx));
    PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)order), nh, idx, PETSC_COPY_VALUES, horder));
    PetscCall(ISRestoreIndices(order, &idx));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::PreStep(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSCheckpointPreStep(ts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every -checkpoint_interval of simulated time, or -checkpoint_wall_interval of wall time (rank 0's
   clock decides, for all ranks). */
PetscErrorCode TimeRun::CheckpointDue(PetscReal t, PetscBool *due)
{
  PetscFunctionBeginUser;
  *due = PETSC_FALSE;
  if (ckpt_interval_ > 0 && t >= ckpt_next_ * (1 - 1e-12)) *due = PETSC_TRUE;
  if (ckpt_wall_ > 0) {
    PetscLogDouble now;
    int            w;
    PetscCall(PetscTime(&now));
    if (ckpt_wall_last_ == 0) ckpt_wall_last_ = now;
    w = now - ckpt_wall_last_ >= ckpt_wall_;
    PetscCallMPI(MPI_Bcast(&w, 1, MPI_INT, 0, comm_));
    if (w) *due = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* checkpoint_<step>.h5 in the output directory, written as a temporary file and renamed (a crash
   while writing leaves the previous checkpoints whole), then linked as checkpoint.h5 (the latest,
   also by a rename). Attributes of "/": the format version, mode, ranks, integrator, time, step, next
   step size, step rejections, the step-size controller's type and history (adapt_type, adapt_state:
   hexadecimal floats), the sampler's position and the scene's fingerprint; datasets: state
   (the TS solution), integrator_history (ts_checkpoint.h; with has_history), run_state_layout (per
   rank, the length of its part of run_state) and run_state (per rank: the length, then the mode's
   StateBlob). */
PetscErrorCode TimeRun::WriteCheckpoint(PetscReal t, PetscInt step)
{
  PetscLogDouble t0, t1;
  PetscViewer    v;
  PetscMPIInt    rank, size;
  char           name[64];
  PetscFunctionBeginUser;
  if (!out_.ready) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(ev_ckpt_write_, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(PetscSNPrintf(name, sizeof name, "checkpoint_%08" PetscInt_FMT ".h5", step));
  const std::string path = out_.dir + "/" + name, tmp = path + ".tmp", latest = out_.dir + "/checkpoint.h5";
  PetscCall(PetscViewerHDF5Open(comm_, tmp.c_str(), FILE_MODE_WRITE, &v));
  {
    std::string integrator;
    PetscInt    ival;
    PetscReal   dt;
    PetscInt    sample, snapshot, rej;
    PetscCall(IntegratorName(ts_, &integrator));
    PetscCall(TSGetTimeStep(ts_, &dt));
    PetscCall(TSGetStepRejections(ts_, &rej));
    sampler_.Position(&sample, &snapshot);
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "format_version", PETSC_INT, &kCheckpointVersion));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "mode", PETSC_STRING, mode_.c_str()));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "integrator", PETSC_STRING, integrator.c_str()));
    ival = size;
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "ranks", PETSC_INT, &ival));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "time", PETSC_REAL, &t));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "step", PETSC_INT, &step));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "dt_next", PETSC_REAL, &dt));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "rejections", PETSC_INT, &rej));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "next_sample", PETSC_INT, &sample));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "next_snapshot", PETSC_INT, &snapshot));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "t_final", PETSC_REAL, &t_final_)); /* the sampling schedule */
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "samples", PETSC_INT, &out_.samples));
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "snapshots", PETSC_INT, &out_.snapshots));
    {
      /* the step-size controller's history, as exact hexadecimal floats */
      const char *type;
      PetscInt    na;
      PetscReal   a[TS_CHECKPOINT_ADAPT_MAX];
      std::string text;
      char        num[64];
      PetscCall(TSCheckpointGetAdaptState(ts_, &type, &na, a));
      for (PetscInt k = 0; k < na; k++) {
        std::snprintf(num, sizeof num, "%a", (double)a[k]);
        text += (k ? " " : "") + std::string(num);
      }
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "adapt_type", PETSC_STRING, type));
      PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "adapt_state", PETSC_STRING, text.c_str()));
    }
    std::vector<std::pair<std::string, std::string>> fp;
    PetscCall(CheckpointFingerprint(fp));
    for (auto &kv : fp) PetscCall(PetscViewerHDF5WriteAttribute(v, "/", ("fingerprint_" + kv.first).c_str(), PETSC_STRING, kv.second.c_str()));
  }
  {
    /* a plain copy of the state: a DM's own VecView (DMPlex: FE^2) writes its field layout and the
       TS's output sequence number, which VecLoad then expects back */
    Vec S;
    IS  order;
    PetscCall(PlainCopy(U_, &S));
    PetscCall(StateOrder(&order));
    if (order) PetscCall(Permute(U_, S, order, SCATTER_FORWARD));
    PetscCall(VecView(S, v));
    PetscCall(VecDestroy(&S));
    Vec      H, Hc;
    PetscInt has;
    PetscCall(TSCheckpointGetHistory(ts_, &H));
    has = H ? 1 : 0;
    PetscCall(PetscViewerHDF5WriteAttribute(v, "/", "has_history", PETSC_INT, &has));
    if (H) { /* a derivative of the state (DOPRI's FSAL stage, Verlet's acceleration) in the state's order too */
      IS horder;
      PetscCall(PlainCopy(H, &Hc, "integrator_history"));
      PetscCall(HistoryOrder(order, H, U_, &horder));
      if (horder) PetscCall(Permute(H, Hc, horder, SCATTER_FORWARD));
      PetscCall(ISDestroy(&horder));
      PetscCall(VecView(Hc, v));
      PetscCall(VecDestroy(&Hc));
    }
    PetscCall(ISDestroy(&order));
  }
  {
    StateBlob blob, global;
    PetscCall(SaveState(t, U_, blob));
    PetscCall(WriteRankBlobs(comm_, v, "run_state", blob));
    PetscInt nu;
    PetscCall(VecGetLocalSize(U_, &nu));
    PetscCall(WriteRankValue(comm_, v, "state_layout", nu)); /* the state's distribution (a restart on another one reads global_state) */
    PetscCall(SaveGlobalState(t, U_, global));
    PetscCall(WriteRankBlobs(comm_, v, "global_state", global));
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscReal bytes  = 0;
  int       failed = 0;
  if (rank == 0) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (!ec) {
      const std::string link = latest + ".tmp";
      fs::remove(link, ec);
      fs::create_hard_link(path, link, ec);
      if (ec) fs::copy_file(path, link, fs::copy_options::overwrite_existing, ec);
      if (!ec) fs::rename(link, latest, ec);
    }
    failed = ec ? 1 : 0;
    if (!failed) bytes = (PetscReal)fs::file_size(path, ec);
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm_));
  PetscCheck(!failed, comm_, PETSC_ERR_FILE_WRITE, "Checkpoint: cannot rename %s to %s and link it as %s", tmp.c_str(), path.c_str(), latest.c_str());
  PetscCallMPI(MPI_Bcast(&bytes, 1, MPIU_REAL, 0, comm_));
  PetscCall(PetscTime(&t1));
  ckpt_seconds_ += t1 - t0;
  ckpt_bytes_     = bytes;
  ckpt_wall_last_ = t1;
  ckpt_last_step_ = step;
  ckpt_count_++;
  if (ckpt_interval_ > 0) ckpt_next_ = ckpt_interval_ * (std::floor(t / ckpt_interval_ * (1 + 1e-12)) + 1); /* the next multiple after t */
  PetscCall(PetscInfo(ts_, "Checkpoint %s at t = %g (step %" PetscInt_FMT "): %.0f bytes in %.3f s\n", path.c_str(), (double)t, step, (double)bytes, t1 - t0));
  PetscCall(PetscLogEventEnd(ev_ckpt_write_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The first message of an error raised while the checkpoint is read (the read errors are
   reported as one message naming the option and the file). */
static PetscErrorCode KeepFirstError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess,
                                     void *ctx)
{
  std::string *first = (std::string *)ctx;
  if (!first->empty()) return n;
  /* a state that does not fit this run (raised by the LoadState hooks) or a file that cannot be read */
  *first = std::string(n == PETSC_ERR_FILE_UNEXPECTED ? "U:" : "R:") + (mess && mess[0] ? mess : std::string("error in ") + (fun ? fun : "?"));
  return n;
}

/* A string attribute of the checkpoint's root group. */
static PetscErrorCode ReadStringAttribute(PetscViewer v, const std::string &name, std::string *value)
{
  char *str = NULL;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", name.c_str(), PETSC_STRING, NULL, &str));
  *value = str;
  PetscCall(PetscFree(str));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::ReadCheckpointFile(PetscViewer v, std::string *problem)
{
  PetscInt    version = -1, ranks = 0, step = 0, rej = 0, sample = 0, snapshot = 0, has = 0;
  PetscReal   t = 0, dt = 0;
  PetscMPIInt size, rank;
  char       *str = NULL;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  {
    PetscBool has_version;
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "format_version", &has_version));
    if (!has_version) {
      *problem = "not a turgor checkpoint (no format_version)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "format_version", PETSC_INT, NULL, &version));
  if (version != kCheckpointVersion) {
    *problem = "checkpoint format version " + std::to_string((long long)version) + "; this turgor reads version " +
               std::to_string((long long)kCheckpointVersion);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  std::string mode;
  PetscCall(ReadStringAttribute(v, "mode", &mode));
  if (mode != mode_) {
    *problem = "written by -mode " + mode + ", this run is -mode " + mode_;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "ranks", PETSC_INT, NULL, &ranks));
  bool other_ranks = false;
  if (ranks != size) {
    std::string why;
    if (!RestartsOnOtherRanks(&why)) {
      *problem = "written on " + std::to_string((long long)ranks) + " MPI ranks, this run has " + std::to_string((long long)size) +
                 " (restart on the same number of ranks: " + why + ")";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    other_ranks = true;
  } else {
    /* the same rank count, another distribution of the state (-fine_distribute 0 against 1): the
       per-rank run_state does not fit either */
    PetscBool present;
    PetscCall(PetscViewerHDF5HasDataset(v, "state_layout", &present));
    if (present) {
      std::vector<PetscReal> sizes;
      PetscInt               n;
      int                    differs;
      PetscCall(ReadWhole(comm_, v, "state_layout", ranks, sizes));
      PetscCall(VecGetLocalSize(U_, &n));
      differs = (PetscInt)sizes[rank] != n;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &differs, 1, MPI_INT, MPI_MAX, comm_));
      if (differs) {
        std::string why;
        if (!RestartsOnOtherRanks(&why)) {
          *problem = "its state is distributed over the ranks otherwise than this run's (" + why + ")";
          PetscFunctionReturn(PETSC_SUCCESS);
        }
        other_ranks = true;
      }
    }
  }
  {
    std::vector<std::pair<std::string, std::string>> fp;
    std::string                                      diff;
    PetscCall(CheckpointFingerprint(fp));
    for (auto &kv : fp) {
      PetscBool   present;
      std::string theirs = "(none)";
      PetscCall(PetscViewerHDF5HasAttribute(v, "/", ("fingerprint_" + kv.first).c_str(), &present));
      if (present) { PetscCall(ReadStringAttribute(v, "fingerprint_" + kv.first, &theirs)); }
      if (theirs != kv.second) diff += (diff.empty() ? "" : "; ") + kv.first + " " + theirs + " in the checkpoint, " + kv.second + " in this scene";
    }
    if (!diff.empty()) {
      *problem = "the checkpoint is from another scene: " + diff + " (give the scene options of the run that wrote it)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    std::string ours;
    PetscCall(IntegratorName(ts_, &ours));
    std::string theirs;
    PetscCall(ReadStringAttribute(v, "integrator", &theirs));
    if (theirs != ours) {
      *problem = "integrated with -ts_type " + theirs + ", this run with " + ours + " (give the same integrator)";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "time", PETSC_REAL, NULL, &t));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "step", PETSC_INT, NULL, &step));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "dt_next", PETSC_REAL, NULL, &dt));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "rejections", PETSC_INT, NULL, &rej));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "next_sample", PETSC_INT, NULL, &sample));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "next_snapshot", PETSC_INT, NULL, &snapshot));
  PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "has_history", PETSC_INT, NULL, &has));
  if (!(t < t_final_)) {
    *problem = "written at t = " + std::to_string((double)t) + " µs, not before -ts_max_time = " + std::to_string((double)t_final_) +
               " µs: nothing to continue";
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  IS order;
  PetscCall(StateOrder(&order));
  {
    Vec S;
    PetscCall(PlainCopy(U_, &S));
    PetscCall(VecLoad(S, v));
    if (order) PetscCall(Permute(U_, S, order, SCATTER_REVERSE));
    else PetscCall(VecCopy(S, U_));
    PetscCall(VecDestroy(&S));
    PetscCall(ISDestroy(&order));
  }
  PetscCall(TSSetTime(ts_, t));
  PetscCall(TSSetStepNumber(ts_, step));
  PetscCall(TSSetTimeStep(ts_, dt));
  PetscCall(TSCheckpointSetRejections(ts_, rej));
  {
    PetscBool present;
    PetscCall(PetscViewerHDF5HasAttribute(v, "/", "adapt_state", &present));
    if (present) { /* (a checkpoint of an earlier turgor has none: the controller starts afresh) */
      const char            *ours;
      PetscInt               na;
      PetscReal              a[TS_CHECKPOINT_ADAPT_MAX];
      std::vector<PetscReal> theirs;
      PetscCall(TSCheckpointGetAdaptState(ts_, &ours, &na, a));
      std::string type;
      PetscCall(ReadStringAttribute(v, "adapt_type", &type));
      if (type != ours) {
        *problem = "integrated with -ts_adapt_type " + type + ", this run with " + ours + " (give the same step-size controller)";
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "adapt_state", PETSC_STRING, NULL, &str));
      for (char *p = str, *end; *p; p = end) {
        const double x = std::strtod(p, &end);
        if (end == p) break;
        theirs.push_back((PetscReal)x);
      }
      PetscCall(PetscFree(str));
      PetscCheck(theirs.size() <= TS_CHECKPOINT_ADAPT_MAX, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "adapt_state: %zu numbers", theirs.size());
      PetscCall(TSCheckpointSetAdaptState(ts_, (PetscInt)theirs.size(), theirs.data()));
    }
  }
  if (has) {
    PetscInt n;
    Vec      H;
    PetscCall(TSCheckpointHistorySize(ts_, &n));
    PetscCall(VecCreateMPI(comm_, n, PETSC_DETERMINE, &H));
    PetscCall(PetscObjectSetName((PetscObject)H, "integrator_history"));
    PetscCall(VecLoad(H, v));
    IS horder;
    PetscCall(StateOrder(&order));
    PetscCall(HistoryOrder(order, H, U_, &horder));
    if (horder) { /* written in the state's order */
      Vec Hl;
      PetscCall(VecDuplicate(H, &Hl));
      PetscCall(Permute(Hl, H, horder, SCATTER_REVERSE));
      PetscCall(TSCheckpointSetHistory(ts_, Hl));
      PetscCall(VecDestroy(&Hl));
    } else PetscCall(TSCheckpointSetHistory(ts_, H));
    PetscCall(VecDestroy(&H));
    PetscCall(ISDestroy(&horder));
    PetscCall(ISDestroy(&order));
  }
  restart_tip_rows_ = sample; /* the rows written up to the checkpoint */
  {
    /* another -ts_max_time or sample count (a run extended): the samples follow this run's
       schedule from the first one after t (the rows already written stay) */
    PetscReal tf = t_final_;
    PetscInt  ns = out_.samples, nsn = out_.snapshots;
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "t_final", PETSC_REAL, &t_final_, &tf));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "samples", PETSC_INT, &out_.samples, &ns));
    PetscCall(PetscViewerHDF5ReadAttribute(v, "/", "snapshots", PETSC_INT, &out_.snapshots, &nsn));
    if (tf != t_final_ || ns != out_.samples || nsn != out_.snapshots) {
      const PetscReal u = (t + 1e-9 * t_final_) / t_final_; /* the sampler's tolerance */
      sample            = (PetscInt)std::floor(u * out_.samples) + 1;
      snapshot          = out_.snapshots > 0 ? (PetscInt)std::floor(u * out_.snapshots) + 1 : 0;
      PetscCall(PetscPrintf(comm_,
                            "Restart at t = %g µs: -ts_max_time or the sample counts differ from the checkpoint's run (%g µs, %" PetscInt_FMT
                            " samples): the samples continue on this run's schedule\n",
                            (double)t, (double)tf, ns));
    }
  }
  sampler_.SetPosition(sample, snapshot);
  if (other_ranks) { /* the run_state is per rank: every rank reads every writer's global_state */
    std::vector<StateBlob> blobs;
    PetscBool              present;
    PetscCall(PetscViewerHDF5HasDataset(v, "global_state", &present));
    if (!present) {
      *problem = "written on " + std::to_string((long long)ranks) + " MPI ranks by a turgor without the rank-independent state (global_state); restart on " +
                 std::to_string((long long)ranks) + " ranks";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(ReadAllRankBlobs(comm_, v, "global_state", ranks, blobs));
    PetscCall(LoadStateOtherRanks(t, U_, blobs));
  } else {
    StateBlob blob;
    PetscCall(ReadRankBlob(comm_, v, "run_state", blob));
    PetscCall(LoadState(t, U_, blob));
    PetscCheck(blob.Done(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "run_state of rank %d: %zu numbers more than this run reads", rank,
               blob.data.size() - blob.pos);
  }
  restart_step_   = step;
  ckpt_last_step_ = step;
  t_last_         = t;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -restart: the file must exist, be a whole HDF5 checkpoint of this format, mode, rank count,
   scene and integrator; anything else is refused naming the option and the file. */
PetscErrorCode TimeRun::ReadCheckpoint()
{
  const char *file = restart_file_.c_str();
  PetscMPIInt rank;
  int         exists = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_ckpt_read_, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    std::error_code ec;
    exists = std::filesystem::is_regular_file(restart_file_, ec) ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, comm_));
  PetscCheck(exists, comm_, PETSC_ERR_FILE_OPEN, "Option -restart %s: no such checkpoint file", file);
  std::string    first, problem;
  PetscViewer    v = NULL;
  PetscErrorCode ierr;
  H5E_auto2_t    hfunc;
  void          *hdata;
  H5Eget_auto2(H5E_DEFAULT, &hfunc, &hdata);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* HDF5's own error stack would bury the message */
  PetscCall(PetscPushErrorHandler(KeepFirstError, &first));
  ierr = PetscViewerHDF5Open(comm_, file, FILE_MODE_READ, &v);
  if (!ierr) ierr = ReadCheckpointFile(v, &problem);
  if (v) (void)PetscViewerDestroy(&v);
  PetscCall(PetscPopErrorHandler());
  H5Eset_auto2(H5E_DEFAULT, hfunc, hdata);
  {
    int bad = ierr ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_));
    const bool unfit = first.compare(0, 2, "U:") == 0;
    PetscCheck(!bad, comm_, PETSC_ERR_FILE_READ, "Option -restart %s: %s: %s", file,
               unfit ? "the checkpoint's state does not fit this run (another scene or other options?)"
                     : "cannot read the checkpoint (truncated, damaged or not a turgor checkpoint)",
               first.empty() ? "read error on another rank" : first.c_str() + 2);
  }
  PetscCheck(problem.empty(), comm_, PETSC_ERR_ARG_INCOMP, "Option -restart %s: %s", file, problem.c_str());
  PetscCall(PetscLogEventEnd(ev_ckpt_read_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
