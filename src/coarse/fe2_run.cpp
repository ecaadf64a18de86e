#include <turgor/core/errors.h>
#include <turgor/coarse/fe2_run.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/radau_iia.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace turgor {

FE2Run::~FE2Run()
{
  PetscCallVoid(MatDestroy(&J_));
}

PetscErrorCode FE2Run::SetTSDefaults()
{
  PetscMPIInt size;
  TSAdapt     adapt;
  SNES        snes;
  KSP         ksp;
  PC          pc;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(TSSetType(ts_, TSRADAUIIA)); /* the seed's best method */
  /* Defaults measured on the bending bar (docs/benchmarks.md): the DSP step controller (fewer
     rejections than basic on the oscillating response), and for Radau IIA RADAU5's advice for
     expensive Jacobians (material tangents): keep the Jacobian while Newton contracts by 0.1. */
  PetscCall(TSGetAdapt(ts_, &adapt));
  PetscCall(TSAdaptSetType(adapt, TSADAPTDSP));
  PetscCall(TSRadauIIASetJacobianReuse(ts_, 0.1));
  PetscCall(TSSetTimeStep(ts_, 0.1));
  PetscCall(TSSetMaxSNESFailures(ts_, -1)); /* a failed nonlinear solve rejects the step, always */
  PetscCall(TSSetMaxStepRejections(ts_, 50));
  PetscCall(TSGetSNES(ts_, &snes));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  /* on more than one rank, every rank factors the whole matrix (PCREDUNDANT, PETSc's LU): the
     result is then the same run to run, which MUMPS's dynamic scheduling does not give */
  PetscCall(PCSetType(pc, size > 1 ? PCREDUNDANT : PCLU));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::ModeSetFromOptions()
{
  PetscFunctionBeginUser;
  /* FE^2 default for the material points' accuracy (an RVE's Psi-tc tolerance): 1e-9 rather than
     the seed's 1e-12 (-mode rve keeps 1e-12). On the bending bar the tip history moves by 2.7e-6 µm,
     far below the coarse tolerance, for 1.5x less time (docs/benchmarks.md); -rve_psi_atol and
     -rve_psi_steptol override it. */
  model_.Pool().SetDefaultTolerance(1e-9);
  ParameterList &params = PhysicsParameters();
  PetscCall(load_.SetFromOptions(comm_, &params));
  PetscCall(load_.RequireUnscheduled(comm_, "fe2"));
  model_.SetLoad(load_);
  PetscCall(model_.SetFromOptions(&params));
  PetscCall(model_.Spec().RequireNoBoundaryGradient(comm_, "fe2"));
  PetscOptionsBegin(comm_, "fe2_", "Coarse FE^2 run (-mode fe2)", "turgor");
  PetscCall(TurgorOptionsInt(&params, "-jacobian_max_age",
                             "Reuse the material tangents (K, C) for this many accepted steps; 0: fresh at every Jacobian request; -1: 0 for radauiia (which "
                             "decides itself), 10 otherwise",
                             "FE2Run", jacobian_max_age_, &jacobian_max_age_, NULL));
  PetscCall(PetscOptionsBool("-stop_at_localisation",
                             "End the run (status localised) after the step whose snapshot first shows an element that lost ellipticity "
                             "(min det of the acoustic tensor <= 0; needs -coarse_acoustic_field and snapshots), or at the last accepted time "
                             "beyond which a material point finds no equilibrium (the integrator cannot pass it)",
                             "FE2Run", stop_at_localisation_, &stop_at_localisation_, NULL));
  PetscOptionsEnd();
  PetscCheck(jacobian_max_age_ >= -1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_jacobian_max_age = %" PetscInt_FMT ": must be >= -1", jacobian_max_age_);
  PetscCheck(!stop_at_localisation_ || model_.Spec().acoustic_field, comm_, PETSC_ERR_ARG_INCOMP,
             "Option -fe2_stop_at_localisation: localisation is found in the snapshots' acoustic field, which -coarse_acoustic_field 0 leaves out");
  PetscCall(monitor_.SetFromOptions("fe2_", "steps", "time"));
  PetscCheck(!monitor_.Active() || !CheckpointsRequested(), comm_, PETSC_ERR_SUP,
             "Option -fe2_eigen_monitor: the stability monitor's history (its last eigenvalues, the first crossing) is not checkpointed; give it without "
             "-checkpoint_interval, -checkpoint_wall_interval and -restart");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::SetUpModel()
{
  PetscFunctionBeginUser;
  PetscCall(model_.SetUp());
  PetscCall(model_.CreateGlobalVector(&U_));
  PetscCall(PetscObjectSetName((PetscObject)U_, "state"));
  PetscCall(VecZeroEntries(U_));
  PetscCall(MatDuplicate(model_.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &J_));
  PetscCall(TSSetDM(ts_, model_.GetDM()));
  PetscCall(TSSetFunctionDomainError(ts_, CheckDomain));
  PetscCall(monitor_.SetUp(model_, out_.ready ? out_.dir : std::string()));
  if (monitor_.Active()) PetscCall(TSMonitorSet(ts_, EigenMonitor, this, NULL));
  /* the summary's time split is of the run (wall_time_s), not of the set-up's relaxation at rest */
  model_.Pool().ResetTimes();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Explicit methods integrate Udot = Mt^-1 G(U) (they need f only); the others solve
   F(U, Udot) = 0 with the assembled Jacobian. */
PetscErrorCode FE2Run::AfterTSSetFromOptions()
{
  PetscBool arkimex;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts_, &arkimex, TSARKIMEX, ""));
  {
    PetscBool is_explicit;
    PetscCall(TSIsExplicit(ts_, &is_explicit));
    explicit_ = is_explicit;
  }
  if (jacobian_max_age_ < 0) {
    /* an integrator with its own Jacobian-reuse control (radauiia) asks only when it needs one;
       SNES-based ones ask at every Newton iteration */
    void (*reuse)(void) = nullptr;
    PetscCall(PetscObjectQueryFunction((PetscObject)ts_, "TSRadauIIASetJacobianReuse_C", &reuse));
    jacobian_max_age_ = reuse ? 0 : 10;
  }
  if (explicit_) PetscCall(TSSetRHSFunction(ts_, NULL, RHSFunction, this));
  else {
    PetscCall(TSSetIFunction(ts_, NULL, IFunction, this));
    PetscCall(TSSetIJacobian(ts_, J_, J_, IJacobian, this));
    PetscCall(TSSetEquationType(ts_, TS_EQ_IMPLICIT)); /* dF/dUdot = Mt, not the identity */
    if (arkimex) PetscCall(TSARKIMEXSetFullyImplicit(ts_, PETSC_TRUE));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::Report()
{
  PetscMPIInt size;
  TSType      type;
  PetscReal   atol, rtol;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(TSGetType(ts_, &type));
  PetscCall(TSGetTolerances(ts_, &atol, NULL, &rtol, NULL));
  PetscCall(PetscPrintf(comm_,
                        "turgor fe2: %" PetscInt_FMT " elements, %" PetscInt_FMT " material points (%s, %s), %d MPI ranks in %" PetscInt_FMT
                        " material-point groups\n",
                        model_.NumElements(), model_.NumMaterialPoints(), model_.Pool().MaterialName(), model_.QuadratureDescription(), size,
                        model_.Pool().NumGroups()));
  PetscCall(model_.Pool().Model().View(PETSC_VIEWER_STDOUT_(comm_)));
  PetscCall(
    PetscPrintf(comm_, "Reference density %.6g ng/µm^2, %s mass matrix\n", (double)model_.ReferenceDensity(), model_.LumpedMass() ? "lumped" : "consistent"));
  PetscCall(PetscPrintf(comm_, "Time integration: %s (%s form) to t = %g µs, rtol = %g, atol = %g\n", type,
                        explicit_ ? "explicit, Udot = Mt^-1 G(U)" : "implicit, F(U, Udot) = Mt Udot - G(U)", (double)t_final_, (double)rtol, (double)atol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx)
{
  return TURGOR_GUARDED({
    FE2Run   *run = (FE2Run *)ctx;
    PetscBool ok;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    run->model_.SetEvaluationTime(t);
    PetscCall(run->model_.IFunction(U, Udot, F, &ok));
    if (!ok) { /* reject: the nonlinear solve fails and TS retries with a smaller step */
      SNES snes;
      PetscCall(TSGetSNES(ts, &snes));
      PetscCall(SNESSetFunctionDomainError(snes));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FE2Run::IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  return TURGOR_GUARDED({
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
    run->model_.SetEvaluationTime(t);
    PetscCall(run->model_.IJacobian(U, shift, B, &ok, refresh));
    if (A != B) {
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FE2Run::RHSFunction(TS ts, PetscReal t, Vec U, Vec G, void *ctx)
{
  return TURGOR_GUARDED({
    FE2Run   *run = (FE2Run *)ctx;
    PetscBool ok, answered;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    PetscCall(run->ObserveRHS(t, U, G, &answered)); /* a restart's first derivative, the FSAL stage */
    if (answered) PetscFunctionReturn(PETSC_SUCCESS);
    run->model_.SetEvaluationTime(t);
    PetscCall(run->model_.RHSFunction(U, G, &ok));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* Called by TS on every stage before it is used: evaluating the materials here (cached for the
   function evaluation that follows) lets an explicit integrator reject a step whose stage makes a
   material point fail. Implicit integrators learn it from the nonlinear solve (domain error). */
PetscErrorCode FE2Run::CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept)
{
  return TURGOR_GUARDED({
    FE2Run *run;
    PetscFunctionBeginUser;
    PetscCall(TSGetApplicationContext(ts, &run));
    *accept = PETSC_TRUE;
    if (!run->explicit_) PetscFunctionReturn(PETSC_SUCCESS); /* implicit: the nonlinear solve rejects */
    run->model_.SetEvaluationTime(t);
    PetscCall(run->model_.EvaluateMaterials(U, false, accept, NULL));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FE2Run::AfterStep(PetscReal t, Vec U)
{
  PetscFunctionBeginUser;
  PetscCall(model_.CommitMaterials());
  steps_since_refresh_++;
  failures_in_step_ = model_.StressFailures() - failures_by_step_;
  failures_by_step_ = model_.StressFailures();
  if (stop_at_localisation_ && localisation_time_ >= 0) { /* found by the last snapshot (the monitor runs after this hook) */
    char why[256];
    PetscCall(PetscSNPrintf(why, sizeof why, "localisation: element %" PetscInt_FMT " lost ellipticity (min det Q = %g (N/m)^2) at the snapshot at t = %g µs",
                            localisation_element_, (double)localisation_det_, (double)localisation_time_));
    PetscCall(StopAfterThisStep("localised", why));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The integrator cannot pass t, its last try found no stress at a material point (or, where it crawled
   on with a step below -ts_adapt_dt_min, the tries of that step did; a tangent that fails at a found
   equilibrium does not count): the point finds no equilibrium near
   its last one however short the step (an RVE that gives way: the stress branch it followed ends),
   the dynamic counterpart of -mode fe2_static's no_equilibrium; localisation at the last accepted
   time. With -fe2_stop_at_localisation the run ends there, localised; otherwise it fails as before,
   the localisation printed. */
PetscErrorCode FE2Run::EndWhereStuck(PetscReal t, bool crawled, std::string *status, std::string *reason)
{
  PetscFunctionBeginUser;
  const bool material = crawled ? failures_in_step_ > 0 : model_.LastStressFailed();
  if (!material || localisation_time_ >= 0) PetscFunctionReturn(PETSC_SUCCESS); /* not the material's doing, or found before */
  localisation_time_    = t;
  localisation_element_ = model_.LastFailedElement();
  no_equilibrium_       = true;
  char why[256];
  PetscCall(PetscSNPrintf(why, sizeof why,
                          "localisation: a material point of element %" PetscInt_FMT
                          " finds no equilibrium beyond t = %g µs (its evaluation fails in the integrator's every try, however short, until it gives up)",
                          localisation_element_, (double)t));
  PetscCall(PetscPrintf(comm_, "  t = %g µs: %s%s\n", (double)t, why, stop_at_localisation_ ? "; stopping (-fe2_stop_at_localisation)" : ""));
  if (!stop_at_localisation_) PetscFunctionReturn(PETSC_SUCCESS);
  *status = "localised";
  *reason = why;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A TS monitor: called at the initial state (step 0) and after every accepted step, after
   AfterStep (TS post-step); the monitor evaluates the material points for output only. */
PetscErrorCode FE2Run::EigenMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  return TURGOR_GUARDED({
    FE2Run *run = (FE2Run *)ctx;
    PetscFunctionBeginUser;
    run->model_.SetEvaluationTime(t);
    PetscCall(run->monitor_.Check(step, t, U));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FE2Run::Observe(PetscReal t, Vec U, std::vector<PetscReal> &row)
{
  PetscReal uy;
  PetscFunctionBeginUser;
  PetscCall(model_.TipDisplacement(U, &uy));
  row = {uy};
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::WriteSnapshot(PetscReal t, Vec U)
{
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(model_.EvaluateCellStress(U, &ok)); /* the stresses at U, without changing the run */
  if (model_.Spec().acoustic_field && localisation_time_ < 0) {
    PetscReal det;
    PetscInt  element;
    PetscCall(model_.LowestAcoustic(&det, &element));
    if (element >= 0 && !(det > 0)) {
      localisation_time_    = t;
      localisation_det_     = det;
      localisation_element_ = element;
      PetscCall(PetscPrintf(comm_, "  t = %g µs: localisation: element %" PetscInt_FMT " lost ellipticity (min det of the acoustic tensor %g (N/m)^2)%s\n",
                            (double)t, element, (double)det, stop_at_localisation_ ? "; stopping after the next step (-fe2_stop_at_localisation)" : ""));
    }
  }
  PetscCall(fields_.Write(model_, U, t));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::OpenSnapshots()
{
  PetscFunctionBeginUser;
  if (!RestartFile().empty()) { /* a restart's snapshots go beside the interrupted run's, which stay whole */
    char base[64];
    PetscCall(PetscSNPrintf(base, sizeof base, "coarse_restart_%08" PetscInt_FMT, RestartStep()));
    PetscCall(fields_.Open(model_, out_.dir, base));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(fields_.Open(model_, out_.dir, "coarse"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- checkpoints ---- */

PetscErrorCode FE2Run::CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp)
{
  PetscFunctionBeginUser;
  if (mesh_hash_.empty()) {
    /* FNV-1a over every vertex's coordinates in the order of their values: the same mesh gives the
       same hash on any number of ranks */
    Vec                coords;
    const PetscScalar *x;
    PetscInt           n;
    PetscMPIInt        size;
    PetscCall(DMGetCoordinates(model_.GetDM(), &coords));
    PetscCall(VecGetLocalSize(coords, &n));
    PetscCall(VecGetArrayRead(coords, &x));
    std::vector<PetscReal> mine(n);
    for (PetscInt k = 0; k < n; k++) mine[k] = PetscRealPart(x[k]);
    PetscCall(VecRestoreArrayRead(coords, &x));
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
    const PetscMPIInt        nm = (PetscMPIInt)n;
    PetscCallMPI(MPI_Allgather(&nm, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_));
    for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
    std::vector<PetscReal> all(displs[size]);
    PetscCallMPI(MPI_Allgatherv(mine.data(), nm, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, comm_));
    std::vector<std::pair<PetscReal, PetscReal>> v(all.size() / 2);
    for (size_t k = 0; k < v.size(); k++) v[k] = {all[2 * k], all[2 * k + 1]};
    std::sort(v.begin(), v.end());
    std::uint64_t        g = 1469598103934665603ull;
    const unsigned char *b = (const unsigned char *)v.data();
    for (size_t k = 0; k < v.size() * sizeof(v[0]); k++) g = (g ^ b[k]) * 1099511628211ull;
    char hex[24];
    PetscCall(PetscSNPrintf(hex, sizeof hex, "%016llx", (unsigned long long)g));
    mesh_hash_ = hex;
  }
  /* what the options do not show: the mesh itself (its options are PETSc's, a file may change) and
     what it makes of them; the physics parameters are compared one by one besides */
  fp.push_back({"elements", std::to_string((long long)model_.NumElements())});
  fp.push_back({"material_points", std::to_string((long long)model_.NumMaterialPoints())});
  fp.push_back({"mesh_coordinates_hash", mesh_hash_});
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2Run::DeclareState(std::deque<StateDeclaration> &decls)
{
  PetscFunctionBeginUser;
  decls.emplace_back("fe2");
  decls.back().Scalar("steps_since_jacobian", &steps_since_refresh_, Combine::Owner);
  decls.back().Scalar("rejections_at_jacobian", &rejections_at_refresh_, Combine::Owner);
  decls.back().Scalar("localisation_time", &localisation_time_, Combine::Owner);
  decls.back().Scalar("localisation_det", &localisation_det_, Combine::Owner);
  decls.back().Scalar("localisation_element", &localisation_element_, Combine::Owner);
  PetscCall(model_.DeclareState(decls, U_));
  PetscCall(model_.RankFreePointIds(point_ids_));
  point_of_id_.clear();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A material point is numbered by its index in the pool's global order here (the coarse model's
   points are this rank's cells' in turn; the pool deals them out in blocks), its id by its element's
   position. */
std::uint64_t FE2Run::EntityId(StateEntity e, PetscInt g) const
{
  if (e != StateEntity::MaterialPoint) return (std::uint64_t)g;
  return (std::uint64_t)point_ids_[g];
}

PetscInt FE2Run::EntityLocal(StateEntity e, std::uint64_t id) const
{
  if (e != StateEntity::MaterialPoint) return -1;
  if (point_of_id_.empty())
    for (size_t g = 0; g < point_ids_.size(); g++) point_of_id_.emplace(point_ids_[g], (PetscInt)g);
  auto it = point_of_id_.find((PetscInt)id);
  return it == point_of_id_.end() ? -1 : it->second;
}

/* a point is held by the group whose block has it */
bool FE2Run::EntityOwned(StateEntity e, PetscInt g) const
{
  if (e != StateEntity::MaterialPoint) return true;
  return g >= model_.Pool().GroupBegin() && g < model_.Pool().GroupEnd();
}

/* This rank's points and unknowns: the same on a rank of another run with the same mesh partition and
   blocks. */
std::uint64_t FE2Run::LayoutHash() const
{
  std::uint64_t h = TimeRun::LayoutHash();
  for (std::uint64_t v : {(std::uint64_t)model_.FirstPoint(), (std::uint64_t)model_.NumMaterialPoints(), (std::uint64_t)model_.Pool().GroupBegin(),
                          (std::uint64_t)model_.Pool().GroupEnd(), (std::uint64_t)model_.Pool().CommSize()})
    h = (h ^ v) * 1099511628211ull;
  return h;
}

/* every state is kept by rank-free ids, a material point's by its group's first rank (one per point) */
bool FE2Run::RestartsOnOtherRanks(std::string *) const
{
  return true;
}

PetscErrorCode FE2Run::AddSummary(JsonObject &js)
{
  PetscInt         snes_its, ksp_its, per[2];
  MaterialCounters rc;
  PetscBool        arkimex;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSARKIMEX, &arkimex));
  if (arkimex) {
    TSARKIMEXType ark;
    PetscCall(TSARKIMEXGetType(ts_, &ark));
    js.Set("ts_type", std::string("arkimex ") + ark + " (fully implicit)");
  }
  PetscCall(TSGetSNESIterations(ts_, &snes_its));
  PetscCall(TSGetKSPIterations(ts_, &ksp_its));
  PetscCall(model_.Pool().GlobalCounters(&rc));
  const CoarseCounters &cc = model_.Counters();
  /* particles: of one material point, and in all of them together */
  model_.Pool().Model().ParticlesPerPoint(&per[0], &per[1]);
  const PetscInt npts = model_.NumMaterialPoints();
  js.Set("jacobian_evals", cc.tangent_evals);
  js.Set("material", model_.Pool().MaterialName());
  js.Set("element", model_.ElementName());
  js.Set("quadrature", model_.QuadratureName());
  js.Set("n_elements", model_.NumElements());
  js.Set("n_material_points", npts);
  js.Set("n_wall_particles", per[0] * npts);
  js.Set("n_fluid_particles", per[1] * npts);
  js.Set("rve_wall_particles", per[0]);
  js.Set("rve_fluid_particles", per[1]);
  js.Set("physics", model_.Pool().Model().Physics());
  PetscCall(model_.Pool().DescribePoints(js, npts));
  js.Set("rve_solves", rc.solves);
  js.Set("rve_tangent_solves", rc.tangent_solves);
  js.Set("material_tangent", TangentMethodName(model_.Pool().Tangent().method));
  js.Set("rve_exact_tangents", rc.exact_tangents);
  js.Set("rve_tangent_linear_its", rc.tangent_linear_its);
  js.Set("rve_tangent_force_evals", rc.tangent_force_evals);
  js.Set("rve_output_solves", rc.output_solves);
  js.Set("psi_tc_iterations", rc.iterations);
  js.Set("rve_predicted_solves", rc.predicted_solves);
  js.Set("rve_skipped_solves", rc.skipped_solves);
  js.Set("rve_failures", rc.failures);
  js.Set("material_evaluations", cc.material_evals);
  js.Set("material_failures", cc.failures); /* evaluations in which some material point failed */
  js.Set("snes_its", snes_its);
  js.Set("ksp_its", ksp_its);
  {
    /* where the time went: material points (trial), their tangents, the coarse assembly (f_int, K,
       C; explicit: the mass solves), and the rest (integrator, the coarse LU factorisations and
       solves, output) */
    PetscReal       trial, tangents, coarse = model_.CoarseAssemblyTime();
    const PetscReal wall = WallTime();
    PetscCall(model_.Pool().GlobalTimes(&trial, &tangents));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &coarse, 1, MPIU_REAL, MPIU_MAX, comm_));
    js.Set("time_material_points_s", trial);
    js.Set("time_tangents_s", tangents);
    js.Set("time_coarse_assembly_s", coarse);
    js.Set("time_integrator_and_linear_algebra_s", wall - trial - tangents - coarse);
  }
  js.Set("pool_remote_bytes_per_evaluation", model_.Pool().RemoteBytesPerEvaluation());
  /* -material_rebalance: the groups' measured cost, largest over mean, before and after */
  js.Set("material_cost_imbalance_before", model_.Pool().CostImbalanceBefore());
  js.Set("material_cost_imbalance_after", model_.Pool().CostImbalanceAfter());
  js.Set("material_points_moved", model_.Pool().PointsMoved());
  AddLocalisation(js);
  if (monitor_.Active()) monitor_.AddSummary(js);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -1 and "": no localisation found (by a snapshot that lost ellipticity, or a point without equilibrium) */
void FE2Run::AddLocalisation(JsonObject &js) const
{
  if (!model_.Spec().acoustic_field) return;
  js.Set("localisation_time", localisation_time_);
  js.Set("localisation_element", localisation_element_);
  js.Set("localisation_criterion", localisation_time_ < 0 ? "" : no_equilibrium_ ? "no_equilibrium" : "acoustic");
}

PetscErrorCode FE2Run::DoneDetails(std::string *details)
{
  MaterialCounters      rc;
  const CoarseCounters &cc = model_.Counters();
  PetscFunctionBeginUser;
  PetscCall(model_.Pool().GlobalCounters(&rc));
  *details = std::to_string(cc.residuals) + " function and " + std::to_string(cc.tangent_evals) + " Jacobian evaluations, " + std::to_string(rc.solves) +
             " RVE solves (" + std::to_string(rc.tangent_solves) + " for tangents)";
  if (rc.exact_tangents)
    *details += ", " + std::to_string(rc.exact_tangents) + " exact tangents (" + std::to_string(rc.tangent_linear_its) + " Krylov iterations)";
  if (monitor_.Active()) *details += "; stability monitor: " + monitor_.Report();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
