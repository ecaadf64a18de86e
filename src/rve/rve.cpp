#include <turgor/core/memory.h>
#include <turgor/rve/rve.h>
#include <cmath>

namespace turgor {

PetscErrorCode RVESpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  const char *const modes[] = {"relaxed", "cauchy_born", "frozen"}, *const rules[] = {"seed", "ser"};
  PetscInt m = (PetscInt)relax, r = (PetscInt)psi_rule;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "rve_", "RVE material point (TW 562 §3.2)", "turgor");
  PetscCall(TurgorOptionsInt(params, "-cells", "Cells per side of the periodic RVE", "RVESpec", cells, &cells, NULL));
  PetscCall(TurgorOptionsEList(params, "-relax", "Fine structure: relaxed (eq 27), cauchy_born (u1 = 0) or frozen (u1 of the last committed state)", "RVESpec",
                               modes, 3, modes[m], &m, NULL));
  PetscCall(TurgorOptionsInt(params, "-max_it", "Psi-tc iterations before an evaluation fails", "RVESpec", max_it, &max_it, NULL));
  PetscCall(TurgorOptionsReal(params, "-psi_dt0", "Initial pseudo time step delta_0 (scaled units)", "RVESpec", psi_dt0, &psi_dt0, NULL));
  PetscCall(TurgorOptionsReal(params, "-psi_increment", "delta <- increment x delta after every pseudo step", "RVESpec", psi_increment, &psi_increment, NULL));
  PetscCall(TurgorOptionsReal(params, "-psi_dt_max", "Largest pseudo time step", "RVESpec", psi_dt_max, &psi_dt_max, NULL));
  PetscCall(TurgorOptionsReal(params, "-psi_atol", "Stop when ||G|| < atol (scaled forces)", "RVESpec", psi_atol, &psi_atol, NULL));
  PetscCall(TurgorOptionsReal(params, "-psi_steptol", "Stop when ||step|| < steptol (scaled displacements)", "RVESpec", psi_steptol, &psi_steptol, NULL));
  PetscCall(TurgorOptionsReal(params, "-warm_dt0", "Pseudo time step of warm solves (from a previous solution)", "RVESpec", warm_dt0, &warm_dt0, NULL));
  PetscCall(TurgorOptionsBool(params, "-predictor",
                              "Start a warm solve from the first-order prediction w + (dw/dF) dF of the last exact tangent (-material_tangent implicit)",
                              "RVESpec", predictor, &predictor, NULL));
  PetscCall(TurgorOptionsBool(params, "-anderson",
                              "Warm solves: Anderson acceleration (depth one) of the modified Newton iterations with kept LU factors (about a sixth "
                              "fewer iterations)",
                              "RVESpec", anderson, &anderson, NULL));
  PetscCall(TurgorOptionsEList(params, "-psi_rule",
                               "Pseudo step growth: seed (delta <- increment x delta) or ser (delta x min(increment, ||G_prev|| / ||G||): shrinks when the "
                               "residual grows)",
                               "RVESpec", rules, 2, rules[r], &r, NULL));
  PetscOptionsEnd();
  relax    = (RelaxationMode)m;
  psi_rule = (PseudoStepRule)r;
  PetscCheck(cells >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_cells = %" PetscInt_FMT ": must be >= 1", cells);
  PetscCheck(max_it >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_max_it = %" PetscInt_FMT ": must be >= 1", max_it);
  PetscCheck(psi_dt0 > 0 && warm_dt0 > 0 && psi_increment >= 1 && psi_dt_max > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Options -rve_psi_dt0, -rve_warm_dt0, -rve_psi_dt_max must be > 0 and -rve_psi_increment >= 1");
  PetscCheck(psi_atol > 0 && psi_steptol > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Options -rve_psi_atol = %g, -rve_psi_steptol = %g: must be > 0",
             (double)psi_atol, (double)psi_steptol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

RVE::~RVE()
{
  for (Vec *v : {&W_, &Wd_, &Rp_, &Rm_, &B_, &Z_}) PetscCallVoid(VecDestroy(v));
}

PetscErrorCode RVE::SetUp(const PeriodicCell &cell, const PhysicsSpec &physics, PetscReal fluid_density)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgRVESolve", PETSC_OBJECT_CLASSID, &ev_solve_));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  cell_ = cell;
  PetscCall(eq_.SetUp(comm_, cell_, physics, fluid_density));
  PetscCall(VecCreateMPI(comm_, rank_ == 0 ? NumUnknowns() : 0, PETSC_DETERMINE, &W_));
  for (Vec *v : {&Wd_, &Rp_, &Rm_, &B_, &Z_}) PetscCall(VecDuplicate(W_, v));
  PetscCall(relax_.SetUp(comm_, eq_, spec_));
  current_.assign(NumUnknowns(), 0);
  committed_ = current_;
  if (eq_.HasHistory()) { /* the terms' history starts at the reference (the glue bonds are made there) */
    PetscCall(VecZeroEntries(W_));
    PetscCall(eq_.Residual(W_, NULL));
    PetscCall(KeepCommittedHistory());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_solve_, 0, 0, 0, 0));
  *out = MaterialResponse();
  /* an output evaluation is counted apart, in nothing else: the work counters are the run's */
  MaterialCounters  output;
  MaterialCounters &counters = kind == EvaluationKind::Output ? output : counters_;
  if (kind == EvaluationKind::Output) counters_.output_solves++;
  counters.solves++;
  if (kind == EvaluationKind::Perturbed) counters.tangent_solves++;
  const PetscReal J = F.Det();
  last_ok_          = false;
  if (!(J > 0) || !std::isfinite(J) || !std::isfinite(Fdot.Norm())) {
    out->ok     = false;
    out->reason = "inverted or invalid deformation (det F = " + std::to_string(J) + ")";
    counters.failures++;
    PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  eq_.SetDeformation(F, Fdot);

  /* start from the current state (warm) or zero (cold, Cauchy-Born); frozen: the committed state */
  const bool                      relax = spec_.relax == RelaxationMode::Relaxed;
  const std::vector<PetscScalar> &start = spec_.relax == RelaxationMode::Frozen ? committed_ : (have_current_ ? current_ : committed_);
  const bool                      warm  = spec_.relax != RelaxationMode::CauchyBorn && (have_current_ || have_committed_);
  PetscScalar                    *w;
  PetscInt                        predicted = 0;
  PetscCall(VecGetArray(W_, &w));
  if (rank_ == 0) {
    const bool     from_current = spec_.relax != RelaxationMode::Frozen && have_current_;
    const Tensor2 &F0 = from_current ? trial_F_ : committed_F_, &Fdot0 = from_current ? trial_Fdot_ : committed_Fdot_;
    if (warm && relax && spec_.predictor && Predict(F, Fdot, start, F0, Fdot0, w)) predicted = 1;
    else
      for (PetscInt k = 0; k < NumUnknowns(); k++) w[k] = warm ? start[k] : 0.0;
  }
  PetscCall(VecRestoreArray(W_, &w));
  PetscCallMPI(MPI_Bcast(&predicted, 1, MPIU_INT, 0, comm_));
  if (relax) {
    bool        converged = false, inside = false;
    std::string why;
    if (warm) {
      PetscCall(relax_.Warm(W_, out, &converged));
      if (converged) PetscCall(Admissible(&inside, &why));
      if (predicted && converged && inside) counters.predicted_solves++;
      if (predicted && !(converged && inside)) { /* the prediction led astray (a contact or bond it crossed): from w itself */
        PetscCall(VecGetArray(W_, &w));
        if (rank_ == 0)
          for (PetscInt k = 0; k < NumUnknowns(); k++) w[k] = start[k];
        PetscCall(VecRestoreArray(W_, &w));
        PetscCall(relax_.Warm(W_, out, &converged));
        if (converged) PetscCall(Admissible(&inside, &why));
      }
    }
    /* a first evaluation at the reference: the material's relaxed state there, solved once on a
       scratch point */
    PetscInt shared = !warm && first_ && first_->make && (F - Tensor2::Identity()).Norm() == 0 && Fdot.Norm() == 0;
    PetscCallMPI(MPI_Bcast(&shared, 1, MPIU_INT, 0, comm_));
    if (shared && !first_->tried) {
      std::unique_ptr<RVE> scratch;
      MaterialResponse     r;
      first_->tried = true;
      PetscCall(first_->make(comm_, spec_, &scratch));
      PetscCall(scratch->Evaluate(F, Fdot, EvaluationKind::Trial, &r));
      counters.iterations += r.iterations; /* its work is this point's */
      if (r.ok) {
        first_->w    = scratch->current_;
        first_->have = true;
      }
    }
    if (shared && first_->have) {
      PetscCall(VecGetArray(W_, &w));
      if (rank_ == 0)
        for (PetscInt k = 0; k < NumUnknowns(); k++) w[k] = first_->w[k];
      PetscCall(VecRestoreArray(W_, &w));
      PetscCall(relax_.Warm(W_, out, &converged));
      if (converged) PetscCall(Admissible(&inside, &why));
    }
    if (!converged || !inside) { /* cold: u1 = 0 and the seed's schedule (also when a warm start failed) */
      PetscCall(VecZeroEntries(W_));
      out->ok = true;
      PetscCall(relax_.Cold(W_, out));
      if (out->ok) {
        PetscCall(Admissible(&inside, &why));
        if (!inside) {
          out->ok     = false;
          out->reason = why;
        }
      }
    }
  }

  /* stress by the virial over all pairs (eq 30), density from the deformed area */
  PetscReal virial[4], buf[6];
  PetscCall(eq_.Virial(W_, virial));
  if (out->ok && kind == EvaluationKind::Trial && relax) { /* flags on every rank: they steer collectives */
    const PetscScalar *wr;
    PetscCall(VecGetArrayRead(W_, &wr));
    current_.assign(wr, wr + (rank_ == 0 ? NumUnknowns() : 0));
    PetscCall(VecRestoreArrayRead(W_, &wr));
    have_current_ = true;
    trial_F_      = F;
    trial_Fdot_   = Fdot;
  }
  const PetscReal area = J * cell_.ReferenceArea();
  for (int c = 0; c < 4; c++) buf[c] = virial[c] / area;
  buf[4] = out->ok ? 1 : 0;
  buf[5] = out->residual;
  PetscCallMPI(MPI_Bcast(buf, 6, MPIU_REAL, 0, comm_));
  out->sigma = {
    {{buf[0], buf[1]}, {buf[2], buf[3]}}
  };
  out->rho = cell_.Mass() / area;
  if (!std::isfinite(out->sigma.Norm()) && out->ok) {
    out->ok     = false;
    out->reason = "non-finite stress";
  }
  if (!out->ok)
    PetscCall(PetscInfo(NULL, "RVE evaluation failed at F = [%g %g; %g %g], Fdot = [%g %g; %g %g]: %s\n", (double)F(0, 0), (double)F(0, 1), (double)F(1, 0),
                        (double)F(1, 1), (double)Fdot(0, 0), (double)Fdot(0, 1), (double)Fdot(1, 0), (double)Fdot(1, 1), out->reason.c_str()));
  last_F_    = F;
  last_Fdot_ = Fdot;
  last_ok_   = out->ok;
  counters.iterations += out->iterations;
  counters.snes_its += out->snes_its;
  counters.ksp_its += out->ksp_its;
  if (!out->ok) counters.failures++;
  PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool RVE::Predict(const Tensor2 &F, const Tensor2 &Fdot, const std::vector<PetscScalar> &w0, const Tensor2 &F0, const Tensor2 &Fdot0, PetscScalar *w) const
{
  const size_t n = w0.size(), ncol = pred_dirs_.size() / 8;
  if (ncol == 0 || n != (size_t)NumUnknowns() || pred_z_.size() != ncol * n) return false;
  bool rate = false; /* without rate directions the state does not depend on Fdot: fit F alone */
  for (size_t c = 0; c < ncol; c++)
    for (int i = 4; i < 8; i++) rate = rate || pred_dirs_[8 * c + i] != 0;
  const int     m = (int)ncol + 1, len = rate ? 8 : 4;
  const Tensor2 Om{
    {{0, -1}, {1, 0}}
  }; /* the spin's generator */
  const Tensor2 spinF = Om * F0, spinFd = Om * Fdot0, dF = F - F0, dFd = Fdot - Fdot0;
  /* the directions as rows of 8 (the spin last) and the target */
  std::vector<PetscReal> D(8 * m);
  for (size_t c = 0; c < ncol; c++)
    for (int i = 0; i < 8; i++) D[8 * c + i] = pred_dirs_[8 * c + i];
  for (int i = 0; i < 4; i++) {
    D[8 * ncol + i]     = spinF.a[i / 2][i % 2];
    D[8 * ncol + 4 + i] = spinFd.a[i / 2][i % 2];
  }
  PetscReal T[8];
  for (int i = 0; i < 4; i++) {
    T[i]     = dF.a[i / 2][i % 2];
    T[4 + i] = dFd.a[i / 2][i % 2];
  }
  /* normal equations G alpha = b, m <= 7: Gaussian elimination with partial pivoting (too small for
     a LAPACK call to pay) */
  PetscReal G[7][8], scale = 0;
  if (m > 7) return false;
  for (int r = 0; r < m; r++) {
    for (int c = 0; c < m; c++) {
      G[r][c] = 0;
      for (int i = 0; i < len; i++) G[r][c] += D[8 * r + i] * D[8 * c + i];
    }
    G[r][m] = 0;
    for (int i = 0; i < len; i++) G[r][m] += D[8 * r + i] * T[i];
    scale = std::max(scale, G[r][r]);
  }
  for (int k = 0; k < m; k++) {
    int p = k;
    for (int r = k + 1; r < m; r++)
      if (std::abs(G[r][k]) > std::abs(G[p][k])) p = r;
    if (!(std::abs(G[p][k]) > 1e-12 * scale)) return false; /* dependent directions */
    for (int c = 0; c <= m; c++) std::swap(G[k][c], G[p][c]);
    for (int r = k + 1; r < m; r++) {
      const PetscReal f = G[r][k] / G[k][k];
      for (int c = k; c <= m; c++) G[r][c] -= f * G[k][c];
    }
  }
  PetscReal alpha[7];
  for (int k = m - 1; k >= 0; k--) {
    PetscReal v = G[k][m];
    for (int c = k + 1; c < m; c++) v -= G[k][c] * alpha[c];
    alpha[k] = v / G[k][k];
  }
  for (size_t k = 0; k < n; k += 2) { /* unknowns are (x, y) pairs: the spin turns each */
    w[k]     = w0[k] - alpha[ncol] * w0[k + 1];
    w[k + 1] = w0[k + 1] + alpha[ncol] * w0[k];
  }
  for (size_t c = 0; c < ncol; c++)
    if (alpha[c] != 0)
      for (size_t k = 0; k < n; k++) w[k] += alpha[c] * pred_z_[c * n + k];
  return true;
}

/* The relaxed positions are those of the last evaluation, at W_; only rank 0 holds particles. */
PetscErrorCode RVE::Admissible(bool *inside, std::string *why)
{
  PetscInt ok        = 1;
  char     text[256] = "";
  PetscFunctionBeginUser;
  PetscCall(eq_.Residual(W_, NULL)); /* the positions of W_ (kept: no new evaluation) */
  if (rank_ == 0 && !eq_.Admissible(why)) {
    ok = 0;
    PetscCall(PetscStrncpy(text, why->c_str(), sizeof text));
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_INT, 0, comm_));
  PetscCallMPI(MPI_Bcast(text, (PetscMPIInt)sizeof text, MPI_CHAR, 0, comm_));
  *inside = ok != 0;
  *why    = text;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::KeepCommittedHistory()
{
  StateDeclaration d("history");
  PetscFunctionBeginUser;
  eq_.DeclareTermState(d);
  committed_history_.clear();
  PetscCall(PackState(d, committed_history_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::StressAt(const Tensor2 &F, const Tensor2 &Fdot, Vec W, Vec R, PetscReal sigma[4])
{
  PetscReal virial[4];
  PetscFunctionBeginUser;
  eq_.SetDeformation(F, Fdot);
  if (R) PetscCall(eq_.Residual(W, R));
  PetscCall(eq_.Virial(W, virial));
  const PetscReal area = F.Det() * cell_.ReferenceArea();
  for (int c = 0; c < 4; c++) sigma[c] = virial[c] / area;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                      Tensor2 *dsigma, MaterialResponse *status)
{
  /* central differences of explicit functions: the truncation error h^2 |third derivative| / 6 (the
     repulsion's r^-7 at r ~ 4 µm: ~1e5 per unit strain cubed, relative) is ~1e-8 at h = 1e-6, the
     round-off ~1e-16 |sigma| / h ~1e-10 relative */
  const PetscReal        h = 1e-6;
  MaterialCounters       output;
  MaterialCounters      &counters = kind == EvaluationKind::Output ? output : counters_;
  const PetscInt         evals0   = eq_.ForceEvaluations();
  const bool             relax    = spec_.relax == RelaxationMode::Relaxed;
  std::vector<PetscReal> ds(4 * n, 0.0);
  PetscInt               fail = 0;
  /* the derivatives of the relaxed state are the next warm solve's predictor (not an output's) */
  const bool     keep = relax && spec_.predictor && kind != EvaluationKind::Output;
  const PetscInt nloc = rank_ == 0 ? NumUnknowns() : 0;
  PetscFunctionBeginUser;
  *status = MaterialResponse();
  if (keep) {
    pred_dirs_.clear(); /* none while it is rebuilt (a failed solve leaves none) */
    pred_z_.assign((size_t)(n * nloc), 0.0);
  }
  PetscCheck(last_ok_ && (last_F_ - F).Norm() == 0 && (last_Fdot_ - Fdot).Norm() == 0, comm_, PETSC_ERR_ORDER,
             "RVE::StressDerivatives: not at the state of the last successful evaluation");
  counters.exact_tangents++;
  for (PetscInt k = 0; k < n && !fail; k++) {
    PetscReal sp[4], sm[4];
    if (relax) { /* G_w dw = -(G(p + h dp, w) - G(p - h dp, w)) / 2h */
      PetscInt its;
      bool     ok;
      PetscCall(StressAt(F + h * dF[k], Fdot + h * dFdot[k], W_, Rp_, sp));
      PetscCall(StressAt(F - h * dF[k], Fdot - h * dFdot[k], W_, Rm_, sm));
      PetscCall(VecWAXPY(B_, -1.0, Rp_, Rm_));
      PetscCall(VecScale(B_, 0.5 / h));
      eq_.SetDeformation(F, Fdot);
      PetscCall(relax_.SolveLinearized(W_, B_, Z_, &its, &ok));
      counters.tangent_linear_its += its;
      if (!ok) {
        fail = 1;
        break;
      }
      if (keep) {
        const PetscScalar *z;
        PetscCall(VecGetArrayRead(Z_, &z));
        std::copy(z, z + nloc, pred_z_.begin() + k * nloc);
        PetscCall(VecRestoreArrayRead(Z_, &z));
      }
    } else PetscCall(VecZeroEntries(Z_));
    /* d sigma = (sigma(p + h dp, w + h dw) - sigma(p - h dp, w - h dw)) / 2h */
    PetscCall(VecWAXPY(Wd_, h, Z_, W_));
    PetscCall(StressAt(F + h * dF[k], Fdot + h * dFdot[k], Wd_, NULL, sp));
    PetscCall(VecWAXPY(Wd_, -h, Z_, W_));
    PetscCall(StressAt(F - h * dF[k], Fdot - h * dFdot[k], Wd_, NULL, sm));
    for (int c = 0; c < 4; c++) ds[4 * k + c] = (sp[c] - sm[c]) / (2 * h);
  }
  /* back to the evaluated state (the positions for output, the next evaluation's start) */
  eq_.SetDeformation(F, Fdot);
  PetscCall(eq_.Residual(W_, NULL));
  counters.tangent_force_evals += eq_.ForceEvaluations() - evals0;
  PetscCallMPI(MPI_Bcast(ds.data(), (PetscMPIInt)ds.size(), MPIU_REAL, 0, comm_));
  for (PetscInt k = 0; k < n; k++)
    dsigma[k] = {
      {{ds[4 * k], ds[4 * k + 1]}, {ds[4 * k + 2], ds[4 * k + 3]}}
    };
  if (fail) {
    status->ok     = false;
    status->reason = "the linearised relaxation G_w dw = -G_p dp did not converge (-rve_tangent_ksp_*)";
    pred_z_.clear();
  } else if (keep) {
    pred_dirs_.assign(8 * n, 0.0);
    for (PetscInt k = 0; k < n; k++)
      for (int i = 0; i < 4; i++) {
        pred_dirs_[8 * k + i]     = dF[k].a[i / 2][i % 2];
        pred_dirs_[8 * k + 4 + i] = dFdot[k].a[i / 2][i % 2];
      }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void RVE::AddCounters(MaterialCounters &c) const
{
  c.solves += counters_.solves;
  c.failures += counters_.failures;
  c.iterations += counters_.iterations;
  c.snes_its += counters_.snes_its;
  c.ksp_its += counters_.ksp_its;
  c.jacobians += relax_.Jacobians();
  c.force_evals += eq_.ForceEvaluations();
  for (const TermStatistic &t : eq_.TermStatistics()) { /* a polygon RVE's glue and contact */
    if (t.name == "bonds_intact") c.bonds_intact += (PetscInt)t.value;
    if (t.name == "bonds_broken") c.bonds_broken += (PetscInt)t.value;
    if (t.name == "contact_mean_contacts") c.contacts += (PetscInt)std::lround(t.value); /* over its evaluations */
  }
  c.tangent_solves += counters_.tangent_solves;
  c.output_solves += counters_.output_solves;
  c.exact_tangents += counters_.exact_tangents;
  c.tangent_linear_its += counters_.tangent_linear_its;
  c.tangent_force_evals += counters_.tangent_force_evals;
  c.predicted_solves += counters_.predicted_solves;
}

PetscErrorCode RVE::Commit()
{
  PetscFunctionBeginUser;
  if (have_current_) {
    committed_      = current_;
    committed_F_    = trial_F_;
    committed_Fdot_ = trial_Fdot_;
    have_committed_ = true;
    if (eq_.HasHistory()) { /* the terms' history moves on at the accepted state (plastic hinges, slip, breaks) */
      PetscScalar *w;
      eq_.SetDeformation(trial_F_, trial_Fdot_);
      PetscCall(VecGetArray(W_, &w));
      for (size_t k = 0; k < current_.size(); k++) w[k] = current_[k];
      PetscCall(VecRestoreArray(W_, &w));
      PetscCall(eq_.AcceptStep(W_));
      PetscCall(KeepCommittedHistory());
      last_ok_ = false; /* W_ and the deformation are the trial's, not the last evaluation's */
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::Revert()
{
  PetscFunctionBeginUser;
  current_      = committed_;
  trial_F_      = committed_F_;
  trial_Fdot_   = committed_Fdot_;
  have_current_ = have_committed_;
  if (eq_.HasHistory() && !committed_history_.empty()) {
    StateDeclaration d("history");
    eq_.DeclareTermState(d);
    PetscCall(UnpackState(d, committed_history_.data(), committed_history_.size()));
    PetscCall(eq_.AfterTermStateRead());
    last_ok_ = false;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* [counters (13), have_current, have_committed, current, committed; equations; relaxation] */
void RVE::DeclareState(StateDeclaration &d)
{
  MaterialCounters &k         = counters_;
  const char       *names[13] = {"solves",          "failures",       "iterations",         "snes_its",
                                 "ksp_its",         "jacobians",      "force_evals",        "tangent_solves",
                                 "output_solves",   "exact_tangents", "tangent_linear_its", "tangent_force_evals",
                                 "predicted_solves"};
  PetscInt         *count[13] = {&k.solves,          &k.failures,       &k.iterations,         &k.snes_its,
                                 &k.ksp_its,         &k.jacobians,      &k.force_evals,        &k.tangent_solves,
                                 &k.output_solves,   &k.exact_tangents, &k.tangent_linear_its, &k.tangent_force_evals,
                                 &k.predicted_solves};
  for (int c = 0; c < 13; c++) d.Scalar(names[c], count[c], Combine::Owner);
  d.Scalar("have_current", &have_current_, Combine::Owner);
  d.Scalar("have_committed", &have_committed_, Combine::Owner);
  d.Sequence("current", &current_);
  d.Sequence("committed", &committed_);
  d.Array("trial_F", &trial_F_.a[0][0], 4, Combine::Owner);
  d.Array("trial_Fdot", &trial_Fdot_.a[0][0], 4, Combine::Owner);
  d.Array("committed_F", &committed_F_.a[0][0], 4, Combine::Owner);
  d.Array("committed_Fdot", &committed_Fdot_.a[0][0], 4, Combine::Owner);
  d.Sequence("predictor_z", &pred_z_);
  d.Sequence("predictor_directions", &pred_dirs_);
  StateDeclaration eq("equations"), relax("relaxation");
  eq_.DeclareState(eq);
  relax_.DeclareState(relax);
  d.Include(std::move(eq));
  d.Include(std::move(relax));
}

PetscErrorCode RVE::AfterStateRead()
{
  PetscFunctionBeginUser;
  const size_t n = rank_ == 0 ? (size_t)NumUnknowns() : 0;
  if (rank_ != 0) { /* the state read is the group's first rank's, which holds every unknown: this rank holds none */
    current_.clear();
    committed_.clear();
    pred_z_.clear();
  }
  PetscCheck(current_.size() == n && committed_.size() == n, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's RVE fine state has %zu unknowns, this RVE %" PetscInt_FMT, current_.size(), NumUnknowns());
  PetscCheck(pred_z_.size() == pred_dirs_.size() / 8 * current_.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's RVE predictor has %zu derivative values in %zu directions, this RVE %zu unknowns", pred_z_.size(), pred_dirs_.size() / 8,
             current_.size());
  last_ok_ = false;
  PetscCall(eq_.AfterStateRead());
  PetscCall(relax_.AfterStateRead());
  if (eq_.HasHistory()) PetscCall(KeepCommittedHistory()); /* a point is saved or moved at a committed state */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEMaterial::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscFunctionBeginUser;
  PetscCall(cell.SetFromOptions(comm, false, params));
  PetscCall(spec.SetFromOptions(comm, params));
  physics.with_loads = false; /* the body force is a load on the coarse model, not part of the material */
  PetscCall(physics.SetFromOptions(comm, TermContext{nullptr, params}));
  {
    PetscReal particles, springs;
    cell.Count((PetscReal)spec.cells, (PetscReal)spec.cells, true, &particles, &springs);
    const std::string what = "one RVE of -rve_cells " + std::to_string((long long)spec.cells) + " (" + std::to_string((long long)spec.cells) + " x " +
                             std::to_string((long long)spec.cells) + " cells, " + std::to_string((long long)particles) + " particles)";
    PetscCall(CheckCount(comm, 2 * particles, what));
    PetscCall(CheckMemory(comm, BytesPerRVE(particles), what));
  }
  PetscCall(prototype_.SetUp(comm, cell, spec.cells));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEMaterialBase::CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const
{
  if (ShareReferenceState() && !first_->make)
    first_->make = [this](MPI_Comm g, const RVESpec &sp, std::unique_ptr<RVE> *scratch) {
      PetscFunctionBeginUser;
      *scratch = std::make_unique<RVE>(g, sp); /* without the cache: it fills it */
      PetscCall((*scratch)->SetUp(prototype_, physics, FluidDensity()));
      PetscFunctionReturn(PETSC_SUCCESS);
    };
  auto rve = std::make_unique<RVE>(group, spec, ShareReferenceState() ? first_ : nullptr);
  PetscFunctionBeginUser;
  PetscCall(rve->SetUp(prototype_, physics, FluidDensity()));
  *point = std::move(rve);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void RVEMaterial::ParticlesPerPoint(PetscInt *wall, PetscInt *fluid) const
{
  *wall  = prototype_.GetTissue().particles.Count(KIND_WALL);
  *fluid = prototype_.GetTissue().particles.Count(KIND_FLUID);
}

PetscErrorCode RVEMaterial::View(PetscViewer viewer) const
{
  const char *const modes[] = {"relaxed", "cauchy_born", "frozen"};
  PetscInt          wall, fluid;
  PetscFunctionBeginUser;
  ParticlesPerPoint(&wall, &fluid);
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "material rve: %" PetscInt_FMT " x %" PetscInt_FMT " periodic cells of %g µm (%" PetscInt_FMT " wall + %" PetscInt_FMT
                                   " fluid particles), %s, Psi-tc atol %g, steptol %g, at most %" PetscInt_FMT " iterations\n",
                                   spec.cells, spec.cells, (double)cell.cell_size, wall, fluid, modes[(int)spec.relax], (double)spec.psi_atol,
                                   (double)spec.psi_steptol, spec.max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
