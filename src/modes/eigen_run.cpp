#include <turgor/modes/eigen_run.h>
#include <turgor/analysis/explicit_stability.h>
#include <turgor/coarse/coarse_snapshot_reader.h>
#include <turgor/core/errors.h>
#include <turgor/core/log.h>
#include <cmath>
#include <cstring>

namespace turgor {

static const char *const kStates[] = {"reference", "relaxed", "snapshot"};

PetscErrorCode EigenSpec::SetFromOptions(MPI_Comm comm)
{
  char      state_name[64], file[PETSC_MAX_PATH_LEN];
  PetscBool state_set, file_set, largest_b = largest ? PETSC_TRUE : PETSC_FALSE, damping_b = damping ? PETSC_TRUE : PETSC_FALSE;
  PetscBool shapes_b = shapes ? PETSC_TRUE : PETSC_FALSE, time_set;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(state_name, kStates[(int)state], sizeof state_name));
  PetscCall(PetscStrncpy(file, snapshot_file.c_str(), sizeof file));
  PetscOptionsBegin(comm, "eigen_",
                    "Eigen analysis of the coarse stiffness (-mode eigen); its SLEPc solvers: -eigen_eps_*/-eigen_st_* (lowest modes), "
                    "-eigen_max_eps_*/-eigen_max_st_* (largest), -eigen_damped_pep_*/-eigen_damped_st_* (damped modes)",
                    "turgor");
  PetscCall(PetscOptionsString("-state",
                               "The state analysed: reference (u = 0), relaxed (static equilibrium under the scene's loads, by -mode fe2_static's load "
                               "stepping), snapshot (a coarse.h5 snapshot, -eigen_snapshot_file)",
                               "EigenSpec", state_name, state_name, sizeof state_name, &state_set));
  PetscCall(PetscOptionsInt("-modes", "Lowest eigenpairs computed (the EPS's nev)", "EigenSpec", modes, &modes, NULL));
  PetscCall(PetscOptionsBool("-largest", "Also the largest eigenvalue: omega_max, the explicit stability limit and the stiffness ratio", "EigenSpec", largest_b,
                             &largest_b, NULL));
  PetscCall(PetscOptionsBool("-damping",
                             "The damped modes (K + s C + s^2 M) phi = 0 with C from the material points' D^v (SLEPc PEP), and the highest mode's damping "
                             "ratio (DOPRI's step limit)",
                             "EigenSpec", damping_b, &damping_b, NULL));
  PetscCall(PetscOptionsBool("-mode_shapes", "Write the mode shapes to modes.h5/modes.xmf", "EigenSpec", shapes_b, &shapes_b, NULL));
  PetscCall(PetscOptionsString("-snapshot_file", "With -eigen_state snapshot: a coarse.h5 written by -mode fe2 or fe2_static on the same mesh", "EigenSpec",
                               file, file, sizeof file, &file_set));
  PetscCall(PetscOptionsReal("-snapshot_time", "With -eigen_state snapshot: the time of the snapshot (default: the last one)", "EigenSpec", snapshot_time,
                             &snapshot_time, &time_set));
  PetscOptionsEnd();
  {
    bool known = false;
    for (int s = 0; s < 3; s++)
      if (!std::strcmp(state_name, kStates[s])) {
        state = (EigenState)s;
        known = true;
      }
    PetscCheck(known, comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option -eigen_state = %s: unknown state (known: reference, relaxed, snapshot)", state_name);
  }
  if (file_set && !state_set) state = EigenState::Snapshot; /* a file says which state */
  PetscCheck(modes >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -eigen_modes = %" PetscInt_FMT ": the number of modes must be >= 1", modes);
  PetscCheck(!time_set || std::isfinite(snapshot_time), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -eigen_snapshot_time = %g: must be finite",
             (double)snapshot_time);
  PetscCheck(state == EigenState::Snapshot || !file_set, comm, PETSC_ERR_ARG_INCOMP,
             "Option -eigen_snapshot_file = %s: only read with -eigen_state snapshot (here -eigen_state %s)", file, state_name);
  PetscCheck(state == EigenState::Snapshot || !time_set, comm, PETSC_ERR_ARG_INCOMP,
             "Option -eigen_snapshot_time = %g: only read with -eigen_state snapshot (here -eigen_state %s)", (double)snapshot_time, state_name);
  PetscCheck(state != EigenState::Snapshot || file[0], comm, PETSC_ERR_ARG_WRONG,
             "Option -eigen_snapshot_file: -eigen_state snapshot needs the file (a coarse.h5 of -mode fe2 or fe2_static)");
  snapshot_file     = file;
  has_snapshot_time = time_set;
  largest           = largest_b;
  damping           = damping_b;
  shapes            = shapes_b;
  PetscFunctionReturn(PETSC_SUCCESS);
}

EigenRun::~EigenRun()
{
  PetscCallVoid(VecDestroy(&U_));
}

PetscErrorCode EigenRun::SetFromOptions()
{
  PetscFunctionBeginUser;
  /* the output directory first: an option refused below then leaves a summary.json that says so */
  PetscCall(PrepareOutputDirectory());
  PetscCall(spec_.SetFromOptions(comm_));
  if (spec_.state == EigenState::Relaxed) {
    /* the relaxed state is -mode fe2_static's answer: its run, options and outputs (tip.csv, the
       relaxed state in coarse.h5) */
    static_ = std::make_unique<FE2StaticRun>(comm_);
    static_->ShareOutputDirectory(*this);
    PetscCall(static_->SetFromOptions());
    model_ = &static_->Model();
  } else {
    own_   = std::make_unique<CoarseModel>(comm_);
    model_ = own_.get();
    model_->Pool().SetDefaultTolerance(1e-9); /* as the FE^2 modes */
    PetscCall(load_.SetFromOptions(comm_));
    PetscCall(load_.RequireUnscheduled(comm_, "eigen"));
    model_->SetLoad(load_);
    PetscCall(model_->SetFromOptions());
    PetscCall(model_->Spec().RequireNoBoundaryGradient(comm_, "eigen at -eigen_state reference or snapshot"));
  }
  /* D^v only for the damped modes */
  model_->Pool().Tangent().viscosity = spec_.damping;
  /* the solvers and their options (defaults through the API: residuals well below 1e-8) */
  PetscCall(lowest_.SetFromOptions("eigen_", PencilEnd::Lowest, spec_.modes, 1e-10));
  if (spec_.largest) PetscCall(largest_.SetFromOptions("eigen_max_", PencilEnd::Largest, 1, 1e-10));
  if (spec_.damping) PetscCall(damped_.SetFromOptions("eigen_damped_", spec_.modes, 1e-10));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EigenRun::SetUp()
{
  PetscFunctionBeginUser;
  PetscCall(RegisterLogStage("eigen setup", &stage_setup_));
  PetscCall(RegisterLogStage("eigen solve", &stage_solve_));
  PetscCall(PetscLogEventRegister("TgEigenAssemble", PETSC_OBJECT_CLASSID, &ev_assemble_));
  PetscCall(PetscLogEventRegister("TgOutput", PETSC_OBJECT_CLASSID, &ev_output_));
  PetscCall(PetscLogStagePush(stage_setup_));
  if (static_) PetscCall(static_->SetUp());
  else PetscCall(model_->SetUp());
  ops_ = std::make_unique<CoarseOperators>(*model_);
  PetscCall(ops_->SetUp());
  {
    const PetscInt nev = lowest_.Requested();
    PetscCheck(nev <= ops_->Size(), comm_, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -eigen_modes (or -eigen_eps_nev) = %" PetscInt_FMT ": the model has only %" PetscInt_FMT " free displacement dofs", nev, ops_->Size());
  }
  PetscCall(model_->CreateGlobalVector(&U_));
  PetscCall(PetscObjectSetName((PetscObject)U_, "state"));
  PetscCall(VecZeroEntries(U_));
  if (spec_.state == EigenState::Snapshot && HasOutputDirectory()) { /* read (and checked) before any work; not under -help */
    CoarseSnapshotRequest req;
    req.path        = spec_.snapshot_file;
    req.has_time    = spec_.has_snapshot_time;
    req.time        = spec_.snapshot_time;
    req.file_option = "-eigen_snapshot_file";
    req.time_option = "-eigen_snapshot_time";
    PetscCall(ReadCoarseSnapshot(*model_, req, U_, &state_time_));
  }
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCall(PetscPrintf(comm_,
                          "turgor eigen: %" PetscInt_FMT " elements, %" PetscInt_FMT " material points (%s, %s), %" PetscInt_FMT
                          " free displacement dofs, %d MPI ranks; state %s%s\n",
                          model_->NumElements(), model_->NumMaterialPoints(), model_->Pool().MaterialName(), model_->QuadratureDescription(), ops_->Size(),
                          size, kStates[(int)spec_.state], spec_.state == EigenState::Snapshot ? (" of " + spec_.snapshot_file).c_str() : ""));
    if (!static_) PetscCall(model_->Pool().Model().View(PETSC_VIEWER_STDOUT_(comm_)));
    PetscCall(PetscPrintf(comm_, "Lowest modes: %" PetscInt_FMT " of K phi = omega^2 M phi (%s mass)%s%s\n", lowest_.Requested(),
                          model_->LumpedMass() ? "lumped" : "consistent", spec_.largest ? "; the largest" : "",
                          spec_.damping ? "; damped modes with C from D^v" : ""));
  }
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EigenRun::Solve()
{
  PetscBool      ok;
  std::string    why;
  PetscLogDouble t1;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0_));
  if (static_) { /* its own stages and events */
    PetscCall(static_->Solve());
    PetscCall(static_->ConvergedState(U_));
    state_time_ = static_->LoadFactor();
    if (static_->Interrupted()) { /* SIGINT/SIGTERM: the load is not all on; no state to analyse */
      PetscLogDouble t1;
      PetscCall(PetscTime(&t1));
      wall_ = t1 - t0_;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(PetscLogStagePush(stage_solve_));
  PetscCall(PetscLogEventBegin(ev_assemble_, 0, 0, 0, 0));
  {
    PetscLogDouble a0;
    PetscCall(PetscTime(&a0));
    model_->SetEvaluationWhere(std::string("at the analysed ") + kStates[(int)spec_.state] + " state");
    PetscCall(ops_->Assemble(U_, spec_.damping, &ok, &why));
    PetscCheck(ok, comm_, PETSC_ERR_NOT_CONVERGED, "Material points failed at the analysed %s state (%s): no stiffness to analyse", kStates[(int)spec_.state],
               why.c_str());
    PetscCall(ops_->Symmetrize());
    PetscCall(PetscTime(&t1));
    assemble_time_ = t1 - a0;
  }
  PetscCall(PetscLogEventEnd(ev_assemble_, 0, 0, 0, 0));
  PetscCall(PetscPrintf(comm_, "K assembled in %.3f s; its asymmetry |K - K^T| / |K| = %.3g (finite-difference tangents), removed\n", (double)assemble_time_,
                        (double)ops_->Asymmetry()));
  PetscCall(lowest_.Solve(*ops_));
  PetscCheck(!lowest_.Pairs().empty(), comm_, PETSC_ERR_NOT_CONVERGED,
             "No eigenpair converged (%s, %" PetscInt_FMT " iterations): try -eigen_eps_max_it, -eigen_eps_ncv or -eigen_eps_target",
             lowest_.Description().c_str(), lowest_.Iterations());
  if ((PetscInt)lowest_.Pairs().size() < lowest_.Requested())
    PetscCall(PetscPrintf(comm_, "WARNING: %zu of %" PetscInt_FMT " eigenpairs converged\n", lowest_.Pairs().size(), lowest_.Requested()));
  PetscCall(PetscPrintf(comm_, "Lowest modes (%s, %" PetscInt_FMT " iterations, %.3f s):\n", lowest_.Description().c_str(), lowest_.Iterations(),
                        (double)lowest_.SolveTime()));
  PetscCall(
    PetscPrintf(comm_, "  %4s %16s %14s %14s %14s %10s %9s\n", "mode", "omega^2 [/µs^2]", "omega [rad/µs]", "f [MHz]", "period [µs]", "residual", "x share"));
  for (size_t k = 0; k < lowest_.Pairs().size(); k++) {
    const Eigenpair &p = lowest_.Pairs()[k];
    const PetscReal  w = p.lambda >= 0 ? std::sqrt(p.lambda) : NAN;
    PetscCall(PetscPrintf(comm_, "  %4zu %16.9g %14.8g %14.8g %14.8g %10.2e %9.3f%s\n", k + 1, (double)p.lambda, (double)w, (double)(w / (2 * PETSC_PI)),
                          (double)(2 * PETSC_PI / w), (double)p.residual, (double)p.x_fraction,
                          p.lambda < 0 ? "  (negative: K is not positive definite)" : ""));
  }
  if (spec_.largest) {
    PetscCall(largest_.Solve(*ops_));
    PetscCheck(!largest_.Pairs().empty(), comm_, PETSC_ERR_NOT_CONVERGED,
               "The largest eigenvalue did not converge (%s, %" PetscInt_FMT " iterations): try -eigen_max_eps_max_it or -eigen_max_eps_ncv",
               largest_.Description().c_str(), largest_.Iterations());
    omega_max_          = std::sqrt(PetscMax(largest_.Pairs().back().lambda, 0.0));
    omega_max_residual_ = largest_.Pairs().back().residual;
    if (spec_.damping) { /* the highest mode's modal damping ratio phi^T C phi / (2 omega phi^T M phi) */
      Vec         x, y;
      PetscScalar c, m;
      PetscCall(ops_->CreateVector(&x));
      PetscCall(VecDuplicate(x, &y));
      PetscCall(largest_.GetVector((PetscInt)largest_.Pairs().size() - 1, x));
      PetscCall(MatMult(ops_->C(), x, y));
      PetscCall(VecDot(x, y, &c));
      PetscCall(MatMult(ops_->M(), x, y));
      PetscCall(VecDot(x, y, &m));
      zeta_max_ = PetscRealPart(c) / (2 * omega_max_ * PetscRealPart(m));
      PetscCall(VecDestroy(&x));
      PetscCall(VecDestroy(&y));
    }
    std::string dopri;
    if (!std::isnan(zeta_max_)) {
      char buf[160];
      PetscCall(PetscSNPrintf(buf, sizeof buf, ", %.6g µs (DOPRI 5dp, with the highest mode's damping ratio %.4g)",
                              (double)DormandPrinceStepLimit(omega_max_, zeta_max_), (double)zeta_max_));
      dopri = buf;
    }
    PetscCall(PetscPrintf(comm_,
                          "Largest: omega_max = %.8g rad/µs (period %.6g µs; %s, %" PetscInt_FMT " iterations, %.3f s, residual %.2e); stiffness ratio "
                          "omega_max / omega_min = %.6g; explicit limits: 2 / omega_max = %.6g µs (central differences, undamped)%s\n",
                          (double)omega_max_, (double)(2 * PETSC_PI / omega_max_), largest_.Description().c_str(), largest_.Iterations(),
                          (double)largest_.SolveTime(), (double)omega_max_residual_, (double)(omega_max_ / OmegaMin()), (double)(2 / omega_max_),
                          dopri.c_str()));
  }
  if (spec_.damping) {
    PetscCall(damped_.Solve(*ops_));
    PetscCall(PetscPrintf(comm_, "Damped modes (%s, %" PetscInt_FMT " iterations, %.3f s):\n", damped_.Description().c_str(), damped_.Iterations(),
                          (double)damped_.SolveTime()));
    for (size_t k = 0; k < damped_.Values().size(); k++) {
      const DampedEigenvalue &v = damped_.Values()[k];
      PetscCall(PetscPrintf(comm_, "  %4zu s = %.8g %+.8g i /µs: damped period %.8g µs, damping ratio %.4g, backward error %.2e\n", k + 1, (double)v.re,
                            (double)v.im, (double)(v.im > 0 ? 2 * PETSC_PI / v.im : NAN), (double)v.Ratio(), (double)v.residual));
    }
  }
  PetscCall(PetscTime(&t1));
  wall_   = t1 - t0_;
  solved_ = true;
  if (HasOutputDirectory() && spec_.shapes) PetscCall(WriteModes());
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* modes.h5/.xmf: snapshot k - 1 at "time" k holds mode k (the vertex vector "mode") on the
   analysed state (its displacement, stress and acoustic field). */
PetscErrorCode EigenRun::WriteModes()
{
  CoarseFieldsWriter fields;
  PetscBool          ok;
  Vec                x, V;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_output_, 0, 0, 0, 0));
  PetscCall(ops_->CreateVector(&x));
  PetscCall(VecDuplicate(U_, &V));
  fields.AddVertexVector("mode", "µm (mode shape, largest 1)");
  PetscCall(fields.Open(*model_, OutputDir(), "modes"));
  PetscCall(model_->EvaluateCellStress(U_, &ok));
  for (size_t k = 0; k < lowest_.Pairs().size(); k++) {
    PetscCall(lowest_.GetVector((PetscInt)k, x));
    PetscCall(ops_->NormalizeShape(x));
    PetscCall(ops_->ToState(x, V));
    PetscCall(fields.Write(*model_, U_, (PetscReal)(k + 1), {V}));
  }
  PetscCall(fields.Close());
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&V));
  PetscCall(PetscLogEventEnd(ev_output_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal EigenRun::OmegaMin() const
{
  for (const Eigenpair &p : lowest_.Pairs())
    if (p.lambda > 0) return std::sqrt(p.lambda);
  return NAN;
}

/* The keys a run reports, completed or not (rank-local where it matters: not collective). */
PetscErrorCode EigenRun::AddSummary(JsonObject &js)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  js.Set("state", kStates[(int)spec_.state]);
  if (spec_.state == EigenState::Snapshot) {
    js.Set("snapshot_file", spec_.snapshot_file);
    js.Set("snapshot_time", state_time_);
  }
  if (spec_.state == EigenState::Relaxed) js.Set("load_factor", state_time_);
  js.Set("material", model_ ? model_->Pool().MaterialName() : "");
  js.Set("element", model_ ? model_->ElementName() : "");
  js.Set("quadrature", model_ ? model_->QuadratureName() : "");
  js.Set("lumped_mass", model_ ? model_->LumpedMass() : false);
  js.Set("n_elements", model_ ? model_->NumElements() : 0);
  js.Set("n_material_points", model_ ? model_->NumMaterialPoints() : 0);
  js.Set("n_dofs", ops_ ? ops_->Size() : 0);
  js.Set("mpi_ranks", (PetscInt)size);
  js.Set("body_force", std::vector<PetscReal>{static_ ? static_->Load().body_acceleration[0] : load_.body_acceleration[0],
                                              static_ ? static_->Load().body_acceleration[1] : load_.body_acceleration[1]});
  js.Set("modes_requested", lowest_.Requested());
  if (!solved_) PetscFunctionReturn(PETSC_SUCCESS);
  std::vector<PetscReal> lambda, omega, freq, period, res, xfrac;
  for (const Eigenpair &p : lowest_.Pairs()) {
    const PetscReal w = p.lambda >= 0 ? std::sqrt(p.lambda) : NAN;
    lambda.push_back(p.lambda);
    omega.push_back(w);
    freq.push_back(w / (2 * PETSC_PI));
    period.push_back(2 * PETSC_PI / w);
    res.push_back(p.residual);
    xfrac.push_back(p.x_fraction);
  }
  js.Set("modes_converged", (PetscInt)lowest_.Pairs().size());
  js.Set("eigenvalues", lambda);
  js.Set("omegas", omega);
  js.Set("frequencies", freq);
  js.Set("periods", period);
  js.Set("residual_norms", res);
  js.Set("x_fractions", xfrac);
  js.Set("positive_definite", lambda.front() > 0);
  js.Set("units", "eigenvalues omega^2 in 1/µs^2, omegas in rad/µs, frequencies in 1/µs (MHz), periods in µs");
  js.Set("solver", lowest_.Description());
  js.Set("iterations", lowest_.Iterations());
  js.Set("solve_time_s", lowest_.SolveTime());
  js.Set("stiffness_asymmetry", ops_->Asymmetry());
  js.Set("assemble_time_s", (PetscReal)assemble_time_);
  if (spec_.largest) {
    js.Set("omega_max", omega_max_);
    js.Set("period_min", 2 * PETSC_PI / omega_max_);
    js.Set("omega_max_residual", omega_max_residual_);
    js.Set("stiffness_ratio", omega_max_ / OmegaMin());
    js.Set("dt_limit_central_difference", 2 / omega_max_);
    js.Set("largest_solver", largest_.Description());
    js.Set("largest_iterations", largest_.Iterations());
    js.Set("largest_solve_time_s", largest_.SolveTime());
    if (spec_.damping) {
      js.Set("damping_ratio_omega_max", zeta_max_);
      js.Set("dt_limit_dopri", DormandPrinceStepLimit(omega_max_, zeta_max_));
    }
  }
  if (spec_.damping) {
    std::vector<PetscReal> re, im, ratio, dperiod, dres;
    for (const DampedEigenvalue &v : damped_.Values()) {
      re.push_back(v.re);
      im.push_back(v.im);
      ratio.push_back(v.Ratio());
      dperiod.push_back(v.im > 0 ? 2 * PETSC_PI / v.im : NAN);
      dres.push_back(v.residual);
    }
    js.Set("damped_real", re);
    js.Set("damped_imag", im);
    js.Set("damping_ratios", ratio);
    js.Set("damped_periods", dperiod);
    js.Set("damped_backward_errors", dres);
    js.Set("damped_solver", damped_.Description());
    js.Set("damped_iterations", damped_.Iterations());
  }
  js.Set("wall_time_s", (PetscReal)wall_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EigenRun::WriteSummary()
{
  JsonObject       js;
  MaterialCounters rc;
  PetscMPIInt      rank;
  PetscFunctionBeginUser;
  if (Interrupted()) {
    PetscCall(Summary(js, "interrupted"));
    char reason[160];
    PetscCall(PetscSNPrintf(reason, sizeof reason, "interrupted (SIGINT/SIGTERM) during the relaxed state's static solve, at load factor %g: no eigen analysis",
                            (double)state_time_));
    js.Set("reason", reason);
    PetscCall(WriteSummaryFile(js));
    PetscCall(PetscPrintf(comm_, "Interrupted during the relaxed state's static solve: no eigen analysis; outputs in %s: %s\n", OutputDir().c_str(),
                          OutputFiles().c_str()));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(Summary(js, "completed"));
  PetscCall(model_->Pool().GlobalCounters(&rc));
  PetscCall(model_->Pool().DescribePoints(js, model_->NumMaterialPoints()));
  js.Set("rve_solves", rc.solves);
  js.Set("rve_output_solves", rc.output_solves);
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  {
    /* eigen.csv before summary.json: a summary that says completed has every output written */
    CsvWriter csv;
    if (rank == 0) {
      PetscCall(csv.Open(PETSC_COMM_SELF, OutputPath("eigen.csv"),
                         {"mode", "eigenvalue", "omega", "frequency", "period", "residual_norm", "x_fraction", "iterations"}));
      for (size_t k = 0; k < lowest_.Pairs().size(); k++) {
        const Eigenpair &p = lowest_.Pairs()[k];
        const PetscReal  w = p.lambda >= 0 ? std::sqrt(p.lambda) : NAN;
        PetscCall(csv.Row({(PetscReal)(k + 1), p.lambda, w, w / (2 * PETSC_PI), 2 * PETSC_PI / w, p.residual, p.x_fraction, (PetscReal)lowest_.Iterations()}));
      }
    }
    PetscCall(CloseOutput(csv));
  }
  PetscCall(WriteSummaryFile(js));
  PetscCall(PetscPrintf(comm_, "Done: %zu modes, lowest omega^2 = %.8g /µs^2 (%s), %.3f s wall\nOutputs in %s: %s\n", lowest_.Pairs().size(),
                        (double)lowest_.Pairs().front().lambda,
                        lowest_.Pairs().front().lambda > 0 ? ("period " + std::to_string(2 * PETSC_PI / OmegaMin()) + " µs").c_str()
                                                           : "negative: K is not positive definite at this state",
                        (double)wall_, OutputDir().c_str(), OutputFiles().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EigenRun::AddFailure(const std::string &reason, JsonObject &js)
{
  PetscFunctionBeginUser;
  if (static_) PetscCall(static_->WriteFailure(reason, "failed")); /* its partial outputs, then our summary over its */
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
