#include <turgor/core/errors.h>
#include <turgor/rve/relaxation.h>
#include <algorithm>
#include <cmath>

namespace turgor {

RVERelaxation::~RVERelaxation()
{
  PetscCallVoid(KSPDestroy(&tangent_ksp_));
  PetscCallVoid(MatDestroy(&tangent_op_));
  PetscCallVoid(VecDestroy(&lin_Wp_));
  PetscCallVoid(VecDestroy(&lin_Rp_));
  PetscCallVoid(MatDestroy(&factor_));
  PetscCallVoid(VecDestroy(&seq_x_));
  PetscCallVoid(VecDestroy(&seq_y_));
  PetscCallVoid(MatFDColoringDestroy(&coloring_));
  PetscCallVoid(MatDestroy(&J_));
  PetscCallVoid(MatDestroy(&K_));
  PetscCallVoid(VecDestroy(&Wprev_));
  for (Vec *v : {&Dprev_, &dW_}) PetscCallVoid(VecDestroy(v));
  PetscCallVoid(VecDestroy(&R_));
  PetscCallVoid(VecDestroy(&D_));
  PetscCallVoid(TSDestroy(&ts_));
}

PetscErrorCode RVERelaxation::SetUp(MPI_Comm comm, RVEEquations &eq, const RVESpec &spec)
{
  PetscFunctionBeginUser;
  comm_ = comm;
  eq_   = &eq;
  spec_ = &spec;
  PetscCallMPI(MPI_Comm_size(comm, &size_));
  PetscCall(PetscLogEventRegister("TgRVEJacobian", PETSC_OBJECT_CLASSID, &ev_jacobian_));
  PetscCall(PetscLogEventRegister("TgRVELinearized", PETSC_OBJECT_CLASSID, &ev_linearized_));
  PetscCall(VecCreateMPI(comm, eq.Rank() == 0 ? eq.Cell().NumUnknowns() : 0, PETSC_DETERMINE, &R_));
  PetscCall(VecDuplicate(R_, &Wprev_));
  PetscCall(VecDuplicate(R_, &D_));
  PetscCall(VecDuplicate(R_, &Dprev_));
  PetscCall(VecDuplicate(R_, &dW_));

  PetscCall(TSCreate(comm, &ts_));
  PetscCall(TSSetOptionsPrefix(ts_, "rve_"));
  PetscCall(TSSetApplicationContext(ts_, this));
  PetscCall(TSSetType(ts_, TSPSEUDO));
  PetscCall(TSSetIFunction(ts_, NULL, IFunction, this));
  PetscCall(TSPseudoSetTimeStep(ts_, PseudoStep, this));
  PetscCall(TSSetPreStep(ts_, PreStep));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSSetMaxSteps(ts_, spec.max_it));
  PetscCall(TSSetMaxTime(ts_, PETSC_MAX_REAL));
  PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_STEPOVER));
  PetscCall(TSSetErrorIfStepFails(ts_, PETSC_FALSE));
  {
    SNES snes;
    KSP  ksp;
    PC   pc;
    PetscCall(TSGetSNES(ts_, &snes));
    PetscCall(SNESSetType(snes, SNESKSPONLY)); /* one linear solve per pseudo step: eq 28 */
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    /* the pseudo steps and the warm Newton iterations share one LU factor of J, kept here */
    PetscCall(FactorAsPC(pc));
  }
  if (spec.psi_rule == PseudoStepRule::SER) { /* a pseudo step that leaves the forces' domain (an inverted cell) is taken again at a quarter of it */
    SNES snes;
    PetscCall(TSGetSNES(ts_, &snes));
    PetscCall(TSSetMaxSNESFailures(ts_, -1));
    PetscCall(TSPseudoSetVerifyTimeStep(ts_, VerifyStep, this));
    PetscCall(SNESSetComputeInitialGuess(snes, StartFromAccepted, this));
  }
  PetscCall(BuildJacobianPattern());
  PetscCall(TSSetFromOptions(ts_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A pseudo step is taken again (TSPSEUDO retries at the dt set here) if its state is outside the
   forces' domain: the residual there is not finite. */
PetscErrorCode RVERelaxation::VerifyStep(TS ts, Vec W, void *ctx, PetscReal *dt, PetscBool *ok)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx = (RVERelaxation *)ctx;
    PetscReal      res, step;
    PetscFunctionBeginUser;
    PetscCall(rx->eq_->ResidualNorm(W, rx->R_, &res));
    PetscCall(TSGetTimeStep(ts, &step));
    *ok = std::isfinite(res) ? PETSC_TRUE : PETSC_FALSE;
    if (!*ok) *dt = 0.25 * step;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* Every pseudo step's Newton start is the last accepted state (a retried step's too: PETSc 3.18's
   TSPSEUDO would start it from the rejected one). */
PetscErrorCode RVERelaxation::StartFromAccepted(SNES snes, Vec W, void *ctx)
{
  return TURGOR_GUARDED({
    Vec accepted;
    PetscFunctionBeginUser;
    PetscCall(TSGetSolution(((RVERelaxation *)ctx)->ts_, &accepted));
    PetscCall(VecCopy(accepted, W));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* TSPSEUDO's F(W, Wdot) = Wdot + G(W); a non-finite force (a crossed wall) is outside the domain. */
PetscErrorCode RVERelaxation::IFunction(TS ts, PetscReal t, Vec W, Vec Wdot, Vec F, void *ctx)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx = (RVERelaxation *)ctx;
    PetscReal      nrm;
    SNES           snes;
    PetscFunctionBeginUser;
    PetscCall(rx->eq_->Residual(W, F));
    PetscCall(VecAXPY(F, 1.0, Wdot));
    PetscCall(VecNorm(F, NORM_INFINITY, &nrm));
    PetscCall(TSGetSNES(ts, &snes));
    if (!std::isfinite(nrm)) PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::ColoringResidual(void *unused, Vec W, Vec R, void *ctx)
{
  return TURGOR_GUARDED({
    PetscFunctionBeginUser;
    PetscCall(((RVERelaxation *)ctx)->eq_->Residual(W, R));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::Refresh(Vec W)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_jacobian_, 0, 0, 0, 0));
  PetscCall(MatFDColoringApply(K_, coloring_, W, NULL));
  have_K_ = true;
  jacobians_++;
  PetscCall(PetscLogEventEnd(ev_jacobian_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* G' by MatFDColoring (one residual per colour), then the pseudo-time shift 1/delta (eq 28). */
PetscErrorCode RVERelaxation::IJacobian(TS ts, PetscReal t, Vec W, Vec Wdot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx = (RVERelaxation *)ctx;
    PetscFunctionBeginUser;
    PetscCall(rx->Refresh(W));
    PetscCall(MatCopy(rx->K_, B, SAME_NONZERO_PATTERN));
    PetscCall(MatShift(B, shift));
    if (A != B) {
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::BuildJacobianPattern(const std::vector<std::vector<PetscInt>> *given)
{
  std::vector<std::vector<PetscInt>> cols;
  PetscFunctionBeginUser;
  if (given) cols = *given;
  else PetscCall(eq_->PatternColumns(cols));
  PetscCall(MatFDColoringDestroy(&coloring_));
  PetscCall(MatDestroy(&factor_));
  PetscCall(VecDestroy(&seq_x_));
  PetscCall(VecDestroy(&seq_y_));
  PetscCall(MatDestroy(&J_));
  PetscCall(MatDestroy(&K_));
  have_K_                 = false;
  const PetscInt        n = eq_->Rank() == 0 ? eq_->Cell().NumUnknowns() : 0;
  std::vector<PetscInt> nnz(n);
  for (PetscInt r = 0; r < n; r++) nnz[r] = 2 * (PetscInt)cols[r / 2].size();
  PetscCall(MatCreate(comm_, &J_));
  PetscCall(MatSetSizes(J_, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(J_, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(J_, 0, nnz.data()));
  PetscCall(MatMPIAIJSetPreallocation(J_, 0, nnz.data(), 0, NULL));
  for (PetscInt r = 0; r < n; r++) {
    std::vector<PetscInt> c;
    for (PetscInt k : cols[r / 2]) c.insert(c.end(), {2 * k, 2 * k + 1});
    std::vector<PetscScalar> zero(c.size(), 0.0);
    PetscCall(MatSetValues(J_, 1, &r, (PetscInt)c.size(), c.data(), zero.data(), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(J_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscCall(MatDuplicate(J_, MAT_COPY_VALUES, &K_));

  MatColoring mc;
  ISColoring  iscoloring;
  PetscCall(MatColoringCreate(K_, &mc));
  PetscCall(MatColoringSetType(mc, MATCOLORINGGREEDY));
  PetscCall(MatColoringSetDistance(mc, 2));
  PetscCall(MatColoringApply(mc, &iscoloring));
  PetscCall(MatColoringDestroy(&mc));
  PetscCall(MatFDColoringCreate(K_, iscoloring, &coloring_));
  PetscCall(MatFDColoringSetFunction(coloring_, (PetscErrorCode(*)(void))(void (*)(void))ColoringResidual, this));
  /* differencing step err * max(|w|, umin) with umin = 1e-2 cell sizes: a typical displacement */
  PetscCall(MatFDColoringSetParameters(coloring_, PETSC_DEFAULT, 1e-2));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)coloring_, "rve_"));
  PetscCall(MatFDColoringSetFromOptions(coloring_));
  PetscCall(MatFDColoringSetUp(K_, iscoloring, coloring_));
  PetscCall(ISColoringDestroy(&iscoloring));
  PetscCall(TSSetIJacobian(ts_, J_, J_, IJacobian, this));
  pattern_cols_     = cols;
  pattern_rebuilds_ = eq_->NeighbourRebuilds();
  PetscCallMPI(MPI_Bcast(&pattern_rebuilds_, 1, MPIU_INT, 0, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Values of a matrix's local rows, row by row in its pattern's order. */
/* This rank's rows of A, their values in row order. */
static PetscErrorCode RowValues(Mat A, std::vector<PetscReal> &values)
{
  PetscInt rs, re;
  PetscFunctionBeginUser;
  values.clear();
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  for (PetscInt r = rs; r < re; r++) {
    PetscInt           nc;
    const PetscScalar *v;
    PetscCall(MatGetRow(A, r, &nc, NULL, &v));
    values.insert(values.end(), v, v + nc);
    PetscCall(MatRestoreRow(A, r, &nc, NULL, &v));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A's values (this rank's rows, in row order) set into its pattern. */
static PetscErrorCode SetRowValues(Mat A, const std::vector<PetscReal> &values, const char *what)
{
  PetscInt                           rs, re;
  std::vector<std::vector<PetscInt>> cols;
  size_t                             at = 0;
  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  for (PetscInt r = rs; r < re; r++) { /* the pattern first: MatGetRow needs an assembled matrix */
    PetscInt        nc;
    const PetscInt *c;
    PetscCall(MatGetRow(A, r, &nc, &c, NULL));
    cols.emplace_back(c, c + nc);
    PetscCall(MatRestoreRow(A, r, &nc, &c, NULL));
  }
  for (PetscInt r = rs; r < re; r++) {
    const std::vector<PetscInt> &c = cols[r - rs];
    PetscCheck(at + c.size() <= values.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint's RVE %s does not fit its pattern (row %" PetscInt_FMT ")", what, r);
    PetscCall(MatSetValues(A, 1, &r, (PetscInt)c.size(), c.data(), values.data() + at, INSERT_VALUES));
    at += c.size();
  }
  PetscCheck(at == values.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "the checkpoint's RVE %s has %zu values more than its pattern", what,
             values.size() - at);
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The Jacobians computed, whether G' is kept, the pattern (each unknown pair's columns) and the
   lists' rebuilds it was made at, and G' and J's values. */
void RVERelaxation::DeclareState(StateDeclaration &d)
{
  saved_pattern_ = pattern_cols_;
  (void)RowValues(K_, saved_K_);
  (void)RowValues(J_, saved_J_);
  d.Scalar("jacobians", &jacobians_, Combine::Owner);
  d.Scalar("have_G", &have_K_, Combine::Owner);
  d.Scalar("pattern_rebuilds", &pattern_rebuilds_, Combine::Owner);
  d.Sequence("G_values", &saved_K_);
  d.Sequence("J_values", &saved_J_);
  d.Table("pattern", StateEntity::Rank)
    .Records([this] { return saved_pattern_.size(); }, [](size_t r) { return (std::uint64_t)r; }, [this](size_t n) { saved_pattern_.resize(n); }, "")
    .Ragged(
      "columns", [this](size_t r, std::vector<PetscReal> &v) { v.assign(saved_pattern_[r].begin(), saved_pattern_[r].end()); },
      [this](size_t r, const PetscReal *v, size_t n) {
        saved_pattern_[r].assign(v, v + n);
        return PETSC_SUCCESS;
      },
      true);
}

PetscErrorCode RVERelaxation::AfterStateRead()
{
  PetscInt differ = 0;
  PetscFunctionBeginUser;
  /* the group's first rank holds the unknowns and decides; the others hold no rows (what they read
     is the first rank's) */
  if (eq_->Rank() != 0) {
    saved_pattern_.clear();
    saved_K_.clear();
    saved_J_.clear();
  }
  if (eq_->Rank() == 0) {
    PetscCheck(saved_pattern_.size() == (size_t)eq_->Cell().NumUnknowns() / 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint's RVE has %zu free particles, this one %" PetscInt_FMT, saved_pattern_.size(), eq_->Cell().NumUnknowns() / 2);
    differ = saved_pattern_ != pattern_cols_;
  }
  PetscCallMPI(MPI_Bcast(&differ, 1, MPIU_INT, 0, comm_));
  const PetscInt rebuilds = pattern_rebuilds_; /* (a new pattern sets its own, and drops G') */
  const bool     have_G   = have_K_;
  if (differ) PetscCall(BuildJacobianPattern(&saved_pattern_));
  pattern_rebuilds_ = rebuilds;
  have_K_           = have_G;
  PetscCall(SetRowValues(K_, saved_K_, "G'"));
  PetscCall(SetRowValues(J_, saved_J_, "Jacobian"));
  std::vector<std::vector<PetscInt>>().swap(saved_pattern_);
  std::vector<PetscReal>().swap(saved_K_);
  std::vector<PetscReal>().swap(saved_J_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* New neighbour lists need a new pattern only if they couple unknowns the current one does not
   (a one-cell RVE is coupled all-to-all, so it never changes). Only rank 0 of the group computes
   forces and rebuilds lists: it decides. */
PetscErrorCode RVERelaxation::PatternStale(PetscBool *stale)
{
  PetscInt verdict = 0; /* 0: current, 1: lists rebuilt but covered, 2: stale */
  PetscFunctionBeginUser;
  if (eq_->Rank() == 0 && eq_->NeighbourRebuilds() != pattern_rebuilds_) {
    /* a complete pattern (every unknown pair coupled with every other: a small RVE) covers any
       lists; the lists' pattern is only worth building when it can add a coupling (it was a sixth
       of a one-cell RVE's warm solves) */
    const size_t n        = pattern_cols_.size();
    const bool   complete = std::all_of(pattern_cols_.begin(), pattern_cols_.end(), [n](const std::vector<PetscInt> &c) { return c.size() == n; });
    verdict               = 1;
    if (!complete) {
      std::vector<std::vector<PetscInt>> cols;
      PetscCall(eq_->PatternColumns(cols));
      for (size_t k = 0; k < cols.size() && verdict == 1; k++)
        if (!std::includes(pattern_cols_[k].begin(), pattern_cols_[k].end(), cols[k].begin(), cols[k].end())) verdict = 2;
    }
  }
  PetscCallMPI(MPI_Bcast(&verdict, 1, MPIU_INT, 0, comm_));
  if (verdict == 1) pattern_rebuilds_ = eq_->NeighbourRebuilds();
  *stale = verdict == 2 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The seed's schedule: delta_0, then delta <- increment x delta (capped); or switched evolution
   relaxation (RVESpec::psi_rule), the growth limited by the residual's last reduction. */
PetscErrorCode RVERelaxation::PseudoStep(TS ts, PetscReal *dt, void *ctx)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx = (RVERelaxation *)ctx;
    PetscInt       step;
    PetscFunctionBeginUser;
    PetscCall(TSGetStepNumber(ts, &step));
    PetscCall(TSGetTimeStep(ts, dt));
    PetscReal growth = rx->spec_->psi_increment;
    if (rx->spec_->psi_rule == PseudoStepRule::SER && rx->res_now_ > rx->res_before_) growth = rx->res_before_ / rx->res_now_;
    if (step > 0) *dt = PetscMin(growth * *dt, rx->spec_->psi_dt_max);
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::PreStep(TS ts)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx;
    Vec            W;
    PetscBool      stale;
    PetscFunctionBeginUser;
    PetscCall(TSGetApplicationContext(ts, &rx));
    PetscCall(TSGetSolution(ts, &W));
    PetscCall(VecCopy(W, rx->Wprev_));
    /* new neighbours since the pattern was built: rebuild it (rare: particles moved > skin/2) */
    PetscCall(rx->PatternStale(&stale));
    if (stale) PetscCall(rx->BuildJacobianPattern());
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* The seed's stopping test: ||step|| < steptol or ||G|| < atol (2-norms, scaled units). This test
   decides: TSPSEUDO's own function-norm tests (-rve_ts_pseudo_fatol/frtol) measure something else
   -- its relative test divides by an initial norm that only its default step rule computes -- so a
   stop they signal is taken back unless the seed's test holds. */
PetscErrorCode RVERelaxation::PostStep(TS ts)
{
  return TURGOR_GUARDED({
    RVERelaxation    *rx;
    Vec               W;
    PetscReal         step, res;
    PetscInt          steps, max_steps;
    TSConvergedReason reason;
    PetscFunctionBeginUser;
    PetscCall(TSGetApplicationContext(ts, &rx));
    PetscCall(TSGetSolution(ts, &W));
    PetscCall(rx->eq_->ResidualNorm(W, rx->R_, &res));
    rx->res_before_ = rx->res_now_;
    rx->res_now_    = res;
    PetscCall(VecAXPY(rx->Wprev_, -1.0, W));
    PetscCall(VecNorm(rx->Wprev_, NORM_2, &step));
    PetscCall(TSGetConvergedReason(ts, &reason));
    if (!std::isfinite(res) || !std::isfinite(step)) PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
    else if (step < rx->spec_->psi_steptol || res < rx->spec_->psi_atol) PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
    else if (reason == TS_CONVERGED_PSEUDO_FATOL || reason == TS_CONVERGED_PSEUDO_FRTOL) {
      PetscCall(TSGetStepNumber(ts, &steps));
      PetscCall(TSGetMaxSteps(ts, &max_steps));
      PetscCall(TSSetConvergedReason(ts, steps >= max_steps ? TS_CONVERGED_ITS : TS_CONVERGED_ITERATING));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::Cold(Vec W, MaterialResponse *out)
{
  TSConvergedReason reason;
  PetscInt          steps, snes0, ksp0, snes1, ksp1;
  PetscReal         res;
  PetscBool         stale;
  PetscFunctionBeginUser;
  PetscCall(eq_->ResidualNorm(W, R_, &res));
  if (res < spec_->psi_atol) { /* already relaxed (e.g. a warm start at an unchanged F) */
    out->residual = res;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PatternStale(&stale));
  if (stale) PetscCall(BuildJacobianPattern());
  res_before_ = res_now_ = res;
  PetscCall(TSSetTime(ts_, 0));
  PetscCall(TSSetStepNumber(ts_, 0));
  PetscCall(TSSetTimeStep(ts_, spec_->psi_dt0));
  PetscCall(TSSetConvergedReason(ts_, TS_CONVERGED_ITERATING));
  PetscCall(TSGetSNESIterations(ts_, &snes0));
  PetscCall(TSGetKSPIterations(ts_, &ksp0));
  PetscCall(TSSolve(ts_, W));
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetSNESIterations(ts_, &snes1));
  PetscCall(TSGetKSPIterations(ts_, &ksp1));
  out->iterations += steps;
  out->snes_its += snes1 - snes0 >= 0 ? snes1 - snes0 : snes1;
  out->ksp_its += ksp1 - ksp0 >= 0 ? ksp1 - ksp0 : ksp1;
  PetscCall(eq_->ResidualNorm(W, R_, &res));
  out->residual = res;
  if (reason == TS_CONVERGED_USER && std::isfinite(res)) PetscFunctionReturn(PETSC_SUCCESS);
  out->ok = false;
  char msg[256];
  if (reason == TS_CONVERGED_ITS)
    PetscCall(PetscSNPrintf(msg, sizeof msg, "Psi-tc did not converge in %" PetscInt_FMT " iterations (-rve_max_it): ||G|| = %.3e", steps, (double)res));
  else
    PetscCall(
      PetscSNPrintf(msg, sizeof msg, "Psi-tc failed after %" PetscInt_FMT " iterations (%s), ||G|| = %.3e", steps, TSConvergedReasons[reason], (double)res));
  out->reason = msg;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The LU factors of J (PETSc's LU with nested-dissection ordering and PCLU's settings): the symbolic
   factorisation once per sparsity pattern, the numeric one whenever J has changed since. Both the
   pseudo steps (through the shell PC) and the warm iterations solve with them, so a warm solve right
   after a cold one reuses the cold solve's last factors. The group's first rank holds every row and
   column of J (the others none): it factors J there alone and tells the others whether that worked.
   A parallel factorisation over the group (MUMPS) gained nothing and scheduled its work between the
   ranks at run time: the same run's answers differed in the last bits from run to run. */
PetscErrorCode RVERelaxation::Factor(bool *ok)
{
  PetscInt good = 1;
  PetscFunctionBeginUser;
  if (eq_->Rank() == 0) {
    bool here;
    PetscCall(FactorHere(&here));
    good = here;
  }
  if (size_ > 1) PetscCallMPI(MPI_Bcast(&good, 1, MPIU_INT, 0, comm_));
  *ok = good != 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVERelaxation::FactorHere(bool *ok)
{
  PetscObjectState state;
  MatFactorInfo    info;
  MatFactorError   err;
  Mat              A = J_;
  PetscFunctionBeginUser;
  *ok = true;
  if (size_ > 1) PetscCall(MatGetDiagonalBlock(J_, &A)); /* every entry: this rank owns all rows and columns */
  PetscCall(MatFactorInfoInitialize(&info));
  info.fill          = 5.0;
  info.dtcol         = 1e-6;
  info.zeropivot     = 100.0 * PETSC_MACHINE_EPSILON;
  info.pivotinblocks = 1.0;
  if (!factor_) {
    IS row = NULL, col = NULL;
    PetscCall(MatGetFactor(A, MATSOLVERPETSC, MAT_FACTOR_LU, &factor_));
    PetscCall(MatGetOrdering(A, MATORDERINGND, &row, &col));
    PetscCall(MatLUFactorSymbolic(factor_, A, row, col, &info));
    PetscCall(ISDestroy(&row));
    PetscCall(ISDestroy(&col));
    factor_state_ = -1;
  }
  PetscCall(PetscObjectStateGet((PetscObject)J_, &state));
  if (state == factor_state_) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatLUFactorNumeric(factor_, A, &info));
  PetscCall(MatFactorGetError(factor_, &err));
  if (err != MAT_FACTOR_NOERROR) {
    PetscCall(MatFactorClearError(factor_));
    factor_state_ = -1;
    *ok           = false;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  factor_state_ = state;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = J^-1 x with the factor (Factor), on the rank that holds it; the others hold no entries */
PetscErrorCode RVERelaxation::ApplyFactor(Vec x, Vec y)
{
  const PetscScalar *xa;
  PetscScalar       *ya;
  PetscInt           n;
  PetscFunctionBeginUser;
  if (size_ == 1) {
    PetscCall(MatSolve(factor_, x, y));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (eq_->Rank() != 0) { /* no entries here, but y changed: its cached norms must go on every rank alike */
    PetscCall(VecGetArray(y, &ya));
    PetscCall(VecRestoreArray(y, &ya));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecGetLocalSize(x, &n));
  if (!seq_x_) {
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, NULL, &seq_x_));
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, NULL, &seq_y_));
  }
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(VecPlaceArray(seq_x_, xa));
  PetscCall(VecPlaceArray(seq_y_, ya));
  PetscCall(MatSolve(factor_, seq_x_, seq_y_));
  PetscCall(VecResetArray(seq_x_));
  PetscCall(VecResetArray(seq_y_));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVERelaxation::FactorAsPC(PC pc)
{
  PetscFunctionBeginUser;
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, this));
  PetscCall(PCShellSetName(pc, "LU factors of G' + shift I, kept by the RVE relaxation"));
  PetscCall(PCShellSetSetUp(pc, FactorSetUp));
  PetscCall(PCShellSetApply(pc, FactorApply));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVERelaxation::FactorSetUp(PC pc)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx;
    bool           ok;
    PetscFunctionBeginUser;
    PetscCall(PCShellGetContext(pc, &rx));
    PetscCall(rx->Factor(&ok));
    if (!ok) PetscCall(PCSetFailedReason(pc, PC_FACTOR_NUMERIC_ZEROPIVOT));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::FactorApply(PC pc, Vec x, Vec y)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx;
    PetscFunctionBeginUser;
    PetscCall(PCShellGetContext(pc, &rx));
    PetscCall(rx->ApplyFactor(x, y));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* A warm iteration's update of W from its modified Newton step D_ = J^-1 G(w_k), with Anderson
   acceleration of depth one (-rve_anderson; Walker and Ni, SIAM J. Numer. Anal. 49, 2011) of the
   fixed-point map g(w) = w - J^-1 G(w), whose residual is f = -D:
     dW = -D_k - gamma (dw - dD),  gamma = (D_k . dD) / (dD . dD),  dD = D_k - D_{k-1},
   dw = w_k - w_{k-1}, the previous update (kept in dW_). With J kept, modified Newton converges only
   linearly (a tenth of the residual an iteration for the SPH cell); the secant of the last two iterates
   removes the slowest error direction. The pair is valid only while J is the same: a refreshed J (or a
   shortened step) starts again. The group's first rank holds every entry (the others none), so gamma
   comes from its entries alone, in one pass with no reduction: the few vector operations of the
   formula, each with its own bookkeeping and reduction, cost as much as the iterations they saved. */
PetscErrorCode RVERelaxation::AndersonStep(Vec W, bool refresh, bool *have_prev)
{
  const PetscScalar *d;
  PetscScalar       *w, *dw, *dprev;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(D_, &n));
  PetscCall(VecGetArrayRead(D_, &d));
  PetscCall(VecGetArray(W, &w));
  PetscCall(VecGetArray(dW_, &dw));
  PetscCall(VecGetArray(Dprev_, &dprev));
  if (*have_prev && !refresh) {
    PetscReal a = 0, b = 0;
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal dd = d[k] - dprev[k];
      a += d[k] * dd;
      b += dd * dd;
    }
    const PetscReal gamma = b > 0 ? a / b : 0;
    for (PetscInt k = 0; k < n; k++) dw[k] = -d[k] - gamma * (dw[k] - (d[k] - dprev[k]));
  } else
    for (PetscInt k = 0; k < n; k++) dw[k] = -d[k];
  for (PetscInt k = 0; k < n; k++) dprev[k] = d[k], w[k] += dw[k];
  PetscCall(VecRestoreArray(Dprev_, &dprev));
  PetscCall(VecRestoreArray(dW_, &dw));
  PetscCall(VecRestoreArray(W, &w));
  PetscCall(VecRestoreArrayRead(D_, &d));
  *have_prev = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Written as a plain loop rather than through TSPSEUDO: a warm solve is a handful of residuals,
   and the TS/SNES bookkeeping per pseudo step would cost more than the physics. G' is recomputed
   when an iteration reduces ||G|| by less than 2x (recomputing costs ~37 residuals for the one-cell
   RVE, an iteration one). */
PetscErrorCode RVERelaxation::Warm(Vec W, MaterialResponse *out, bool *converged)
{
  PetscReal res, res_new, step;
  bool      refresh = !have_K_, have_prev = false;
  PetscBool stale;
  PetscFunctionBeginUser;
  *converged = false;
  PetscCall(eq_->ResidualNorm(W, R_, &res));
  out->residual = res;
  if (res < spec_->psi_atol) {
    *converged = true;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PatternStale(&stale));
  if (stale) {
    PetscCall(BuildJacobianPattern());
    refresh = true;
  }
  for (PetscInt it = 0; it < spec_->max_it; it++) {
    if (refresh) {
      PetscCall(Refresh(W));
      PetscCall(MatCopy(K_, J_, SAME_NONZERO_PATTERN));
      PetscCall(MatShift(J_, 1.0 / spec_->warm_dt0));
      PetscCall(eq_->ResidualNorm(W, R_, &res)); /* the colouring evaluated elsewhere: G(W) back into R_ */
    }
    bool ok;
    PetscCall(Factor(&ok));
    if (!ok) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(ApplyFactor(R_, D_)); /* direct: KSPSolve's bookkeeping cost as much as these small solves (-log_view) */
    if (spec_->anderson) {
      PetscCall(AndersonStep(W, refresh, &have_prev));
      PetscCall(VecNorm(dW_, NORM_2, &step));
    } else {
      PetscCall(VecAXPY(W, -1.0, D_));
      PetscCall(VecNorm(D_, NORM_2, &step));
    }
    PetscCall(eq_->ResidualNorm(W, R_, &res_new));
    /* with a fresh G' a step that does not reduce ||G|| is too long (a kink of the forces, e.g. a
       pair at its cutoff): backtrack by halving before giving up */
    bool full_step = true;
    for (int half = 0; refresh && !(res_new < res) && half < 10; half++) {
      if (spec_->anderson) { /* the update was +dW_ */
        PetscCall(VecScale(dW_, 0.5));
        PetscCall(VecAXPY(W, -1.0, dW_));
      } else { /* the update was -D_ */
        PetscCall(VecScale(D_, 0.5));
        PetscCall(VecAXPY(W, 1.0, D_));
      }
      step *= 0.5;
      full_step = false;
      have_prev = false; /* the iterates' differences no longer those of the map */
      PetscCall(eq_->ResidualNorm(W, R_, &res_new));
    }
    out->iterations++;
    out->ksp_its++;
    out->residual = res_new;
    if (!std::isfinite(res_new)) PetscFunctionReturn(PETSC_SUCCESS);
    /* a shortened step says nothing about convergence: only a full Newton step may pass steptol */
    if ((full_step && step < spec_->psi_steptol) || res_new < spec_->psi_atol) {
      *converged = true;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    if (!(res_new < 0.5 * res)) {
      if (refresh && !(res_new < res)) PetscFunctionReturn(PETSC_SUCCESS); /* fresh G' and still no progress */
      refresh = true;
    } else refresh = false;
    res = res_new;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A hand-written matrix-free product rather than PETSc's MatMFFD: MatMFFD differences one-sided,
   and its O(h) error (about 1e-7 relative here, the repulsion's r^-7 curvature) would leave the
   exact tangents short of their 1e-6 check; central differences of the scaled residual with a
   step of 1e-6 cell sizes along x / |x| are accurate to ~1e-10. */
PetscErrorCode RVERelaxation::LinearizedMult(Mat A, Vec x, Vec y)
{
  return TURGOR_GUARDED({
    RVERelaxation *rx;
    PetscReal      nx;
    PetscFunctionBeginUser;
    PetscCall(MatShellGetContext(A, &rx));
    PetscCall(VecNorm(x, NORM_2, &nx));
    if (nx == 0) {
      PetscCall(VecZeroEntries(y));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    const PetscReal h = 1e-6 / nx;
    PetscCall(VecWAXPY(rx->lin_Wp_, h, x, rx->lin_W_));
    PetscCall(rx->eq_->Residual(rx->lin_Wp_, rx->lin_Rp_));
    PetscCall(VecWAXPY(rx->lin_Wp_, -h, x, rx->lin_W_));
    PetscCall(rx->eq_->Residual(rx->lin_Wp_, y));
    PetscCall(VecAYPX(y, -1.0, rx->lin_Rp_)); /* G(W + h x) - G(W - h x) */
    PetscCall(VecScale(y, 0.5 / h));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode RVERelaxation::SolveLinearized(Vec W, Vec b, Vec z, PetscInt *its, bool *ok)
{
  KSPConvergedReason reason;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_linearized_, 0, 0, 0, 0));
  *ok  = true;
  *its = 0;
  if (!tangent_ksp_) {
    PetscInt n, N;
    PC       pc;
    PetscCall(VecGetLocalSize(R_, &n));
    PetscCall(VecGetSize(R_, &N));
    PetscCall(VecDuplicate(R_, &lin_Wp_));
    PetscCall(VecDuplicate(R_, &lin_Rp_));
    PetscCall(MatCreateShell(comm_, n, n, N, N, this, &tangent_op_));
    PetscCall(MatShellSetOperation(tangent_op_, MATOP_MULT, (void (*)(void))LinearizedMult));
    PetscCall(KSPCreate(comm_, &tangent_ksp_));
    PetscCall(KSPSetOptionsPrefix(tangent_ksp_, "rve_tangent_"));
    PetscCall(KSPSetType(tangent_ksp_, KSPGMRES));
    PetscCall(KSPSetPCSide(tangent_ksp_, PC_RIGHT));
    PetscCall(KSPSetTolerances(tangent_ksp_, 1e-8, 1e-30, PETSC_DEFAULT, 100));
    PetscCall(KSPGetPC(tangent_ksp_, &pc));
    PetscCall(FactorAsPC(pc));
    PetscCall(KSPSetOperators(tangent_ksp_, tangent_op_, tangent_op_));
    PetscCall(KSPSetFromOptions(tangent_ksp_));
  }
  /* with the kept factor first; if GMRES does not converge with it (a factor of a G' far from this
     state's: it preconditions badly), once more with G' and its factor taken at W */
  bool fresh = false;
  for (int attempt = 0; attempt < 2; attempt++) {
    if (!have_K_ || attempt == 1) { /* no G' yet (a state relaxed without a solve), or the retry: G' at W */
      PetscBool stale;
      PetscCall(PatternStale(&stale));
      if (stale) PetscCall(BuildJacobianPattern());
      PetscCall(Refresh(W));
      PetscCall(MatCopy(K_, J_, SAME_NONZERO_PATTERN));
      PetscCall(MatShift(J_, 1.0 / spec_->warm_dt0));
      fresh = true;
    }
    bool     fok;
    PetscInt attempt_its;
    PetscCall(Factor(&fok));
    if (!fok) {
      *ok = false;
      break;
    }
    lin_W_ = W;
    PetscCall(MatAssemblyBegin(tangent_op_, MAT_FINAL_ASSEMBLY)); /* a new state: the KSP sets its operator up again */
    PetscCall(MatAssemblyEnd(tangent_op_, MAT_FINAL_ASSEMBLY));
    PetscCall(VecZeroEntries(z));
    PetscCall(KSPSolve(tangent_ksp_, b, z));
    PetscCall(KSPGetConvergedReason(tangent_ksp_, &reason));
    PetscCall(KSPGetIterationNumber(tangent_ksp_, &attempt_its));
    lin_W_ = nullptr;
    *its += attempt_its;
    *ok = reason > 0;
    if (*ok || fresh) break;
  }
  PetscCall(PetscLogEventEnd(ev_linearized_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
