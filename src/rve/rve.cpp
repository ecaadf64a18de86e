#include <turgor/core/log.h>
#include <turgor/rve/rve.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

namespace turgor {

RVE::~RVE()
{
  (void)MatFDColoringDestroy(&coloring_);
  (void)MatDestroy(&J_);
  (void)MatDestroy(&K_);
  (void)VecDestroy(&W_);
  (void)VecDestroy(&Wprev_);
  (void)VecDestroy(&R_);
  (void)VecDestroy(&D_);
  (void)TSDestroy(&ts_);
}

PetscErrorCode RVE::SetFromOptions()
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCall(spec_.SetFromOptions(comm_, false));
  PetscOptionsBegin(comm_, "rve_", "RVE material point (TW 562 §3.2)", "turgor");
  PetscCall(PetscOptionsInt("-cells", "Cells per side of the periodic RVE", "RVE", cells_, &cells_, NULL));
  {
    const char *const modes[] = {"relaxed", "cauchy_born", "frozen"};
    PetscInt          m       = (PetscInt)relax_;
    PetscCall(PetscOptionsEList("-relax", "Fine structure: relaxed (eq 27), cauchy_born (u1 = 0) or frozen (u1 of the last committed state)", "RVE", modes, 3, modes[m], &m, NULL));
    relax_ = (Relaxation)m;
  }
  PetscCall(PetscOptionsInt("-max_it", "Psi-tc iterations before an evaluation fails", "RVE", max_it_, &max_it_, NULL));
  PetscCall(PetscOptionsReal("-psi_dt0", "Initial pseudo time step delta_0 (scaled units)", "RVE", dt0_, &dt0_, NULL));
  PetscCall(PetscOptionsReal("-psi_increment", "delta <- increment x delta after every pseudo step", "RVE", increment_, &increment_, NULL));
  PetscCall(PetscOptionsReal("-psi_dt_max", "Largest pseudo time step", "RVE", dt_max_, &dt_max_, NULL));
  PetscCall(PetscOptionsReal("-psi_atol", "Stop when ||G|| < atol (scaled forces)", "RVE", atol_, &atol_, NULL));
  PetscCall(PetscOptionsReal("-psi_steptol", "Stop when ||step|| < steptol (scaled displacements)", "RVE", steptol_, &steptol_, NULL));
  PetscCall(PetscOptionsReal("-warm_dt0", "Initial pseudo time step when starting from a previous solution", "RVE", warm_dt0_, &warm_dt0_, NULL));
  PetscOptionsEnd();
  PetscCheck(cells_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_cells = %" PetscInt_FMT ": must be >= 1", cells_);
  PetscCheck(max_it_ >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_max_it = %" PetscInt_FMT ": must be >= 1", max_it_);
  PetscCheck(dt0_ > 0 && warm_dt0_ > 0 && increment_ >= 1 && dt_max_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Options -rve_psi_dt0, -rve_warm_dt0, -rve_psi_dt_max must be > 0 and -rve_psi_increment >= 1");
  PetscCheck(atol_ > 0 && steptol_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Options -rve_psi_atol = %g, -rve_psi_steptol = %g: must be > 0", (double)atol_, (double)steptol_);
  /* the body force is a load on the coarse model, not part of the material */
  physics_.with_loads = false;
  PetscCall(physics_.SetFromOptions(comm_, TermContext{}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::SetUp()
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgRVESolve", PETSC_OBJECT_CLASSID, &ev_solve_));
  PetscCall(PetscLogEventRegister("TgRVEJacobian", PETSC_OBJECT_CLASSID, &ev_jacobian_));
  spec_.cells_x = spec_.cells_y = cells_;
  PetscCall(GeneratePeriodicSquareGridTissue(comm_, spec_, &tissue_));
  const ParticleSet &P = tissue_.particles;
  for (PetscInt i = 0; i < P.n; i++)
    if (!P.fixed[i]) free_.push_back(i);
  PetscCall(model_.SetUp(physics_, P));
  x_.assign(2 * P.n, 0);
  v_.assign(2 * P.n, 0);
  f_.assign(2 * P.n, 0);

  /* scales: lengths by the cell size, forces by k_w x cell size (or the fluid's c_s^2 rho x cell) */
  length_scale_ = spec_.cell_size;
  force_scale_  = physics_.CharacteristicForce(length_scale_, spec_.fluid_density);
  if (force_scale_ == 0) force_scale_ = length_scale_; /* no term sets one: forces in µN */
  PetscCheck(force_scale_ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "RVE: the force scale must be > 0 (check -wall_stiffness / -sph_sound_speed)");

  PetscCall(VecCreateMPI(comm_, rank_ == 0 ? NumUnknowns() : 0, PETSC_DETERMINE, &W_));
  PetscCall(VecDuplicate(W_, &Wprev_));
  PetscCall(VecDuplicate(W_, &R_));
  PetscCall(VecDuplicate(W_, &D_));
  current_.assign(NumUnknowns(), 0);
  committed_ = current_;

  PetscCall(TSCreate(comm_, &ts_));
  PetscCall(TSSetOptionsPrefix(ts_, "rve_"));
  PetscCall(TSSetApplicationContext(ts_, this));
  PetscCall(TSSetType(ts_, TSPSEUDO));
  PetscCall(TSSetIFunction(ts_, NULL, IFunction, this));
  PetscCall(TSPseudoSetTimeStep(ts_, PseudoStep, this));
  PetscCall(TSSetPreStep(ts_, PreStep));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSSetMaxSteps(ts_, max_it_));
  PetscCall(TSSetMaxTime(ts_, PETSC_MAX_REAL));
  PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_STEPOVER));
  PetscCall(TSSetErrorIfStepFails(ts_, PETSC_FALSE));
  {
    SNES        snes;
    KSP         ksp;
    PC          pc;
    PetscMPIInt size;
    PetscCall(TSGetSNES(ts_, &snes));
    PetscCall(SNESSetType(snes, SNESKSPONLY)); /* one linear solve per pseudo step: eq 28 */
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    if (size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  {
    /* TSPSEUDO's relative test divides by an initial residual norm that only its default step rule
       computes; with the seed's schedule it would stop after one step. Our own tests (PostStep)
       replace it unless the user sets it. */
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, "rve_", "-ts_pseudo_frtol", &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, "-rve_ts_pseudo_frtol", "-1e300"));
  }
  PetscCall(BuildJacobianPattern());
  PetscCall(TSSetFromOptions(ts_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* x = F X for all particles (u1 added in Residual), v = Fdot X, and the lattice a_i = F A_i. */
PetscErrorCode RVE::SetDeformation(const Tensor2 &F, const Tensor2 &Fdot)
{
  PetscFunctionBeginUser;
  F_    = F;
  Fdot_ = Fdot;
  for (PetscInt i = 0; i < tissue_.particles.n; i++) {
    F.Apply(&tissue_.X[2 * i], &x_[2 * i]);
    Fdot.Apply(&tissue_.X[2 * i], &v_[2 * i]);
  }
  const PetscReal A1[2] = {tissue_.period[0], 0}, A2[2] = {0, tissue_.period[1]};
  PetscReal       a1[2], a2[2], va1[2], va2[2];
  F.Apply(A1, a1);
  F.Apply(A2, a2);
  Fdot.Apply(A1, va1);
  Fdot.Apply(A2, va2);
  PeriodicImages images;
  images.Set(a1, a2, va1, va2);
  model_.SetPeriodicImages(images);
  cache_valid_ = false;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* r = -f_free / force_scale at x = F X + L w, and the virial of all internal forces (may be NULL).
   TSPSEUDO, the stopping tests and the stress ask for the same W several times: the last result is
   kept (invalidated when the deformation changes). */
PetscErrorCode RVE::Residual(const PetscScalar *w, PetscScalar *r, PetscReal *virial)
{
  const PetscInt n = NumUnknowns();
  PetscFunctionBeginUser;
  if (!(cache_valid_ && !std::memcmp(cache_w_.data(), w, n * sizeof(PetscScalar)))) {
    for (size_t k = 0; k < free_.size(); k++) {
      const PetscInt i = free_[k];
      PetscReal      X[2];
      F_.Apply(&tissue_.X[2 * i], X);
      x_[2 * i]     = X[0] + length_scale_ * w[2 * k];
      x_[2 * i + 1] = X[1] + length_scale_ * w[2 * k + 1];
    }
    PetscCall(model_.ComputeForces(x_.data(), v_.data(), f_.data(), cache_virial_));
    counters_.force_evals++;
    cache_w_.assign(w, w + n);
    cache_r_.resize(n);
    for (size_t k = 0; k < free_.size(); k++) {
      cache_r_[2 * k]     = -f_[2 * free_[k]] / force_scale_;
      cache_r_[2 * k + 1] = -f_[2 * free_[k] + 1] / force_scale_;
    }
    cache_valid_ = true;
  }
  if (r) std::memcpy(r, cache_r_.data(), n * sizeof(PetscScalar));
  if (virial)
    for (int c = 0; c < 4; c++) virial[c] = cache_virial_[c];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ||G(W)||_2 (collective), with G(W) left in R_. */
PetscErrorCode RVE::ResidualNorm(Vec W, PetscReal *norm)
{
  PetscFunctionBeginUser;
  PetscCall(ColoringResidual(NULL, W, R_, this));
  PetscCall(VecNorm(R_, NORM_2, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::IFunction(TS ts, PetscReal t, Vec W, Vec Wdot, Vec Fv, void *ctx)
{
  RVE               *rve = (RVE *)ctx;
  const PetscScalar *w, *wd;
  PetscScalar       *r;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(W, &w));
  PetscCall(VecGetArrayRead(Wdot, &wd));
  PetscCall(VecGetArray(Fv, &r));
  if (rve->rank_ == 0) {
    PetscCall(rve->Residual(w, r, NULL));
    for (PetscInt k = 0; k < rve->NumUnknowns(); k++) r[k] += wd[k];
  }
  PetscCall(VecRestoreArray(Fv, &r));
  PetscCall(VecRestoreArrayRead(Wdot, &wd));
  PetscCall(VecRestoreArrayRead(W, &w));
  {
    /* a state with a non-finite force (a crossed wall) is outside the domain: reject the step */
    PetscReal nrm;
    SNES      snes;
    PetscCall(VecNorm(Fv, NORM_INFINITY, &nrm));
    PetscCall(TSGetSNES(ts, &snes));
    if (!std::isfinite(nrm)) PetscCall(SNESSetFunctionDomainError(snes));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::ColoringResidual(void *unused, Vec W, Vec R, void *ctx)
{
  RVE               *rve = (RVE *)ctx;
  const PetscScalar *w;
  PetscScalar       *r;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(W, &w));
  PetscCall(VecGetArray(R, &r));
  if (rve->rank_ == 0) PetscCall(rve->Residual(w, r, NULL));
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(W, &w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* G' by MatFDColoring (one residual per colour), then the pseudo-time shift 1/delta (eq 28). */
PetscErrorCode RVE::IJacobian(TS ts, PetscReal t, Vec W, Vec Wdot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  RVE *rve = (RVE *)ctx;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(rve->ev_jacobian_, 0, 0, 0, 0));
  PetscCall(MatFDColoringApply(rve->K_, rve->coloring_, W, NULL));
  rve->have_K_ = true;
  rve->counters_.jacobians++;
  PetscCall(MatCopy(rve->K_, B, SAME_NONZERO_PATTERN));
  PetscCall(MatShift(B, shift));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(rve->ev_jacobian_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The sparsity of G': particles interacting directly (springs, particle-spring pairs with both
   spring ends, fluid pairs), closed over two hops because the SPH force on i depends on its
   neighbours' densities and correction matrices. Rebuilt when the neighbour lists are. */
PetscErrorCode RVE::PatternColumns(std::vector<std::vector<PetscInt>> &cols) const
{
  const ParticleSet                &P  = tissue_.particles;
  const NeighbourSearch            &nb = model_.Neighbours();
  std::vector<std::set<PetscInt>> adj(P.n);
  PetscFunctionBeginUser;
  auto link = [&](PetscInt i, PetscInt j) {
    adj[i].insert(j);
    adj[j].insert(i);
  };
  for (PetscInt i = 0; i < P.n; i++) adj[i].insert(i);
  for (const Spring &s : P.springs) link(s.i, s.j);
  const PointSegmentList &ps = nb.ParticleSpringPairs();
  for (size_t q = 0; q < ps.size(); q++) {
    link(ps.p[q], P.springs[ps.s[q]].i);
    link(ps.p[q], P.springs[ps.s[q]].j);
  }
  const PairList &fp = nb.FluidPairs();
  for (size_t q = 0; q < fp.size(); q++) link(fp.i[q], fp.j[q]);
  std::vector<PetscInt> dof(P.n, -1);
  for (size_t k = 0; k < free_.size(); k++) dof[free_[k]] = (PetscInt)k;
  cols.assign(free_.size(), {});
  for (size_t k = 0; k < free_.size(); k++) {
    std::set<PetscInt> two;
    for (PetscInt j : adj[free_[k]])
      for (PetscInt l : adj[j])
        if (dof[l] >= 0) two.insert(dof[l]);
    cols[k].assign(two.begin(), two.end());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::BuildJacobianPattern()
{
  std::vector<std::vector<PetscInt>> cols;
  PetscFunctionBeginUser;
  PetscCall(PatternColumns(cols));
  PetscCall(MatFDColoringDestroy(&coloring_));
  PetscCall(MatDestroy(&J_));
  PetscCall(MatDestroy(&K_));
  have_K_ = false;
  const PetscInt        n = rank_ == 0 ? NumUnknowns() : 0;
  std::vector<PetscInt> nnz(n);
  for (PetscInt r = 0; r < n; r++) nnz[r] = 2 * (PetscInt)cols[r / 2].size();
  PetscCall(MatCreate(comm_, &J_));
  PetscCall(MatSetSizes(J_, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(J_, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(J_, 0, nnz.data()));
  PetscCall(MatMPIAIJSetPreallocation(J_, 0, nnz.data(), 0, NULL));
  for (PetscInt r = 0; r < n; r++) {
    std::vector<PetscInt>    c;
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
  pattern_rebuilds_ = model_.Neighbours().Rebuilds();
  PetscCallMPI(MPI_Bcast(&pattern_rebuilds_, 1, MPIU_INT, 0, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The seed's schedule: delta_0, then delta <- increment x delta (capped). */
PetscErrorCode RVE::PseudoStep(TS ts, PetscReal *dt, void *ctx)
{
  RVE     *rve = (RVE *)ctx;
  PetscInt step;
  PetscFunctionBeginUser;
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(TSGetTimeStep(ts, dt));
  if (step > 0) *dt = PetscMin(rve->increment_ * *dt, rve->dt_max_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::PreStep(TS ts)
{
  RVE *rve;
  Vec  W;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &rve));
  PetscCall(TSGetSolution(ts, &W));
  PetscCall(VecCopy(W, rve->Wprev_));
  /* new neighbours since the pattern was built: rebuild it (rare: particles moved > skin/2) */
  PetscBool stale;
  PetscCall(rve->PatternStale(&stale));
  if (stale) PetscCall(rve->BuildJacobianPattern());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* New neighbour lists need a new pattern only if they couple unknowns the current one does not
   (a one-cell RVE is coupled all-to-all, so it never changes). Only rank 0 of the group computes
   forces and rebuilds lists: it decides. */
PetscErrorCode RVE::PatternStale(PetscBool *stale)
{
  PetscInt verdict = 0; /* 0: current, 1: lists rebuilt but covered, 2: stale */
  PetscFunctionBeginUser;
  if (rank_ == 0 && model_.Neighbours().Rebuilds() != pattern_rebuilds_) {
    std::vector<std::vector<PetscInt>> cols;
    PetscCall(PatternColumns(cols));
    verdict = 1;
    for (size_t k = 0; k < cols.size() && verdict == 1; k++)
      if (!std::includes(pattern_cols_[k].begin(), pattern_cols_[k].end(), cols[k].begin(), cols[k].end())) verdict = 2;
  }
  PetscCallMPI(MPI_Bcast(&verdict, 1, MPIU_INT, 0, comm_));
  if (verdict == 1) pattern_rebuilds_ = model_.Neighbours().Rebuilds();
  *stale = verdict == 2 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The seed's stopping test: ||step|| < steptol or ||G|| < atol (2-norms, scaled units). */
PetscErrorCode RVE::PostStep(TS ts)
{
  RVE      *rve;
  Vec       W;
  PetscReal step, res;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &rve));
  PetscCall(TSGetSolution(ts, &W));
  PetscCall(rve->ResidualNorm(W, &res));
  PetscCall(VecAXPY(rve->Wprev_, -1.0, W));
  PetscCall(VecNorm(rve->Wprev_, NORM_2, &step));
  if (!std::isfinite(res) || !std::isfinite(step)) PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
  else if (step < rve->steptol_ || res < rve->atol_) PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Psi-tc from the current content of W_; *out gets ok / reason / iteration counts. */
/* The seed's Psi-tc with TSPSEUDO from the current content of W_ (a cold start). */
PetscErrorCode RVE::Relax(MaterialResponse *out)
{
  const PetscReal dt0 = dt0_;
  TSConvergedReason reason;
  PetscInt          steps, snes0, ksp0, snes1, ksp1;
  PetscReal         res;
  PetscFunctionBeginUser;
  PetscCall(ResidualNorm(W_, &res));
  if (res < atol_) { /* already relaxed (e.g. a warm start at an unchanged F) */
    out->residual = res;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscBool stale;
  PetscCall(PatternStale(&stale));
  if (stale) PetscCall(BuildJacobianPattern());
  PetscCall(TSSetTime(ts_, 0));
  PetscCall(TSSetStepNumber(ts_, 0));
  PetscCall(TSSetTimeStep(ts_, dt0));
  PetscCall(TSSetConvergedReason(ts_, TS_CONVERGED_ITERATING));
  PetscCall(TSGetSNESIterations(ts_, &snes0));
  PetscCall(TSGetKSPIterations(ts_, &ksp0));
  PetscCall(TSSolve(ts_, W_));
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetStepNumber(ts_, &steps));
  PetscCall(TSGetSNESIterations(ts_, &snes1));
  PetscCall(TSGetKSPIterations(ts_, &ksp1));
  out->iterations += steps;
  out->snes_its += snes1 - snes0 >= 0 ? snes1 - snes0 : snes1;
  out->ksp_its += ksp1 - ksp0 >= 0 ? ksp1 - ksp0 : ksp1;
  PetscCall(ResidualNorm(W_, &res));
  out->residual = res;
  if (reason == TS_CONVERGED_USER && std::isfinite(res)) PetscFunctionReturn(PETSC_SUCCESS);
  out->ok = false;
  char msg[256];
  if (reason == TS_CONVERGED_ITS) PetscCall(PetscSNPrintf(msg, sizeof msg, "Psi-tc did not converge in %" PetscInt_FMT " iterations (-rve_max_it): ||G|| = %.3e", steps, (double)res));
  else PetscCall(PetscSNPrintf(msg, sizeof msg, "Psi-tc failed after %" PetscInt_FMT " iterations (%s), ||G|| = %.3e", steps, TSConvergedReasons[reason], (double)res));
  out->reason = msg;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Warm starts (W_ holds the last converged u1): the limit delta -> infinity of eq 28, i.e. Newton,
   with G' and its LU factors kept from the last solve (modified Newton). Written as a plain loop
   rather than through TSPSEUDO: a warm solve is a handful of residuals, and the TS/SNES bookkeeping
   per pseudo step would cost more than the physics. G' is recomputed when an iteration reduces
   ||G|| by less than 2x (recomputing costs ~37 residuals for the one-cell RVE, an iteration one).
   *converged = false sends the caller to a cold TSPSEUDO solve. */
PetscErrorCode RVE::WarmRelax(MaterialResponse *out, bool *converged)
{
  PetscReal res, res_new, step;
  bool      refresh = !have_K_;
  PetscFunctionBeginUser;
  *converged = false;
  PetscCall(ResidualNorm(W_, &res));
  out->residual = res;
  if (res < atol_) {
    *converged = true;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscBool stale;
  PetscCall(PatternStale(&stale));
  if (stale) {
    PetscCall(BuildJacobianPattern());
    refresh = true;
  }
  for (PetscInt it = 0; it < max_it_; it++) {
    if (refresh) {
      PetscCall(PetscLogEventBegin(ev_jacobian_, 0, 0, 0, 0));
      PetscCall(MatFDColoringApply(K_, coloring_, W_, NULL));
      PetscCall(MatCopy(K_, J_, SAME_NONZERO_PATTERN));
      PetscCall(MatShift(J_, 1.0 / warm_dt0_));
      PetscCall(PetscLogEventEnd(ev_jacobian_, 0, 0, 0, 0));
      have_K_ = true;
      counters_.jacobians++;
      PetscCall(ResidualNorm(W_, &res)); /* the colouring evaluated elsewhere: G(W) back into R_ */
    }
    /* the TSPSEUDO solver's own KSP: its LU factors of J_ are the ones to reuse. With a direct
       PC (the default) the triangular solves are called on the factor itself: KSPSolve's
       bookkeeping cost as much as the solve on these 36-unknown systems (-log_view). */
    SNES      snes;
    KSP       ksp;
    PC        pc;
    PetscBool direct;
    PetscCall(TSGetSNES(ts_, &snes));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(KSPSetOperators(ksp, J_, J_));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &direct, PCLU, PCCHOLESKY, ""));
    if (direct) {
      PCFailedReason pr;
      Mat            factor;
      PetscCall(KSPSetUp(ksp)); /* refactors only if J_ changed */
      PetscCall(PCGetFailedReason(pc, &pr));
      if (pr != PC_NOERROR) PetscFunctionReturn(PETSC_SUCCESS);
      PetscCall(PCFactorGetMatrix(pc, &factor));
      PetscCall(MatSolve(factor, R_, D_));
    } else {
      KSPConvergedReason kr;
      PetscCall(KSPSolve(ksp, R_, D_));
      PetscCall(KSPGetConvergedReason(ksp, &kr));
      if (kr < 0) PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(VecAXPY(W_, -1.0, D_));
    PetscCall(VecNorm(D_, NORM_2, &step));
    PetscCall(ResidualNorm(W_, &res_new));
    /* with a fresh G' a step that does not reduce ||G|| is too long (a kink of the forces, e.g. a
       pair at its cutoff): backtrack by halving before giving up */
    bool full_step = true;
    for (int half = 0; refresh && !(res_new < res) && half < 10; half++) {
      PetscCall(VecScale(D_, 0.5));
      PetscCall(VecAXPY(W_, 1.0, D_));
      step *= 0.5;
      full_step = false;
      PetscCall(ResidualNorm(W_, &res_new));
    }
    out->iterations++;
    out->ksp_its++;
    out->residual = res_new;
    if (!std::isfinite(res_new)) PetscFunctionReturn(PETSC_SUCCESS);
    /* a shortened step says nothing about convergence: only a full Newton step may pass steptol */
    if ((full_step && step < steptol_) || res_new < atol_) {
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

/* A relaxation can converge to an equilibrium in which fluid particles have been pushed through a
   wall (after a violent trial deformation): a state the tissue cannot reach. Every fluid particle
   must lie inside its own (deformed) cell polygon; otherwise the evaluation is not accepted. */
PetscErrorCode RVE::FluidInsideCells(bool *inside)
{
  const ParticleSet    &P      = tissue_.particles;
  const PeriodicImages &images = model_.Images();
  PetscInt              ok     = 1;
  PetscFunctionBeginUser;
  if (rank_ == 0) {
    for (PetscInt p = 0; p < P.n && ok; p++) {
      if (P.kind[p] != KIND_FLUID) continue;
      const auto &ring = tissue_.cell_walls[P.cell[p]];
      const auto &img  = tissue_.cell_wall_images[P.cell[p]];
      const PetscReal px = x_[2 * p], py = x_[2 * p + 1];
      bool            in = false; /* crossing-number test */
      for (size_t e = 0, n = ring.size(); e < n; e++) {
        const size_t    f  = (e + 1) % n;
        const PetscReal ax = x_[2 * ring[e]] + images.x[img[e]][0], ay = x_[2 * ring[e] + 1] + images.x[img[e]][1];
        const PetscReal bx = x_[2 * ring[f]] + images.x[img[f]][0], by = x_[2 * ring[f] + 1] + images.x[img[f]][1];
        if ((ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay)) in = !in;
      }
      if (!in) ok = 0;
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPIU_INT, 0, comm_));
  *inside = ok != 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_solve_, 0, 0, 0, 0));
  *out = MaterialResponse();
  counters_.solves++;
  if (kind == EvaluationKind::Perturbed) counters_.tangent_solves++;
  const PetscReal J = F.Det();
  if (!(J > 0) || !std::isfinite(J) || !std::isfinite(Fdot.Norm())) {
    out->ok     = false;
    out->reason = "inverted or invalid deformation (det F = " + std::to_string(J) + ")";
    counters_.failures++;
    PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(SetDeformation(F, Fdot));

  /* start from the current state (warm) or zero (cold, Cauchy-Born); frozen: the committed state */
  const bool                      relax = relax_ == Relaxation::Relaxed;
  const std::vector<PetscScalar> &start = relax_ == Relaxation::Frozen ? committed_ : (have_current_ ? current_ : committed_);
  const bool                      warm  = relax_ != Relaxation::CauchyBorn && (have_current_ || have_committed_);
  PetscScalar                    *w;
  PetscCall(VecGetArray(W_, &w));
  if (rank_ == 0)
    for (PetscInt k = 0; k < NumUnknowns(); k++) w[k] = warm ? start[k] : 0.0;
  PetscCall(VecRestoreArray(W_, &w));
  if (relax) {
    bool converged = false, inside = false;
    if (warm) {
      PetscCall(WarmRelax(out, &converged));
      if (converged) PetscCall(FluidInsideCells(&inside));
    }
    if (!converged || !inside) { /* cold: u1 = 0 and the seed's schedule (also when a warm start failed) */
      PetscCall(VecZeroEntries(W_));
      out->ok = true;
      PetscCall(Relax(out));
      if (out->ok) {
        PetscCall(FluidInsideCells(&inside));
        if (!inside) {
          out->ok     = false;
          out->reason = "the relaxed RVE has fluid particles outside their cell (a wall was crossed)";
        }
      }
    }
  }

  /* stress by the virial over all pairs (eq 30), density from the deformed area */
  PetscReal          virial[4] = {0, 0, 0, 0}, buf[6];
  const PetscScalar *wr;
  PetscCall(VecGetArrayRead(W_, &wr));
  if (rank_ == 0) PetscCall(Residual(wr, NULL, virial));
  if (out->ok && kind == EvaluationKind::Trial && relax) { /* flags on every rank: they steer collectives */
    current_.assign(wr, wr + (rank_ == 0 ? NumUnknowns() : 0));
    have_current_ = true;
  }
  PetscCall(VecRestoreArrayRead(W_, &wr));
  PetscReal mass = 0;
  for (PetscReal m : tissue_.particles.mass) mass += m;
  const PetscReal area = J * Area();
  for (int c = 0; c < 4; c++) buf[c] = virial[c] / area;
  buf[4] = out->ok ? 1 : 0;
  buf[5] = out->residual;
  PetscCallMPI(MPI_Bcast(buf, 6, MPIU_REAL, 0, comm_));
  out->sigma = {{{buf[0], buf[1]}, {buf[2], buf[3]}}};
  out->rho   = mass / area;
  if (!std::isfinite(out->sigma.Norm()) && out->ok) {
    out->ok     = false;
    out->reason = "non-finite stress";
  }
  if (!out->ok) PetscCall(PetscInfo(ts_, "RVE evaluation failed at F = [%g %g; %g %g], Fdot = [%g %g; %g %g]: %s\n", (double)F(0, 0), (double)F(0, 1), (double)F(1, 0), (double)F(1, 1), (double)Fdot(0, 0), (double)Fdot(0, 1), (double)Fdot(1, 0), (double)Fdot(1, 1), out->reason.c_str()));
  counters_.iterations += out->iterations;
  counters_.snes_its += out->snes_its;
  counters_.ksp_its += out->ksp_its;
  if (!out->ok) counters_.failures++;
  PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::Commit()
{
  PetscFunctionBeginUser;
  if (have_current_) {
    committed_      = current_;
    have_committed_ = true;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVE::Revert()
{
  PetscFunctionBeginUser;
  current_      = committed_;
  have_current_ = have_committed_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
