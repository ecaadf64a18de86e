#include <turgor/coarse/fe2_run.h>
#include <turgor/fine/fine_run.h>
#include <turgor/core/log.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/radau_iia.h>
#include <cmath>
#include <cstring>

namespace turgor {

FE2Run::~FE2Run()
{
  (void)TSDestroy(&ts_);
  (void)VecDestroy(&U_);
  (void)MatDestroy(&J_);
}

PetscErrorCode FE2Run::SetFromOptions()
{
  PetscFunctionBeginUser;
  /* FE^2 default for the material points' accuracy (an RVE's Psi-tc tolerance): 1e-9 rather than
     the seed's 1e-12 (-mode rve keeps 1e-12). On the bending bar the tip history moves by 2.7e-6 µm,
     far below the coarse tolerance, for 1.5x less time (docs/benchmarks.md); -rve_psi_atol and
     -rve_psi_steptol override it. */
  model_.Pool().SetDefaultTolerance(1e-9);
  PetscCall(load_.SetFromOptions(comm_));
  model_.SetLoad(load_);
  PetscCall(model_.SetFromOptions());
  PetscOptionsBegin(comm_, "fe2_", "Coarse FE^2 run (-mode fe2)", "turgor");
  PetscCall(PetscOptionsInt("-tip_samples", "Samples of the tip displacement in tip.csv over [0, ts_max_time] (by TS interpolation)", "FE2Run", tip_samples_, &tip_samples_, NULL));
  PetscCall(PetscOptionsInt("-snapshots", "Coarse field snapshots (HDF5 + XDMF) over [0, ts_max_time]; 0 = none", "FE2Run", snapshots_, &snapshots_, NULL));
  PetscCall(PetscOptionsReal("-progress_interval", "Seconds of wall time between progress lines; 0 = none", "FE2Run", progress_interval_, &progress_interval_, NULL));
  PetscCall(PetscOptionsInt("-jacobian_max_age", "Reuse the material tangents (K, C) for this many accepted steps; 0: fresh at every Jacobian request; -1: 0 for radau5 (which decides itself), 10 otherwise", "FE2Run", jacobian_max_age_, &jacobian_max_age_, NULL));
  PetscOptionsEnd();
  PetscCheck(tip_samples_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_tip_samples = %" PetscInt_FMT ": must be >= 1", tip_samples_);
  PetscCheck(snapshots_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_snapshots = %" PetscInt_FMT ": must be >= 0", snapshots_);
  PetscCall(OutputDirectory(comm_, &output_dir_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::SetUp()
{
  PetscMPIInt size, rank;
  PetscBool   user_reuse = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(RegisterLogStage("FE2 setup", &stage_setup_));
  PetscCall(RegisterLogStage("FE2 solve", &stage_solve_));
  PetscCall(PetscLogStagePush(stage_setup_));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));

  PetscCall(model_.SetUp());
  PetscCall(model_.CreateGlobalVector(&U_));
  PetscCall(PetscObjectSetName((PetscObject)U_, "state"));
  PetscCall(VecZeroEntries(U_));
  PetscCall(MatDuplicate(model_.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &J_));

  PetscCall(TSCreate(comm_, &ts_));
  PetscCall(TSSetApplicationContext(ts_, this));
  PetscCall(TSSetDM(ts_, model_.GetDM()));
  PetscCall(TSSetProblemType(ts_, TS_NONLINEAR));
  PetscCall(TSSetType(ts_, TSRADAUIIA)); /* the seed's best method */
  {
    /* Defaults measured on the bending bar (docs/benchmarks.md): the DSP step controller (fewer
       rejections than basic on the oscillating response), and for radau5 RADAU5's advice for
       expensive Jacobians (material tangents): keep the Jacobian while Newton contracts by 0.1. */
    TSAdapt adapt;
    PetscCall(TSGetAdapt(ts_, &adapt));
    PetscCall(TSAdaptSetType(adapt, TSADAPTDSP));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-ts_radauiia_jacobian_reuse", &user_reuse));
    if (!user_reuse) PetscCall(PetscOptionsSetValue(NULL, "-ts_radauiia_jacobian_reuse", "0.1"));
  }
  PetscCall(TSSetTolerances(ts_, 1e-3, NULL, 1e-3, NULL));
  PetscCall(TSSetMaxTime(ts_, kBendingBarFinalTime));
  PetscCall(TSSetMaxSteps(ts_, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTimeStep(ts_, 0.1));
  PetscCall(TSSetErrorIfStepFails(ts_, PETSC_FALSE));
  PetscCall(TSSetMaxSNESFailures(ts_, -1)); /* a failed nonlinear solve rejects the step, always */
  PetscCall(TSSetMaxStepRejections(ts_, 50));
  PetscCall(TSSetFunctionDomainError(ts_, CheckDomain));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSMonitorSet(ts_, Monitor, this, NULL));
  {
    SNES snes;
    KSP  ksp;
    PC   pc;
    PetscCall(TSGetSNES(ts_, &snes));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
    if (size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  PetscCall(TSSetFromOptions(ts_));
  if (!user_reuse) PetscCall(PetscOptionsClearValue(NULL, "-ts_radauiia_jacobian_reuse")); /* our default, consumed (or moot) */
  PetscCall(TSGetMaxTime(ts_, &t_final_));
  PetscCheck(t_final_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_max_time = %g: must be > 0", (double)t_final_);
  {
    /* explicit methods integrate Udot = Mt^-1 G(U); the others solve F(U, Udot) = 0 */
    TSType    type;
    PetscBool is_rk, is_euler, is_ssp, is_arkimex;
    PetscCall(TSGetType(ts_, &type));
    PetscCall(PetscStrcmp(type, TSRK, &is_rk));
    PetscCall(PetscStrcmp(type, TSEULER, &is_euler));
    PetscCall(PetscStrcmp(type, TSSSP, &is_ssp));
    PetscCall(PetscStrcmp(type, TSARKIMEX, &is_arkimex));
    PetscBool is_am;
    PetscCall(PetscStrcmp(type, TSAM, &is_am)); /* Adams-Moulton with functional iteration: needs f only */
    explicit_ = is_rk || is_euler || is_ssp || is_am;
    if (jacobian_max_age_ < 0) {
      PetscBool is_radau5;
      PetscCall(PetscStrcmp(type, TSRADAUIIA, &is_radau5));
      jacobian_max_age_ = is_radau5 ? 0 : 10; /* SNES asks at every Newton iteration; radau5 only when needed */
    }
    if (explicit_) PetscCall(TSSetRHSFunction(ts_, NULL, RHSFunction, this));
    else {
      PetscCall(TSSetIFunction(ts_, NULL, IFunction, this));
      PetscCall(TSSetIJacobian(ts_, J_, J_, IJacobian, this));
      PetscCall(TSSetEquationType(ts_, TS_EQ_IMPLICIT)); /* dF/dUdot = Mt, not the identity */
      if (is_arkimex) PetscCall(TSARKIMEXSetFullyImplicit(ts_, PETSC_TRUE));
    }
  }
  sampler_.Configure(t_final_, tip_samples_, snapshots_, progress_interval_);

  /* report */
  {
    TSType    type;
    PetscReal atol, rtol;
    PetscCall(TSGetType(ts_, &type));
    PetscCall(TSGetTolerances(ts_, &atol, NULL, &rtol, NULL));
    PetscCall(PetscPrintf(comm_, "turgor fe2: %" PetscInt_FMT " Q1 elements, %" PetscInt_FMT " material points (%s, selective reduced integration), %d MPI ranks in %" PetscInt_FMT " material-point groups\n", model_.NumElements(), model_.NumMaterialPoints(), model_.Pool().MaterialName(), size, model_.Pool().NumGroups()));
    PetscCall(PetscPrintf(comm_, "Reference density %.6g ng/µm^2, %s mass matrix\n", (double)model_.ReferenceDensity(), model_.LumpedMass() ? "lumped" : "consistent"));
    PetscCall(PetscPrintf(comm_, "Time integration: %s (%s form) to t = %g µs, rtol = %g, atol = %g\n", type, explicit_ ? "explicit, Udot = Mt^-1 G(U)" : "implicit, F(U, Udot) = Mt Udot - G(U)", (double)t_final_, (double)rtol, (double)atol));
  }
  if (rank == 0) PetscCall(tip_csv_.Open(PETSC_COMM_SELF, output_dir_ + "/tip.csv", {"time", "tip_displacement_y"}));
  if (snapshots_ > 0) PetscCall(fields_.Open(model_, output_dir_, "coarse"));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx)
{
  FE2Run   *run = (FE2Run *)ctx;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(run->model_.IFunction(U, Udot, F, &ok));
  if (!ok) { /* reject: the nonlinear solve fails and TS retries with a smaller step */
    SNES snes;
    PetscCall(TSGetSNES(ts, &snes));
    PetscCall(SNESSetFunctionDomainError(snes));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  FE2Run   *run = (FE2Run *)ctx;
  PetscBool ok;
  PetscInt  rej;
  PetscFunctionBeginUser;
  PetscCall(TSGetStepRejections(ts, &rej));
  const bool refresh = run->jacobian_max_age_ <= 0 || run->steps_since_refresh_ >= run->jacobian_max_age_ || rej != run->rejections_at_refresh_;
  if (refresh) {
    run->steps_since_refresh_   = 0;
    run->rejections_at_refresh_ = rej;
  }
  PetscCall(run->model_.IJacobian(U, shift, B, &ok, refresh));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::RHSFunction(TS ts, PetscReal t, Vec U, Vec G, void *ctx)
{
  FE2Run   *run = (FE2Run *)ctx;
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(run->model_.RHSFunction(U, G, &ok));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Called by TS on every stage before it is used: evaluating the materials here (cached for the
   function evaluation that follows) lets an explicit integrator reject a step whose stage makes a
   material point fail. Implicit integrators learn it from the nonlinear solve (domain error). */
PetscErrorCode FE2Run::CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept)
{
  FE2Run *run;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &run));
  *accept = PETSC_TRUE;
  if (!run->explicit_) PetscFunctionReturn(PETSC_SUCCESS); /* implicit: the nonlinear solve rejects */
  PetscCall(run->model_.EvaluateMaterials(U, false, accept, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::PostStep(TS ts)
{
  FE2Run *run;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &run));
  PetscCall(run->model_.CommitMaterials());
  run->steps_since_refresh_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::Observe(PetscReal t, Vec U)
{
  PetscReal uy;
  PetscFunctionBeginUser;
  PetscCall(model_.TipDisplacement(U, &uy));
  tip_final_ = uy;
  if (tip_csv_.IsOpen()) PetscCall(tip_csv_.Row({t, uy}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  FE2Run *run = (FE2Run *)ctx;
  PetscFunctionBeginUser;
  PetscCall(run->sampler_.Monitor(
    ts, step, t, U, [run](PetscReal tk, Vec X) { return run->Observe(tk, X); },
    [run](PetscReal tk, Vec X) -> PetscErrorCode {
      PetscBool ok;
      PetscFunctionBeginUser;
      PetscCall(run->model_.EvaluateMaterials(X, false, &ok, NULL)); /* the stresses at X */
      PetscCall(run->fields_.Write(run->model_, X, tk));
      PetscFunctionReturn(PETSC_SUCCESS);
    },
    run->model_.Counters().residuals));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::Solve()
{
  TSConvergedReason reason;
  PetscReal         t;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(stage_solve_));
  PetscCall(TSSolve(ts_, U_));
  wall_ = sampler_.Elapsed();
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCheck(reason >= 0, comm_, PETSC_ERR_NOT_CONVERGED, "FE2 run failed at t = %g µs (%s): steps were rejected %s; see the material-point failures above, or lower -ts_dt / tighten -ts_rtol", (double)t, TSConvergedReasons[reason], reason == TS_DIVERGED_STEP_REJECTED ? "more than -ts_max_reject times in a row" : "repeatedly");
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::WriteSummary()
{
  JsonObject  js;
  TSType      type;
  PetscReal   rtol, atol, t;
  PetscInt    steps, rej, snes_its, ksp_its;
  MaterialCounters rc;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts_, &type));
  std::string ts_type = type;
  if (ts_type == TSRK) {
    TSRKType rk;
    PetscCall(TSRKGetType(ts_, &rk));
    ts_type += std::string(" ") + rk;
  } else if (ts_type == TSARKIMEX) {
    TSARKIMEXType ark;
    PetscCall(TSARKIMEXGetType(ts_, &ark));
    ts_type += std::string(" ") + ark + " (fully implicit)";
  }
  PetscCall(TSGetTolerances(ts_, &atol, NULL, &rtol, NULL));
  PetscCall(TSGetSolveTime(ts_, &t));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetStepRejections(ts_, &rej));
  PetscCall(TSGetSNESIterations(ts_, &snes_its));
  PetscCall(TSGetKSPIterations(ts_, &ksp_its));
  PetscCall(model_.Pool().GlobalCounters(&rc));
  const CoarseCounters &cc = model_.Counters();
  /* particles: of one RVE, and in all RVEs together */
  PetscInt                       per[2];
  const std::vector<std::string> physics = model_.Pool().Model().Physics();
  model_.Pool().Model().ParticlesPerPoint(&per[0], &per[1]);
  const PetscInt npts = model_.NumMaterialPoints();

  js.Set("mode", "fe2");
  js.Set("ts_type", ts_type);
  js.Set("rtol", rtol);
  js.Set("atol", atol);
  js.Set("t_final", t);
  js.Set("steps", steps);
  js.Set("rejected_steps", rej);
  js.Set("rhs_evals", cc.residuals);
  js.Set("jacobian_evals", cc.tangent_evals);
  js.Set("wall_time_s", (PetscReal)wall_);
  js.Set("material", model_.Pool().MaterialName());
  js.Set("n_elements", model_.NumElements());
  js.Set("n_material_points", npts);
  js.Set("n_wall_particles", per[0] * npts);
  js.Set("n_fluid_particles", per[1] * npts);
  js.Set("rve_wall_particles", per[0]);
  js.Set("rve_fluid_particles", per[1]);
  js.Set("physics", physics);
  js.Set("rve_solves", rc.solves);
  js.Set("rve_tangent_solves", rc.tangent_solves);
  js.Set("psi_tc_iterations", rc.iterations);
  js.Set("rve_failures", rc.failures);
  js.Set("material_evaluations", cc.material_evals);
  js.Set("material_failures", cc.failures); /* evaluations in which some material point failed */
  js.Set("snes_its", snes_its);
  js.Set("ksp_its", ksp_its);
  js.Set("tip_displacement_final", tip_final_);
  {
    /* where the time went: material points (trial), their tangents, and the rest (integrator,
       coarse assembly and linear algebra, output) */
    PetscReal trial, tangents;
    PetscCall(model_.Pool().GlobalTimes(&trial, &tangents));
    js.Set("time_material_points_s", trial);
    js.Set("time_tangents_s", tangents);
    js.Set("time_integrator_and_linear_algebra_s", (PetscReal)wall_ - trial - tangents);
  }
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    js.Set("mpi_ranks", (PetscInt)size);
  }
  js.Set("pool_remote_bytes_per_evaluation", model_.Pool().RemoteBytesPerEvaluation());
  js.Set("snapshots", fields_.Count());
  PetscCall(js.Write(comm_, output_dir_ + "/summary.json"));
  PetscCall(PetscPrintf(comm_, "Done: t = %g µs, %" PetscInt_FMT " steps (%" PetscInt_FMT " rejected), %" PetscInt_FMT " function and %" PetscInt_FMT " Jacobian evaluations, %" PetscInt_FMT " RVE solves (%" PetscInt_FMT " for tangents), %.3f s wall; final tip displacement %.6g µm\nOutputs in %s: tip.csv, summary.json%s\n", (double)t, steps, rej, cc.residuals, cc.tangent_evals, rc.solves, rc.tangent_solves, (double)wall_, (double)tip_final_, output_dir_.c_str(), snapshots_ > 0 ? ", coarse.h5 + coarse.xmf" : ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
