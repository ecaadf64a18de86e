#include <turgor/analysis/stability_monitor.h>
#include <cmath>

namespace turgor {

StabilityMonitor::~StabilityMonitor()
{
  for (Vec *v : {&U_prev_, &mode_prev_, &work_, &x_}) PetscCallVoid(VecDestroy(v));
}

PetscErrorCode StabilityMonitor::SetFromOptions(const std::string &prefix, const char *unit, const char *abscissa)
{
  const std::string every_opt = "-" + prefix + "eigen_monitor", modes_opt = every_opt + "_modes";
  const std::string every_help = std::string("Every this many ") + unit +
                                 ", the lowest eigenvalues of the stiffness K (with M as the metric) at the current state; the first " +
                                 "crossing of zero (loss of stability) is reported, interpolated, and its states written to stability.h5/.xmf; 0: off";
  PetscFunctionBeginUser;
  prefix_   = prefix;
  unit_     = unit;
  abscissa_ = abscissa;
  PetscOptionsBegin(comm_, NULL, "Stability monitor (eigenvalues of the coarse stiffness along the run)", "turgor");
  PetscCall(PetscOptionsInt(every_opt.c_str(), every_help.c_str(), "StabilityMonitor", every_, &every_, NULL));
  PetscCall(PetscOptionsInt(modes_opt.c_str(), "Eigenvalues computed at each check (nearest 0)", "StabilityMonitor", modes_, &modes_, NULL));
  PetscOptionsEnd();
  PetscCheck(every_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %" PetscInt_FMT ": must be >= 0 (0: no monitor)", every_opt.c_str(), every_);
  PetscCheck(modes_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %" PetscInt_FMT ": must be >= 1", modes_opt.c_str(), modes_);
  if (every_ > 0) PetscCall(solver_.SetFromOptions(prefix + "eigen_monitor_", PencilEnd::Lowest, modes_, 1e-10));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StabilityMonitor::SetUp(CoarseModel &model, const std::string &dir)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  if (!Active()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventRegister("TgEigenMonitor", PETSC_OBJECT_CLASSID, &ev_check_));
  model_ = &model;
  dir_   = dir;
  ops_   = std::make_unique<CoarseOperators>(model);
  PetscCall(ops_->SetUp());
  PetscCall(model.CreateGlobalVector(&U_prev_));
  PetscCall(VecDuplicate(U_prev_, &mode_prev_));
  PetscCall(VecDuplicate(U_prev_, &work_));
  PetscCall(ops_->CreateVector(&x_));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0 && !dir.empty()) {
    std::vector<std::string> cols = {abscissa_};
    for (PetscInt k = 0; k < modes_; k++) cols.push_back("lambda_" + std::to_string(k + 1));
    cols.insert(cols.end(), {"negative", "residual_max", "iterations"});
    PetscCall(csv_.Open(PETSC_COMM_SELF, dir + "/stability.csv", cols));
  }
  PetscCall(PetscPrintf(comm_, "Stability monitor: every %" PetscInt_FMT " %s, the %" PetscInt_FMT " eigenvalues of K phi = lambda M phi nearest 0\n", every_,
                        unit_.c_str(), modes_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StabilityMonitor::Check(PetscInt count, PetscReal t, Vec U)
{
  PetscBool   ok;
  std::string why;
  PetscFunctionBeginUser;
  if (!Active() || count % every_) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscLogEventBegin(ev_check_, 0, 0, 0, 0));
  checks_++;
  PetscCall(ops_->Assemble(U, false, &ok, &why));
  std::vector<PetscReal> row = {t};
  if (!ok) { /* no answer at this state: a row of NaN, the run goes on */
    PetscCall(PetscPrintf(comm_, "Stability monitor at %s %g: material points failed (%s); no eigenvalues\n", abscissa_.c_str(), (double)t, why.c_str()));
    row.resize(modes_ + 4, NAN);
    if (csv_.IsOpen()) PetscCall(csv_.Row(row));
    PetscCall(PetscLogEventEnd(ev_check_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(ops_->Symmetrize());
  PetscCall(solver_.Solve(*ops_));
  const std::vector<Eigenpair> &pairs = solver_.Pairs();
  PetscReal                     rmax  = 0;
  PetscInt                      neg   = 0;
  for (PetscInt k = 0; k < modes_; k++) row.push_back(k < (PetscInt)pairs.size() ? pairs[k].lambda : NAN);
  for (const Eigenpair &p : pairs) {
    rmax = PetscMax(rmax, p.residual);
    neg += p.lambda < 0;
  }
  row.insert(row.end(), {(PetscReal)neg, rmax, (PetscReal)solver_.Iterations()});
  if (csv_.IsOpen()) PetscCall(csv_.Row(row));
  const PetscReal lambda = pairs.empty() ? NAN : pairs[0].lambda;
  if (!lost_ && lambda_prev_ > 0 && lambda <= 0) {
    lost_       = true;
    bracket_[0] = t_prev_;
    bracket_[1] = t;
    crossing_   = t_prev_ + (t - t_prev_) * lambda_prev_ / (lambda_prev_ - lambda);
    PetscCall(PetscPrintf(comm_,
                          "Stability monitor: LOSS OF STABILITY -- the lowest eigenvalue of K crossed zero between %s %g (lambda = %.6g /µs^2) and %g "
                          "(%.6g /µs^2), at about %.8g by linear interpolation%s\n",
                          abscissa_.c_str(), (double)t_prev_, (double)lambda_prev_, (double)t, (double)lambda, (double)crossing_,
                          dir_.empty() ? "" : "; both states in stability.h5/.xmf"));
    if (!dir_.empty()) {
      PetscCall(solver_.GetVector(0, x_));
      PetscCall(ops_->NormalizeShape(x_));
      PetscCall(ops_->ToState(x_, work_));
      PetscCall(WriteCrossing(U, t));
    }
  }
  if (!lost_ && pairs.size()) { /* keep this check's state and lowest mode: the last stable one so far */
    PetscCall(VecCopy(U, U_prev_));
    PetscCall(solver_.GetVector(0, x_));
    PetscCall(ops_->NormalizeShape(x_));
    PetscCall(ops_->ToState(x_, mode_prev_));
  }
  if (pairs.size()) {
    t_prev_      = t;
    lambda_prev_ = lambda;
  }
  lambda_last_ = lambda;
  PetscCall(CheckOutputError(comm_, csv_.Error())); /* rank 0 writes the file */
  PetscCall(PetscLogEventEnd(ev_check_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StabilityMonitor::CloseOutputs()
{
  PetscFunctionBeginUser;
  if (!Active()) PetscFunctionReturn(PETSC_SUCCESS);
  csv_.Finish();
  PetscCall(CheckOutputError(comm_, csv_.Error()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* stability.h5/.xmf: the last stable state (snapshot 0, at its abscissa) and the first unstable one
   U (snapshot 1, at t), each with its lowest mode (mode_prev_, work_). */
PetscErrorCode StabilityMonitor::WriteCrossing(Vec U, PetscReal t)
{
  PetscBool ok;
  PetscFunctionBeginUser;
  fields_.AddVertexVector("mode", "µm (mode shape, largest 1)");
  PetscCall(fields_.Open(*model_, dir_, "stability"));
  PetscCall(model_->EvaluateCellStress(U_prev_, &ok));
  PetscCall(fields_.Write(*model_, U_prev_, bracket_[0], {mode_prev_}));
  PetscCall(model_->EvaluateCellStress(U, &ok));
  PetscCall(fields_.Write(*model_, U, t, {work_}));
  PetscCall(fields_.Close());
  PetscFunctionReturn(PETSC_SUCCESS);
}

void StabilityMonitor::AddSummary(JsonObject &js) const
{
  js.Set("eigen_monitor_every", every_);
  js.Set("eigen_monitor_checks", checks_);
  js.Set("eigen_monitor_lowest", lambda_last_);
  js.Set("stability_lost", lost_);
  js.Set("stability_crossing", crossing_);
  js.Set("stability_crossing_bracket", std::vector<PetscReal>{bracket_[0], bracket_[1]});
}

std::string StabilityMonitor::Report() const
{
  if (!Active()) return "";
  char buf[256];
  if (lost_)
    std::snprintf(buf, sizeof buf, "stability lost at %s %.8g (between %g and %g)", abscissa_.c_str(), (double)crossing_, (double)bracket_[0],
                  (double)bracket_[1]);
  else std::snprintf(buf, sizeof buf, "no loss of stability in %d checks (lowest eigenvalue last %.6g /µs^2)", (int)checks_, (double)lambda_last_);
  return buf;
}

} // namespace turgor
