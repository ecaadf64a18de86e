#include <turgor/modes/strain_path_run.h>
#include <turgor/material/acoustic_tensor.h>
#include <limits>
#include <cmath>

namespace turgor {

static const char *const kPaths[] = {"uniaxial", "biaxial", "shear", "rotation", "hold"};

PetscErrorCode StrainPathRun::SetFromOptions()
{
  PetscFunctionBeginUser;
  /* the output directory first: an option refused below then leaves a summary.json that says so */
  PetscCall(PrepareOutputDirectory());
  PetscOptionsBegin(comm_, NULL, "Renamed options of -mode rve", "turgor");
  for (const char *o : {"type", "rate", "t_final", "steps", "tangents"}) {
    const std::string old_name = std::string("-rve_") + (std::string(o) == "type" ? "path" : o), new_name = std::string("-path_") + o;
    PetscCall(PetscOptionsDeprecated(old_name.c_str(), new_name.c_str(), "0.2", "-mode rve's strain path options are -path_*; -rve_* are the RVE material's"));
  }
  PetscOptionsEnd();
  PetscOptionsBegin(comm_, "path_", "Strain path of one material point (-mode rve)", "turgor");
  PetscCall(PetscOptionsEList("-type", "Strain path: uniaxial (F11 = 1 + r t), biaxial, shear (F12 = r t), rotation (F = R(r t)), hold (F = I)",
                              "StrainPathRun", kPaths, 5, kPaths[path_], &path_, NULL));
  PetscCall(PetscOptionsReal("-rate", "Strain rate r [1/µs] (angular velocity for rotation [rad/µs])", "StrainPathRun", rate_, &rate_, NULL));
  PetscCall(PetscOptionsReal("-t_final", "Duration of the path [µs]", "StrainPathRun", t_final_, &t_final_, NULL));
  PetscCall(PetscOptionsInt("-steps", "Material-point evaluations along the path (plus the initial one)", "StrainPathRun", steps_, &steps_, NULL));
  PetscCall(PetscOptionsBool("-tangents", "Also compute D^e and D^v at every step", "StrainPathRun", tangents_, &tangents_, NULL));
  PetscCall(
    PetscOptionsBool("-allow_failures",
                     "A failed evaluation is recorded and the path goes on, and the run still ends 'completed' (default: it ends 'failed', exit status 1)",
                     "StrainPathRun", allow_failures_, &allow_failures_, NULL));
  PetscCall(PetscOptionsInt("-stop_after_failures",
                            "The path ends after this many failed evaluations in a row (past a material point's collapse every later one fails, each "
                            "at the cost of a full relaxation; a stall at a kink of a force law is one failure); 0: never",
                            "StrainPathRun", stop_after_, &stop_after_, NULL));
  PetscOptionsEnd();
  PetscCheck(stop_after_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -path_stop_after_failures = %" PetscInt_FMT ": must be >= 0 (0: never)", stop_after_);
  PetscCheck(steps_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -path_steps = %" PetscInt_FMT ": must be >= 1", steps_);
  PetscCheck(t_final_ > 0 && std::isfinite(t_final_), comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -path_t_final = %g: must be > 0 and finite", (double)t_final_);
  PetscCheck(std::isfinite(rate_), comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -path_rate = %g: must be finite", (double)rate_);
  PetscCall(pool_.SetFromOptions());
  PetscFunctionReturn(PETSC_SUCCESS);
}

void StrainPathRun::Path(PetscReal t, Tensor2 *F, Tensor2 *Fdot) const
{
  const PetscReal r = rate_;
  *F                = Tensor2::Identity();
  *Fdot             = Tensor2::Zero();
  switch (path_) {
  case 0: /* uniaxial */
    (*F)(0, 0) += r * t;
    (*Fdot)(0, 0) = r;
    break;
  case 1: /* biaxial */
    (*F)(0, 0) += r * t;
    (*F)(1, 1) += r * t;
    (*Fdot)(0, 0) = (*Fdot)(1, 1) = r;
    break;
  case 2: /* simple shear */
    (*F)(0, 1)    = r * t;
    (*Fdot)(0, 1) = r;
    break;
  case 3: { /* rigid rotation */
    const PetscReal c = std::cos(r * t), s = std::sin(r * t);
    *F = {
      {{c, -s}, {s, c}}
    };
    *Fdot = {
      {{-r * s, -r * c}, {r * c, -r * s}}
    };
  } break;
  default: /* hold */
    break;
  }
}

PetscErrorCode StrainPathRun::SetUp()
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(pool_.SetUp(rank == 0 ? 1 : 0)); /* one material point, owned by rank 0 */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StrainPathRun::Solve()
{
  PetscMPIInt    rank;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::vector<std::string> cols = {"time", "F11", "F12", "F21", "F22", "Fdot11", "Fdot12", "Fdot21", "Fdot22", "s11", "s12", "s21", "s22", "rho"};
  for (const char *m : {"De", "Dv"})
    for (const char *ij : {"11_11", "11_22", "11_12", "22_11", "22_22", "22_12", "12_11", "12_22", "12_12"}) cols.push_back(std::string(m) + ij);
  for (const char *c : {"acoustic_min_det", "acoustic_angle", "iterations", "residual", "ok"}) cols.push_back(c);
  if (rank == 0) PetscCall(csv_.Open(PETSC_COMM_SELF, OutputPath("rve.csv"), cols));
  PetscCall(PetscTime(&t0));
  for (PetscInt k = 0; k <= steps_; k++) {
    const PetscReal  t = t_final_ * k / steps_;
    Tensor2          F, Fd;
    MaterialResponse r;
    Tangents         D;
    PetscInt         ok;
    Path(t, &F, &Fd);
    PetscCall(pool_.Evaluate(&F, &Fd, &r, tangents_, &D));
    ok = rank == 0 ? (r.ok ? 1 : 0) : 0; /* rank 0 owns the point; every rank commits with it */
    PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_INT, 0, comm_));
    evaluations_++;
    if (ok) PetscCall(pool_.Commit());
    else failures_++;
    failed_in_a_row_ = ok ? 0 : failed_in_a_row_ + 1;
    const bool last  = stop_after_ > 0 && failed_in_a_row_ >= stop_after_; /* every rank knows ok: they leave the path together */
    if (rank != 0) {
      if (last) break;
      continue;
    }
    if (r.ok) {
      last_   = r;
      t_last_ = t;
    } else {
      if (first_failure_.empty()) first_failure_ = "at t = " + std::to_string(t) + " µs: " + r.reason;
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  t = %g µs: evaluation failed: %s (F = [%g %g; %g %g])\n", (double)t, r.reason.c_str(), (double)F(0, 0),
                            (double)F(0, 1), (double)F(1, 0), (double)F(1, 1)));
    }
    const Tensor2  &s          = r.sigma;
    const PetscReal asym       = r.ok ? std::fabs(s(0, 1) - s(1, 0)) / PetscMax(s.Norm(), PETSC_SMALL) : 0;
    max_asymmetry_             = PetscMax(max_asymmetry_, asym);
    std::vector<PetscReal> row = {t, F(0, 0), F(0, 1), F(1, 0), F(1, 1), Fd(0, 0), Fd(0, 1), Fd(1, 0), Fd(1, 1), s(0, 0), s(0, 1), s(1, 0), s(1, 1), r.rho};
    for (int i = 0; i < 9; i++) row.push_back(D.De[i / 3][i % 3]);
    for (int i = 0; i < 9; i++) row.push_back(D.Dv[i / 3][i % 3]);
    /* material stability along the path: min over directions of det Q(n) (loss of ellipticity at <= 0) */
    AcousticMinimum am = {std::numeric_limits<PetscReal>::quiet_NaN(), std::numeric_limits<PetscReal>::quiet_NaN()};
    if (r.ok && tangents_) {
      am = MinAcousticDeterminant(D.De, r.sigma);
      if (!(am.det > 0) && ellipticity_lost_ < 0) {
        ellipticity_lost_ = t;
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "  t = %g µs: loss of ellipticity: min det Q(n) = %g (N/m)^2 at n = %.1f degrees\n", (double)t, (double)am.det,
                              (double)(am.angle * 180 / PETSC_PI)));
      }
    }
    row.insert(row.end(), {am.det, am.angle, (PetscReal)r.iterations, r.residual, r.ok ? 1.0 : 0.0});
    PetscCall(csv_.Row(row));
    if (r.ok)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  t = %7.3g µs  sigma = [%10.4g %10.4g; %10.4g %10.4g] N/m  rho = %.5g  %2" PetscInt_FMT " Psi-tc iterations\n",
                            (double)t, (double)s(0, 0), (double)s(0, 1), (double)s(1, 0), (double)s(1, 1), (double)r.rho, r.iterations));
    if (last) {
      PetscCall(
        PetscPrintf(PETSC_COMM_SELF, "  the path ends after %" PetscInt_FMT " failed evaluations in a row (-path_stop_after_failures)\n", failed_in_a_row_));
      break;
    }
  }
  PetscCall(PetscTime(&t1));
  wall_ = t1 - t0;
  PetscCall(CloseOutput(csv_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StrainPathRun::AddSummary(JsonObject &js)
{
  PetscFunctionBeginUser;
  js.Set("material", pool_.MaterialName());
  js.Set("path", kPaths[path_]);
  js.Set("rate", rate_);
  js.Set("t_final", t_final_);
  js.Set("steps", steps_);
  js.Set("tangents", (bool)tangents_);
  js.Set("evaluations", evaluations_); /* fewer than steps + 1 where -path_stop_after_failures ended the path */
  js.Set("failures", failures_);
  js.Set("wall_time_s", wall_);
  js.Set("max_stress_asymmetry", max_asymmetry_);
  if (tangents_) js.Set("ellipticity_lost_at", ellipticity_lost_); /* the first t with min det Q <= 0; -1: never */
  /* the last evaluation that succeeded: a failed one has no stress */
  js.Set("sigma_final", std::vector<PetscReal>{last_.sigma(0, 0), last_.sigma(0, 1), last_.sigma(1, 0), last_.sigma(1, 1)});
  js.Set("rho_final", last_.rho);
  js.Set("t_sigma_final", t_last_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StrainPathRun::WriteSummary()
{
  JsonObject       js;
  MaterialCounters c;
  PetscMPIInt      rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(pool_.GlobalCounters(&c));
  PetscCall(pool_.DescribePoints(js, 1));
  const bool failed = failures_ > 0 && !allow_failures_;
  PetscCall(Summary(js, failed ? "failed" : "completed"));
  if (failures_ > 0) {
    std::string first = first_failure_;
    PetscCall(BroadcastString(comm_, &first));
    js.Set("reason", std::to_string(failures_) + " of " + std::to_string(evaluations_) + " evaluations failed (first " + first + ")" +
                       (allow_failures_ ? ", allowed by -path_allow_failures" : ""));
  }
  js.Set("rve_solves", c.solves);
  js.Set("psi_tc_iterations", c.iterations);
  js.Set("rve_predicted_solves", c.predicted_solves);
  js.Set("rve_skipped_solves", c.skipped_solves);
  js.Set("snes_its", c.snes_its);
  js.Set("ksp_its", c.ksp_its);
  js.Set("jacobian_evals", c.jacobians);
  js.Set("force_evals", c.force_evals);
  PetscCall(WriteSummaryFile(js, failed)); /* a failed one says why: WriteFailure leaves it */
  PetscCall(PetscPrintf(comm_,
                        "%s: %" PetscInt_FMT " evaluations (%" PetscInt_FMT " failed), %" PetscInt_FMT " RVE solves, %" PetscInt_FMT
                        " Psi-tc iterations, %.3f s; outputs in %s: %s\n",
                        failed ? "Failed" : "Done", evaluations_, failures_, c.solves, c.iterations, wall_, OutputDir().c_str(), OutputFiles().c_str()));
  PetscCheck(!failed, comm_, PETSC_ERR_NOT_CONVERGED,
             "%" PetscInt_FMT " of %" PetscInt_FMT " material-point evaluations failed along the path (-path_allow_failures to accept that)", failures_,
             evaluations_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StrainPathRun::AddFailure(const std::string &reason, JsonObject &js)
{
  PetscFunctionBeginUser;
  csv_.Finish(); /* what it holds; its own failure is the reason already */
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
