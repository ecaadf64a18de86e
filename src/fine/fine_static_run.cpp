#include <turgor/core/errors.h>
#include <turgor/core/options.h>
#include <turgor/core/geometry.h>
#include <turgor/fine/fine_static_run.h>
#include <turgor/fine/particle_output.h>
#include <turgor/particles/polygon_couplings.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode FineStaticSpec::SetFromOptions(MPI_Comm comm)
{
  PetscReal t[64];
  PetscInt  nt = 64;
  PetscBool tset, mset;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "fine_static_", "Static equilibrium of a polygonal tissue (-mode fine_static)", "turgor");
  PetscCall(PetscOptionsRealArray("-times",
                                  "The scene's times [µs] whose equilibria are found, increasing (the controls' positions and forces, the turgor's ramp at "
                                  "each; default 0)",
                                  "FineStaticSpec", t, &nt, &tset));
  PetscCall(PetscOptionsInt("-substeps", "Increments from one load time to the next (each halved on a failed Newton solve)", "FineStaticSpec", substeps,
                            &substeps, NULL));
  PetscCall(PetscOptionsInt("-max_cutbacks", "Halvings of a failed increment before the run fails", "FineStaticSpec", max_cutbacks, &max_cutbacks, NULL));
  PetscCall(PetscOptionsBool("-snapshots", "particles.h5/xmf: the equilibrium at every load time", "FineStaticSpec", snapshots, &snapshots, NULL));
  {
    const char *const solvers[] = {"psitc", "newton"};
    PetscInt          which     = (PetscInt)solver;
    PetscCall(PetscOptionsEList("-solver",
                                "psitc: pseudo-transient continuation, the pseudo step growing into Newton's (robust from a tissue at rest); newton: "
                                "PETSc SNES (-fine_static_snes_*: Newton with a line search, or trust region)",
                                "FineStaticSpec", solvers, 2, solvers[which], &which, NULL));
    solver = (FineStaticSolver)which;
  }
  PetscCall(PetscOptionsBool("-monitor", "Print every pseudo step's residual (-fine_static_solver psitc; -fine_static_snes_monitor for newton)",
                             "FineStaticSpec", monitor, &monitor, NULL));
  PetscCall(PetscOptionsInt("-psi_max_steps", "Pseudo-transient continuation: the most pseudo steps per increment", "FineStaticSpec", psi_max_steps,
                            &psi_max_steps, NULL));
  PetscCall(PetscOptionsReal("-max_step",
                             "Largest move [µm] of a node in a Newton step (-fine_static_solver newton: the step is scaled down to it) and, about, in the "
                             "first pseudo step (psitc); default: a tenth of the mean bar",
                             "FineStaticSpec", max_step, &max_step, &mset));
  PetscOptionsEnd();
  PetscCall(ClampFromOptions(comm, &clamp));
  PetscCheck(!tset || nt < 64, comm, PETSC_ERR_ARG_SIZ, "Option -fine_static_times: more than 63 times");
  PetscCheck(!tset || nt >= 1, comm, PETSC_ERR_ARG_WRONG, "Option -fine_static_times: no value given");
  if (tset) times.assign(t, t + nt);
  for (size_t k = 0; k < times.size(); k++)
    PetscCheck(std::isfinite(times[k]) && times[k] >= 0 && (k == 0 || times[k] > times[k - 1]), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -fine_static_times: value %zu (%g) must be finite, >= 0 and above the one before", k + 1, (double)times[k]);
  PetscCheck(!mset || (std::isfinite(max_step) && max_step > 0), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_max_step = %g: must be finite and > 0",
             (double)max_step);
  PetscCheck(psi_max_steps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_psi_max_steps = %" PetscInt_FMT ": must be >= 1", psi_max_steps);
  PetscCheck(substeps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_substeps = %" PetscInt_FMT ": must be >= 1", substeps);
  PetscCheck(max_cutbacks >= 0 && max_cutbacks <= 40, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -fine_static_max_cutbacks = %" PetscInt_FMT ": must be in [0, 40]", max_cutbacks);
  PetscFunctionReturn(PETSC_SUCCESS);
}

FineStaticRun::~FineStaticRun()
{
  PetscCallVoid(MatFDColoringDestroy(&coloring_));
  PetscCallVoid(MatDestroy(&J_));
  PetscCallVoid(VecDestroy(&W_));
  PetscCallVoid(SNESDestroy(&snes_));
  PetscCallVoid(DMDestroy(&swarm_));
}

PetscErrorCode FineStaticRun::SetFromOptions()
{
  KSP ksp;
  PC  pc;
  PetscFunctionBeginUser;
  PetscCall(PrepareOutputDirectory()); /* first: an option refused below leaves a summary.json that says so */
  tissues_.type = "voronoi";           /* this mode's default: a polygonal tissue (-mode fine's is the seed's square grid) */
  PetscCall(tissues_.SetFromOptions(comm_));
  PetscCall(load_.SetFromOptions(comm_));
  PetscCall(physics_.SetFromOptions(comm_, TermContext{&load_, nullptr}));
  PetscCall(spec_.SetFromOptions(comm_));
  PetscCall(controls_.SetFromOptions(comm_));
  /* Newton with a largest node move per step, then a backtracking line search, and a direct solve
     (defaults through the API; the user's -fine_static_snes_*, _ksp_*, _pc_* win in SetUp). The
     cap: a turgid tissue at rest has straight, unstretched walls across the voids at its cell
     junctions, held only by their hinges until the turgor stretches them (no geometric stiffness
     yet), so the first Newton steps move those nodes 100x too far; the line search alone then
     creeps along the whole step (1 % per iteration; 64 cells: 50 iterations not enough), PETSc's
     trust region scales its radius with |u|, which starts at 0 (a loaded chain: no progress) */
  PetscCall(SNESCreate(comm_, &snes_));
  PetscCall(SNESSetOptionsPrefix(snes_, "fine_static_"));
  PetscCall(SNESSetType(snes_, SNESNEWTONLS));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
#if defined(PETSC_HAVE_MUMPS)
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
#endif
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::SetUp()
{
  PetscFunctionBeginUser;
  PetscCheck(snes_, comm_, PETSC_ERR_ORDER, "SetFromOptions() must be called before SetUp()");
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCall(tissues_.Generate(comm_, &tissue_)); /* every rank: the checks below agree everywhere */
  const ParticleSet &P = tissue_.particles;
  PetscCheck(!P.polygons.empty() && P.Count(KIND_FLUID) == 0, comm_, PETSC_ERR_SUP,
             "-mode fine_static: the tissue must be polygonal (-tissue_type voronoi, node_file or polyline); a square grid's SPH fluid has no static "
             "equilibrium to solve for");
  PetscCall(tissue_.Clamp(comm_, spec_.clamp, "-fine_clamp"));
  PetscCall(controls_.SetUp(comm_, tissue_, rank_ == 0));
  tip_ = tissue_.ClosestWallParticle(tissue_.hi[0], 0.5 * (tissue_.lo[1] + tissue_.hi[1])); /* as -mode fine's tip.csv */
  if (rank_ != 0) { /* checked on every rank above; held, computed and written by rank 0 alone */
    Tissue none;
    for (int d = 0; d < 2; d++) none.lo[d] = tissue_.lo[d], none.hi[d] = tissue_.hi[d];
    tissue_ = none;
  }
  PetscCall(model_.SetUp(physics_, P));
  X_ = tissue_.X;
  x_ = X_;
  v0_.assign(X_.size(), 0);
  f_.assign(X_.size(), 0);
  /* the unknowns: every free component (not clamped, not held by a velocity control), on rank 0 */
  {
    std::vector<char> held(X_.size(), 0);
    for (const ControlGroup &G : controls_.Groups())
      if (G.velocity)
        for (PetscInt i : G.nodes)
          for (int d = 0; d < 2; d++) held[2 * i + d] |= !G.free[d];
    if (rank_ == 0)
      for (PetscInt i = 0; i < P.n; i++)
        for (int d = 0; d < 2; d++)
          if (!P.fixed[i] && !held[2 * i + d]) dof_.push_back(2 * i + d);
  }
  PetscInt n = (PetscInt)dof_.size(), N;
  PetscCallMPI(MPI_Allreduce(&n, &N, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCheck(N > 0, comm_, PETSC_ERR_ARG_WRONG, "-mode fine_static: every node is clamped or held by a control: nothing to solve for");
  PetscCall(VecCreateMPI(comm_, n, N, &W_));
  PetscCall(PetscObjectSetName((PetscObject)W_, "unknowns"));
  {
    PetscScalar *w;
    PetscCall(VecGetArray(W_, &w));
    for (PetscInt k = 0; k < n; k++) w[k] = 0;
    PetscCall(VecRestoreArray(W_, &w));
  }
  w_conv_.assign(n, 0);
  {
    Vec r;
    PetscCall(VecDuplicate(W_, &r));
    PetscCall(SNESSetFunction(snes_, r, Residual, this));
    PetscCall(VecDestroy(&r));
  }
  /* forces in units of a typical force of a cell (k_b x the cell size): the absolute tolerance
     1e-12 of it reaches the turgor's and the glue's forces, which are 1e-5 of it. A chain (a
     polyline: no area) takes its length as the size. */
  {
    const PetscReal W = tissue_.hi[0] - tissue_.lo[0], H = tissue_.hi[1] - tissue_.lo[1];
    const PetscReal cell = W * H > 0 ? std::sqrt(W * H / (PetscReal)std::max((size_t)1, P.polygons.size())) : std::max(W, H);
    cell_size_           = cell;
    force_scale_         = physics_.CharacteristicForce(cell, 0);
    if (!(force_scale_ > 0)) force_scale_ = 1;
    /* the finite differences perturb positions x = X + u, so their step is relative to |x| (sqrt(eps)
       x the coordinates' size, MatFDColoring's umin): a step relative to u, small where x is large,
       drowns in x's round-off (1e-4 of the difference on a 1 µm chain: Newton stalls) */
    coordinate_scale_ = 0;
    for (PetscReal c : X_) coordinate_scale_ = std::max(coordinate_scale_, std::fabs(c));
    if (!(coordinate_scale_ > 0)) coordinate_scale_ = 1;
  }
  /* the absolute tolerance 1e-12, or the round-off floor of |R| where that is higher: each force
     carries about eps x the coordinates' size x k_b of error, so |R| cannot fall below
     sqrt(N) eps |x| / L (1 600 cells, 128 000 unknowns: 3e-12; the residual stalled at 1.4e-12) */
  PetscReal floor = 0;
  if (rank_ == 0) floor = std::sqrt((PetscReal)N) * PETSC_MACHINE_EPSILON * coordinate_scale_ / cell_size_;
  PetscCallMPI(MPI_Bcast(&floor, 1, MPIU_REAL, 0, comm_));
  PetscCall(SNESSetTolerances(snes_, std::max((PetscReal)1e-12, floor), 1e-10, PETSC_DEFAULT, 50, PETSC_DEFAULT));
  {
    SNESLineSearch ls;
    PetscCall(SNESGetLineSearch(snes_, &ls));
    PetscCall(SNESLineSearchSetPreCheck(ls, CapStep, this));
    if (!(spec_.max_step > 0)) { /* default: a tenth of a bar at rest */
      PetscReal bars = 0;
      for (const Spring &b : P.springs) bars += b.rest_length;
      spec_.max_step = P.springs.empty() ? 1 : 0.1 * bars / (PetscReal)P.springs.size();
    }
  }
  PetscCall(SNESSetFromOptions(snes_));
  {
    PetscReal atol, rtol;
    PetscInt  maxit;
    PetscCall(SNESGetTolerances(snes_, &atol, &rtol, NULL, &maxit, NULL));
    PetscCheck(std::isfinite(atol) && atol >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_snes_atol = %g: must be finite and >= 0", (double)atol);
    PetscCheck(std::isfinite(rtol) && rtol >= 0 && rtol < 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_snes_rtol = %g: must be in [0, 1)",
               (double)rtol);
    PetscCheck(maxit >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_static_snes_max_it = %" PetscInt_FMT ": must be >= 1", maxit);
    std::string clamped;
    for (const std::string &c : spec_.clamp) clamped += (clamped.empty() ? "" : ",") + c;
    PetscCall(PetscPrintf(comm_, "turgor fine_static: %" PetscInt_FMT " cells, %" PetscInt_FMT " nodes, %" PetscInt_FMT " unknowns, clamp: %s\n",
                          (PetscInt)P.polygons.size(), P.n, N, clamped.empty() ? "none" : clamped.c_str()));
    PetscCall(model_.View(PETSC_VIEWER_STDOUT_(comm_)));
    if (controls_.Active()) PetscCall(controls_.View(comm_));
    PetscCall(PetscPrintf(comm_,
                          "Static equilibrium at %zu load time(s) up to t = %g µs, %" PetscInt_FMT " increment(s) each; %s, |f| <= max(%g x %g µN, %g |f_0|)\n",
                          spec_.times.size(), (double)spec_.times.back(), spec_.substeps,
                          spec_.solver == FineStaticSolver::PSITC ? "pseudo-transient continuation" : "Newton (SNES)", (double)atol, (double)force_scale_,
                          (double)rtol));
  }
  if (HasOutputDirectory()) {
    std::vector<std::string> cols = {"time"};
    for (const std::string &c : controls_.Columns()) cols.push_back(c);
    if (rank_ == 0) {
      PetscCall(groups_csv_.Open(PETSC_COMM_SELF, OutputPath("groups.csv"), cols));
      PetscCall(
        static_csv_.Open(PETSC_COMM_SELF, OutputPath("static.csv"), {"time", "tip_displacement_y", "increments", "cutbacks", "iterations", "residual"}));
    }
    if (spec_.snapshots) {
      PetscCall(CreateParticleSwarm(comm_, P, rank_ == 0 ? P.n : 0, &swarm_));
      PetscCall(snapshots_.Open(swarm_, P, X_.data(), OutputDir(), "particles"));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::Place(Vec W)
{
  const PetscScalar *w;
  PetscFunctionBeginUser;
  if (rank_ != 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetArrayRead(W, &w));
  x_ = X_; /* clamped nodes stay there */
  controls_.Impose(t_, x_.data(), nullptr);
  if (held_blend_ < 1) /* the predictor: the held components part of the way from where they were at the last equilibrium */
    for (size_t k = 0; k < x_.size(); k++) x_[k] = held_before_[k] + held_blend_ * (x_[k] - held_before_[k]);
  for (size_t k = 0; k < dof_.size(); k++) x_[dof_[k]] = X_[dof_[k]] + w[k];
  PetscCall(VecRestoreArrayRead(W, &w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::Forces(bool *ok)
{
  const ParticleSet &P = tissue_.particles;
  PetscFunctionBeginUser;
  *ok = true;
  if (rank_ != 0) PetscFunctionReturn(PETSC_SUCCESS);
  *ok = FirstInvertedCell() < 0; /* outside the forces' domain (a gas law's p0 A0 / A) */
  if (!*ok) PetscFunctionReturn(PETSC_SUCCESS);
  model_.SetTime(t_);
  PetscCall(model_.ComputeForces(x_.data(), v0_.data(), f_.data(), nullptr));
  evaluations_++;
  push_.resize(f_.size());
  controls_.ControlForces(t_, f_.data(), push_.data(), P.n);
  for (const ControlGroup &G : controls_.Groups()) /* the force groups' pushes (a velocity group's reaction is not a force on the unknowns) */
    if (!G.velocity)
      for (PetscInt i : G.nodes)
        for (int d = 0; d < 2; d++) f_[2 * i + d] += push_[2 * i + d];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt FineStaticRun::FirstInvertedCell() const
{
  const ParticleSet &P = tissue_.particles;
  for (size_t c = 0; c < P.polygons.size(); c++)
    if (!P.polygons[c].open && P.polygons[c].nodes.size() >= 3 && !(PolygonArea(P.polygons[c].nodes, x_.data()) > 0)) return (PetscInt)c;
  return -1;
}

/* R = -f / force scale on the unknowns; NaN and a domain error where a cell is inverted (the line
   search backs off, or the increment is cut back). */
PetscErrorCode FineStaticRun::Residual(SNES snes, Vec W, Vec R, void *ctx)
{
  return TURGOR_GUARDED({
    FineStaticRun *run = (FineStaticRun *)ctx;
    PetscScalar   *r;
    bool           ok;
    PetscMPIInt    bad;
    PetscFunctionBeginUser;
    PetscCall(run->Place(W));
    PetscCall(run->Forces(&ok));
    PetscCall(VecGetArray(R, &r));
    for (size_t k = 0; k < run->dof_.size(); k++) r[k] = ok ? -run->f_[run->dof_[k]] / run->force_scale_ : NAN;
    PetscCall(VecRestoreArray(R, &r));
    bad = !ok;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, run->comm_));
    if (bad && snes) PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* The step Y (SNES's: W - Y is tried) scaled so that no node moves more than -fine_static_max_step. */
PetscErrorCode FineStaticRun::CapStep(SNESLineSearch ls, Vec W, Vec Y, PetscBool *changed, void *ctx)
{
  FineStaticRun *run = (FineStaticRun *)ctx;
  PetscReal      big = 0;
  PetscFunctionBeginUser;
  {
    const PetscScalar *y;
    PetscInt           n;
    PetscCall(VecGetLocalSize(Y, &n));
    PetscCall(VecGetArrayRead(Y, &y));
    for (PetscInt k = 0; k < n; k++) big = std::max(big, (PetscReal)std::fabs(y[k]));
    PetscCall(VecRestoreArrayRead(Y, &y));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &big, 1, MPIU_REAL, MPIU_MAX, run->comm_));
  *changed = PETSC_FALSE;
  if (big > run->spec_.max_step) {
    PetscCall(VecScale(Y, run->spec_.max_step / big));
    *changed = PETSC_TRUE;
    run->capped_steps_++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::ColoringResidual(void *snes, Vec W, Vec R, void *ctx)
{
  return Residual((SNES)snes, W, R, ctx);
}

/* The Jacobian's pattern: the unknowns of every pair of coupled nodes (PolygonCouplings within the
   terms' reach and the neighbour lists' skin: contacts that open during the increment are covered);
   its columns coloured, the matrix differenced by MatFDColoring. Rebuilt at every increment. */
PetscErrorCode FineStaticRun::BuildJacobian()
{
  const ParticleSet &P = tissue_.particles;
  const PetscInt     n = (PetscInt)dof_.size();
  PetscInt           start;
  ISColoring         iscoloring;
  MatColoring        mc;
  PetscFunctionBeginUser;
  PetscCall(MatFDColoringDestroy(&coloring_));
  PetscCall(MatDestroy(&J_));
  PetscCall(VecGetOwnershipRange(W_, &start, NULL));
  std::vector<std::vector<PetscInt>> cols(n);
  if (rank_ == 0) {
    PetscReal reach = 0;
    for (const auto &t : physics_.Terms()) reach = std::max(reach, t->Reach(P));
    reach += physics_.neighbour_skin;
    std::vector<std::set<PetscInt>> adj;
    PolygonCouplings(
      P, x_.data(), reach, [](PetscInt i) { return i; }, adj);
    std::vector<PetscInt> unknown(X_.size(), -1);
    for (PetscInt k = 0; k < n; k++) unknown[dof_[k]] = k;
    for (PetscInt k = 0; k < n; k++) {
      for (PetscInt j : adj[dof_[k] / 2])
        for (int d = 0; d < 2; d++)
          if (unknown[2 * j + d] >= 0) cols[k].push_back(start + unknown[2 * j + d]);
      std::sort(cols[k].begin(), cols[k].end());
    }
  }
  std::vector<PetscInt> nnz(n);
  for (PetscInt k = 0; k < n; k++) nnz[k] = (PetscInt)cols[k].size();
  PetscCall(MatCreateAIJ(comm_, n, n, PETSC_DETERMINE, PETSC_DETERMINE, 0, nnz.data(), 0, NULL, &J_));
  PetscCall(MatSetOption(J_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (PetscInt k = 0; k < n; k++) {
    std::vector<PetscScalar> zeros(cols[k].size(), 0);
    const PetscInt           row = start + k;
    PetscCall(MatSetValues(J_, 1, &row, (PetscInt)cols[k].size(), cols[k].data(), zeros.data(), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J_, MAT_FINAL_ASSEMBLY));
  PetscCall(MatColoringCreate(J_, &mc));
  PetscCall(MatColoringSetType(mc, MATCOLORINGGREEDY));
  PetscCall(MatColoringSetDistance(mc, 2));
  PetscCall(MatColoringApply(mc, &iscoloring));
  PetscCall(MatColoringDestroy(&mc));
  PetscCall(MatFDColoringCreate(J_, iscoloring, &coloring_));
  PetscCall(MatFDColoringSetFunction(coloring_, (PetscErrorCode(*)(void))(void (*)(void))ColoringResidual, this));
  PetscCall(MatFDColoringSetParameters(coloring_, PETSC_DEFAULT, coordinate_scale_)); /* step sqrt(eps) x max(|u|, |x| scale) */
  PetscCall(MatFDColoringSetFromOptions(coloring_));
  PetscCall(MatFDColoringSetUp(J_, iscoloring, coloring_));
  PetscCall(ISColoringDestroy(&iscoloring));
  PetscCall(SNESSetJacobian(snes_, J_, J_, SNESComputeJacobianDefaultColor, coloring_));
  jacobians_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Pseudo-transient continuation from W_ to |R| <= tol: (I / dt + R'(u)) du = -R(u), u += du, the
   pseudo step growing as the residual falls (switched evolution relaxation, dt_n+1 = dt_n |R_n-1| /
   |R_n|, and at least doubled after a step that lowered it: a soft mode -- a cantilever's bending --
   otherwise holds the residual and the step where they are, 0.2 % a step) into Newton's. The
   first step moves no node more than -fine_static_max_step (dt_0 = max_step / |R|_inf: du ~ dt R
   where R' is small against 1/dt); a step that inverts a cell, fails to factor or makes the
   residual 100 times larger is taken again at a quarter of dt from the same state (a turgid
   cantilever under its weight: accepted, such steps threw the residual up 500x, again and again;
   a stricter 4x costs a confined tissue three times the steps). By hand rather than TSPSEUDO,
   which in PETSc 3.18 retries a rejected step from the rejected state and leaves the step rule
   without the last residual (the RVE's relaxation works around both); here the loop is short. R' comes from the colouring at
   every step and is factored with the pseudo shift by the SNES's KSP (a direct solve). */
PetscErrorCode FineStaticRun::PseudoTransient(PetscReal tol, bool *converged, PetscInt *steps)
{
  KSP       ksp;
  Vec       R, dW, Wtry, Rtry;
  Mat       A = NULL; /* R' + I / dt, refilled from R' at each try (one matrix, not one per try) */
  PetscReal rn, rprev = 0, dt = 0, rinf;
  PetscFunctionBeginUser;
  *converged = false;
  *steps     = 0;
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(VecDuplicate(W_, &R));
  PetscCall(VecDuplicate(W_, &dW));
  PetscCall(VecDuplicate(W_, &Wtry));
  PetscCall(VecDuplicate(W_, &Rtry));
  PetscCall(Residual(NULL, W_, R, this));
  PetscCall(VecNorm(R, NORM_2, &rn));
  PetscCall(VecNorm(R, NORM_INFINITY, &rinf));
  dt = rinf > 0 ? spec_.max_step / rinf : 1; /* max_step: a tenth of a bar by default */
  for (PetscInt k = 0; k < spec_.psi_max_steps && std::isfinite(rn) && rn > tol; k++) {
    PetscBool stop;
    PetscCall(InterruptRequestedAll(comm_, &stop)); /* SIGINT/SIGTERM: stop within a step, not at the next load time */
    if (stop) {
      interrupted_ = true;
      break;
    }
    if (k > 0) dt = std::min(dt * (rn < rprev ? std::max((PetscReal)2, rprev / rn) : rprev / rn), (PetscReal)1e300);
    PetscCall(MatFDColoringApply(J_, coloring_, W_, NULL)); /* R'(u), with R(u) evaluated afresh */
    jacobians_++;
    bool taken = false;
    for (int retry = 0; retry < 8 && !taken; retry++) {
      if (!A) PetscCall(MatDuplicate(J_, MAT_COPY_VALUES, &A));
      else PetscCall(MatCopy(J_, A, SAME_NONZERO_PATTERN));
      PetscCall(MatShift(A, 1 / dt));
      PetscCall(KSPSetOperators(ksp, A, A));
      PetscCall(KSPSolve(ksp, R, dW));
      KSPConvergedReason solved;
      PetscCall(KSPGetConvergedReason(ksp, &solved));
      PetscReal rt = NAN;
      if (solved >= 0) { /* a failed factorisation leaves dW undefined: retried at a shorter step, whose shift helps the factor */
        PetscCall(VecWAXPY(Wtry, -1.0, dW, W_));
        PetscCall(Residual(NULL, Wtry, Rtry, this));
        PetscCall(VecNorm(Rtry, NORM_2, &rt));
      }
      if (std::isfinite(rt) && rt <= 100 * rn) {
        taken = true;
        rprev = rn;
        rn    = rt;
        PetscCall(VecCopy(Wtry, W_));
        PetscCall(VecCopy(Rtry, R));
      } else dt *= 0.25; /* a cell inverted, or the residual grew 100-fold: the same state, a shorter pseudo step */
    }
    (*steps)++;
    if (spec_.monitor)
      PetscCall(PetscPrintf(comm_, "    pseudo step %" PetscInt_FMT ": |R| %.3e (|f| %.3g µN), pseudo step %.3g%s\n", *steps, (double)rn,
                            (double)(rn * force_scale_), (double)dt, taken ? "" : " (failed)"));
    if (!taken) break;
  }
  residual_  = rn;
  *converged = std::isfinite(rn) && rn <= tol;
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&dW));
  PetscCall(VecDestroy(&Wtry));
  PetscCall(VecDestroy(&Rtry));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The linear response of the free nodes to the held ones' move from the last equilibrium:
   R' du = -dR/dheld . move, the derivative along the move by a difference of 1e-3 of it. Without it
   the first residual sees only the held nodes moved: the bonds beside a grip open by the grip's
   whole step, past the glue's peak, and the solve starts from a broken state. */
PetscErrorCode FineStaticRun::Predict()
{
  const PetscReal eps = 1e-3;
  KSP             ksp;
  Vec             R0, Re, dW;
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(VecDuplicate(W_, &R0));
  PetscCall(VecDuplicate(W_, &Re));
  PetscCall(VecDuplicate(W_, &dW));
  held_before_ = X_;
  controls_.Impose(t_conv_, held_before_.data(), nullptr);
  held_blend_ = eps;
  PetscCall(Residual(NULL, W_, Re, this));
  held_blend_ = 0;
  PetscCall(MatFDColoringApply(J_, coloring_, W_, NULL)); /* R' and R at the last equilibrium's held positions */
  jacobians_++;
  PetscCall(Residual(NULL, W_, R0, this));
  PetscCall(VecAXPBY(Re, -1 / eps, 1 / eps, R0)); /* (Re - R0) / eps: the move's part only (a Newton step on R0 too would overshoot as at rest) */
  PetscCall(KSPSetOperators(ksp, J_, J_));
  PetscCall(KSPSolve(ksp, Re, dW));
  held_blend_ = 1;
  KSPConvergedReason solved;
  PetscReal          move;
  PetscCall(KSPGetConvergedReason(ksp, &solved));
  PetscCall(VecNorm(dW, NORM_INFINITY, &move));
  if (solved >= 0 && std::isfinite(move)) PetscCall(VecAXPY(W_, -1.0, dW)); /* else no prediction: the solve starts where the last equilibrium was */
  PetscCall(VecDestroy(&R0));
  PetscCall(VecDestroy(&Re));
  PetscCall(VecDestroy(&dW));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::SolveAt(PetscReal t, bool *converged, std::string *why)
{
  SNESConvergedReason reason;
  PetscInt            its;
  PetscFunctionBeginUser;
  t_ = t;
  {
    PetscScalar *w;
    PetscCall(VecGetArray(W_, &w));
    for (size_t k = 0; k < dof_.size(); k++) w[k] = w_conv_[k];
    PetscCall(VecRestoreArray(W_, &w));
  }
  PetscCall(Place(W_));
  PetscCall(BuildJacobian());
  if (t_ != t_conv_ && controls_.Active()) PetscCall(Predict());
  PetscReal r0, atol, rtol;
  {
    Vec R;
    PetscCall(SNESGetFunction(snes_, &R, NULL, NULL));
    PetscCall(SNESComputeFunction(snes_, W_, R));
    PetscCall(VecNorm(R, NORM_2, &r0));
  }
  PetscCall(SNESGetTolerances(snes_, &atol, &rtol, NULL, NULL, NULL));
  if (spec_.solver == FineStaticSolver::PSITC) {
    bool ok;
    PetscCall(PseudoTransient(std::max(atol, rtol * r0), &ok, &its));
    reason = ok ? SNES_CONVERGED_FNORM_ABS : SNES_DIVERGED_MAX_IT;
  } else {
    PetscCall(SNESSolve(snes_, NULL, W_));
    PetscCall(SNESGetConvergedReason(snes_, &reason));
    PetscCall(SNESGetIterationNumber(snes_, &its));
    PetscCall(SNESGetFunctionNorm(snes_, &residual_));
  }
  iterations_ += its;
  /* converged means the forces balance to the tolerances: a trust region that shrank to nothing, or a
     step below -snes_stol, is SNES's success but not an equilibrium */
  const PetscReal tol = std::max(atol, rtol * r0);
  *converged          = (reason == SNES_CONVERGED_FNORM_ABS || reason == SNES_CONVERGED_FNORM_RELATIVE) && std::isfinite(residual_);
  if (!*converged) {
    failed_solves_++;
    char norms[96];
    PetscCall(
      PetscSNPrintf(norms, sizeof norms, ", |R| = %.3e (tolerance %.3e; |f| = %.3g µN)", (double)residual_, (double)tol, (double)(residual_ * force_scale_)));
    *why = std::string(spec_.solver == FineStaticSolver::PSITC ? "pseudo-transient continuation " : "Newton ") + (reason > 0 ? "stalled (" : "") +
           SNESConvergedReasons[reason] + (reason > 0 ? ")" : "") + " after " + std::to_string((long long)its) + " iterations" + norms;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* the equilibrium: the terms' history moves on (rank 0 holds the particles) */
  PetscCall(Place(W_));
  bool ok;
  PetscCall(Forces(&ok));
  if (rank_ == 0) {
    PetscCall(model_.AcceptStep(x_.data(), v0_.data(), t));
    const PetscScalar *w;
    PetscCall(VecGetArrayRead(W_, &w));
    for (size_t k = 0; k < dof_.size(); k++) w_conv_[k] = w[k];
    PetscCall(VecRestoreArrayRead(W_, &w));
  }
  t_conv_ = t;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::Solve()
{
  PetscLogDouble t0, t1;
  PetscLogEvent  ev;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgFineStatic", PETSC_OBJECT_CLASSID, &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  solving_ = true;
  for (PetscReal target : spec_.times) {
    const PetscInt inc0 = increments_, cut0 = cutbacks_, its0 = iterations_;
    PetscReal      dt       = (target - t_conv_) / (PetscReal)spec_.substeps;
    PetscInt       halvings = 0;
    while (t_conv_ < target || (target == 0 && increments_ == inc0)) {
      const PetscReal t = dt > 0 && t_conv_ + dt < target - 1e-12 * target ? t_conv_ + dt : target;
      bool            ok;
      std::string     why;
      PetscCall(SolveAt(t, &ok, &why));
      if (interrupted_) break;
      if (ok) {
        increments_++;
        halvings = 0;
        if (target == 0) break;
        continue;
      }
      last_failure_ = "at t = " + std::to_string(t) + " µs: " + why;
      /* a residual that creeps down to the last pseudo step is not a load too large for one
         increment: measured on a free turgid bar of 400 cells, the iteration crawls along the
         bar's softest mode, whose step the finite-difference Jacobian sizes wrongly */
      const char *creeping = why.find("DIVERGED_MAX_IT") != std::string::npos
                             ? "; a residual that falls slowly but never converges is a soft mode the finite-difference Jacobian cannot resolve "
                               "(a long free bar): -mode fine relaxes it dynamically (-pressure_ramp_time, -body_force_ramp_time, -viscosity_coefficient)"
                             : "";
      PetscCheck(halvings < spec_.max_cutbacks && dt > 0, comm_, PETSC_ERR_NOT_CONVERGED,
                 "-mode fine_static: no equilibrium %s (increment %g µs after %" PetscInt_FMT " cut-backs; -fine_static_max_cutbacks = %" PetscInt_FMT
                 ", or more -fine_static_substeps)%s",
                 last_failure_.c_str(), (double)dt, halvings, spec_.max_cutbacks, creeping);
      dt *= 0.5;
      halvings++;
      cutbacks_++;
      PetscCall(PetscPrintf(comm_, "  cut back at t = %g µs (%s): increment %g µs\n", (double)t, why.c_str(), (double)dt));
    }
    if (interrupted_) {
      PetscCall(PetscPrintf(comm_, "Interrupted (SIGINT/SIGTERM) on the way to t = %g µs: stopping; the last equilibrium is t = %g µs\n", (double)target,
                            (double)t_conv_));
      break;
    }
    PetscCall(Record(target, increments_ - inc0, cutbacks_ - cut0, iterations_ - its0));
    PetscBool stop;
    PetscCall(InterruptRequestedAll(comm_, &stop));
    if (stop) {
      interrupted_ = true;
      PetscCall(PetscPrintf(comm_, "Interrupted after the equilibrium at t = %g µs: stopping\n", (double)target));
      break;
    }
  }
  solving_ = false;
  PetscCall(PetscTime(&t1));
  wall_ = t1 - t0;
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The equilibrium at load time t: no inverted cell, finite forces; groups.csv, static.csv and a
   snapshot. */
PetscErrorCode FineStaticRun::Record(PetscReal t, PetscInt increments, PetscInt cutbacks, PetscInt iterations)
{
  const ParticleSet &P = tissue_.particles;
  PetscFunctionBeginUser;
  PetscCall(Place(W_));
  bool ok;
  PetscCall(Forces(&ok));
  PetscMPIInt bad      = 0;
  PetscInt    inverted = -1;
  if (rank_ == 0) {
    inverted = FirstInvertedCell();
    for (PetscReal v : f_) bad |= !std::isfinite(v);
  }
  PetscCallMPI(MPI_Bcast(&inverted, 1, MPIU_INT, 0, comm_));
  PetscCallMPI(MPI_Bcast(&bad, 1, MPI_INT, 0, comm_));
  PetscCheck(inverted < 0, comm_, PETSC_ERR_NOT_CONVERGED, "-mode fine_static: cell %" PetscInt_FMT " is inverted at the equilibrium of t = %g µs", inverted,
             (double)t);
  PetscCheck(!bad, comm_, PETSC_ERR_FP, "-mode fine_static: non-finite forces at the equilibrium of t = %g µs", (double)t);
  tip_uy_ = rank_ == 0 && tip_ >= 0 ? x_[2 * tip_ + 1] - X_[2 * tip_ + 1] : 0;
  PetscCallMPI(MPI_Bcast(&tip_uy_, 1, MPIU_REAL, 0, comm_));
  /* the groups' reactions: minus the forces on their held components (no inertia at rest) */
  PetscCall(controls_.Observe(comm_, t, x_.data(), f_.data(), last_groups_, false));
  load_times_done_++;
  if (rank_ == 0 && groups_csv_.IsOpen()) {
    std::vector<PetscReal> row = {t};
    row.insert(row.end(), last_groups_.begin(), last_groups_.end());
    PetscCall(groups_csv_.Row(row));
    PetscCall(static_csv_.Row({t, tip_uy_, (PetscReal)increments, (PetscReal)cutbacks, (PetscReal)iterations, residual_}));
  }
  if (spec_.snapshots && HasOutputDirectory()) {
    /* the force of every term on each node: zero where it is free (the equilibrium), minus the
       reaction where it is held */
    ParticleSnapshotWriter::Fields fields;
    fields.nodes.push_back({"force", "µN", rank_ == 0 ? f_ : std::vector<PetscReal>(), 2});
    PetscCall(AddTermSnapshotFields(model_, P, snapshots_, x_.data(), v0_.data(), &fields));
    PetscCall(snapshots_.Write(swarm_, t, x_.data(), v0_.data(), fields));
  }
  PetscCall(PetscPrintf(comm_,
                        "  t = %g µs: equilibrium after %" PetscInt_FMT " increment(s), %" PetscInt_FMT
                        " cut-back(s), |R| = %.3g (|f| = %.3g µN on the free nodes)\n",
                        (double)t, increments, cutbacks, (double)residual_, (double)(residual_ * force_scale_)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::AddSummary(JsonObject &js)
{
  const ParticleSet &P = tissue_.particles;
  PetscInt           N = 0;
  PetscFunctionBeginUser;
  if (W_) PetscCall(VecGetSize(W_, &N));
  js.Set("n_nodes", P.n);
  js.Set("n_cells", (PetscInt)P.polygons.size());
  js.Set("n_bars", (PetscInt)P.springs.size());
  js.Set("unknowns", N);
  js.Set("physics", model_.ActiveTerms());
  js.Set("times", spec_.times);
  js.Set("load_times_done", load_times_done_);
  js.Set("t_final", t_conv_); /* the last equilibrium's time */
  js.Set("tip_displacement_y", tip_uy_);
  js.Set("t_requested", spec_.times.back());
  js.Set("increments", increments_);
  js.Set("cutbacks", cutbacks_);
  js.Set("solver", spec_.solver == FineStaticSolver::PSITC ? "psitc" : "newton");
  js.Set("iterations", iterations_);
  js.Set("failed_solves", failed_solves_);
  js.Set("capped_steps", capped_steps_);
  js.Set("max_step", spec_.max_step);
  js.Set("jacobians", jacobians_);
  js.Set("force_evaluations", evaluations_);
  js.Set("force_scale", force_scale_);
  js.Set("residual_final", residual_);
  js.Set("wall_time_s", wall_);
  const std::vector<std::string> cols = controls_.Columns();
  for (size_t k = 0; k < cols.size() && k < last_groups_.size(); k++) js.Set(cols[k], last_groups_[k]);
  for (const TermStatistic &s : model_.Statistics()) js.Set(s.name, s.value);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::AddFailure(const std::string &reason, JsonObject &js)
{
  PetscFunctionBeginUser;
  if (solving_) js.Set("last_failure", last_failure_);
  groups_csv_.Finish();
  static_csv_.Finish();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineStaticRun::WriteSummary()
{
  JsonObject js;
  PetscFunctionBeginUser;
  PetscCall(CloseOutput(groups_csv_));
  PetscCall(CloseOutput(static_csv_));
  if (spec_.snapshots && HasOutputDirectory()) PetscCall(snapshots_.Close());
  PetscCall(Summary(js, interrupted_ ? "interrupted" : "completed"));
  PetscCall(WriteSummaryFile(js));
  PetscCall(PetscPrintf(comm_,
                        "%s: t = %g µs in %" PetscInt_FMT " increments (%" PetscInt_FMT " cut back), %" PetscInt_FMT " iterations, %" PetscInt_FMT
                        " force and %" PetscInt_FMT " Jacobian evaluations, %.3f s wall\nOutputs in %s: %s\n",
                        interrupted_ ? "Interrupted" : "Done", (double)t_conv_, increments_, cutbacks_, iterations_, evaluations_, jacobians_, (double)wall_,
                        OutputDir().c_str(), OutputFiles().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
