#include <turgor/core/log.h>
#include <turgor/run/time_run.h>

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
  PetscCall(OutputDirectory(comm, &dir));
  PetscOptionsBegin(comm, prefix.c_str(), "Outputs of the run", "turgor");
  PetscCall(PetscOptionsInt("-tip_samples", "Samples of the tip displacement in tip.csv over [0, ts_max_time] (by TS interpolation)", "RunOutputSpec", samples,
                            &samples, NULL));
  PetscCall(PetscOptionsInt("-snapshots", "Field snapshots (HDF5 + XDMF) over [0, ts_max_time]; 0 = none", "RunOutputSpec", snapshots, &snapshots, NULL));
  PetscCall(PetscOptionsReal("-progress_interval", "Seconds of wall time between progress lines; 0 = none", "RunOutputSpec", progress_interval,
                             &progress_interval, NULL));
  PetscOptionsEnd();
  PetscCheck(samples >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -%stip_samples = %" PetscInt_FMT ": must be >= 1", prefix.c_str(), samples);
  PetscCheck(snapshots >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -%ssnapshots = %" PetscInt_FMT ": must be >= 0", prefix.c_str(), snapshots);
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
  PetscCall(ModeSetFromOptions());
  PetscCall(out_.SetFromOptions(comm_, mode_ + "_"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::SetUp()
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCall(RegisterLogStage((mode_ + " setup").c_str(), &stage_setup_));
  PetscCall(RegisterLogStage((mode_ + " solve").c_str(), &stage_solve_));
  PetscCall(PetscLogEventRegister("TgOutput", PETSC_OBJECT_CLASSID, &ev_output_));
  PetscCall(PetscLogStagePush(stage_setup_));
  PetscCheck(ts_, comm_, PETSC_ERR_ORDER, "SetFromOptions() must be called before SetUp()");
  PetscCall(SetUpModel());
  PetscCall(TSMonitorSet(ts_, Monitor, this, NULL));
  PetscCall(TSSetFromOptions(ts_));
  PetscCall(TSGetMaxTime(ts_, &t_final_));
  PetscCheck(t_final_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_max_time = %g: must be > 0", (double)t_final_);
  PetscCall(AfterTSSetFromOptions());
  sampler_.Configure(t_final_, out_.samples, out_.snapshots, out_.progress_interval);
  PetscCall(Report());
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) {
    std::vector<std::string> columns = {"time"};
    for (const std::string &c : ObservedColumns()) columns.push_back(c);
    PetscCall(tip_csv_.Open(PETSC_COMM_SELF, out_.dir + "/tip.csv", columns));
  }
  if (out_.snapshots > 0) PetscCall(OpenSnapshots());
  PetscCall(PetscLogStagePop());
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
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  TimeRun *run = (TimeRun *)ctx;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(run->ev_output_, 0, 0, 0, 0));
  PetscCall(run->sampler_.Monitor(
    ts, step, t, U, [run](PetscReal tk, Vec X) { return run->Sample(tk, X); }, [run](PetscReal tk, Vec X) { return run->WriteSnapshot(tk, X); },
    run->FunctionEvaluations()));
  PetscCall(PetscLogEventEnd(run->ev_output_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::Solve()
{
  TSConvergedReason reason;
  PetscReal         t;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(stage_solve_));
  PetscCall(TSSolve(ts_, U_));
  wall_ = sampler_.Elapsed();
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCheck(reason >= 0, comm_, PETSC_ERR_NOT_CONVERGED, "The %s run failed at t = %g µs (%s): %s", mode_.c_str(), (double)t, TSConvergedReasons[reason],
             FailureAdvice());
  PetscCall(AfterSolve());
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TimeRun::WriteSummary()
{
  JsonObject  js;
  TSType      type;
  PetscReal   rtol, atol, t;
  PetscInt    steps, rej, evals = FunctionEvaluations();
  PetscMPIInt size;
  PetscBool   is_rk, is_arkimex;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts_, &type));
  std::string ts_type = type;
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
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetStepRejections(ts_, &rej));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &evals, 1, MPIU_INT, MPI_MAX, comm_));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  js.Set("mode", mode_);
  js.Set("ts_type", ts_type);
  js.Set("rtol", rtol);
  js.Set("atol", atol);
  js.Set("t_final", t);
  js.Set("steps", steps);
  js.Set("rejected_steps", rej);
  js.Set("rhs_evals", evals);
  js.Set("wall_time_s", (PetscReal)wall_);
  PetscCall(AddSummary(js));
  js.Set("tip_displacement_final", observed_);
  js.Set("mpi_ranks", (PetscInt)size);
  js.Set("snapshots", SnapshotCount());
  PetscCall(js.Write(comm_, out_.dir + "/summary.json"));
  std::string details;
  PetscCall(DoneDetails(&details));
  PetscCall(PetscPrintf(comm_,
                        "Done: t = %g µs, %" PetscInt_FMT " steps (%" PetscInt_FMT
                        " rejected), %s, %.3f s wall; final tip displacement %.6g µm\nOutputs in %s: tip.csv, summary.json%s\n",
                        (double)t, steps, rej, details.c_str(), (double)wall_, (double)observed_, out_.dir.c_str(),
                        out_.snapshots > 0 ? (std::string(", ") + SnapshotFiles()).c_str() : ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
