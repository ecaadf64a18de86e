#include <turgor/core/errors.h>
#include <turgor/core/log.h>
#include <turgor/modes/fe2_static_run.h>
#include <cmath>

namespace turgor {

PetscErrorCode StaticLoadSpec::SetFromOptions(MPI_Comm comm)
{
  PetscBool snap = snapshot ? PETSC_TRUE : PETSC_FALSE, stop = stop_at_localisation ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "fe2_static_", "Static FE^2 solve with load stepping (-mode fe2_static); its SNES: -fe2_static_snes_*, -fe2_static_ksp_*", "turgor");
  PetscCall(PetscOptionsInt("-load_steps",
                            "Initial number of load increments: the loads (the body force, -coarse_boundary_gradient) are applied in increments of the load "
                            "factor of 1/load_steps",
                            "StaticLoadSpec", load_steps, &load_steps, NULL));
  PetscCall(PetscOptionsReal("-min_increment",
                             "Smallest increment of the load factor: a failed increment is halved and retried, and the run fails when it would fall below "
                             "this, in (0, 1]",
                             "StaticLoadSpec", min_increment, &min_increment, NULL));
  PetscCall(PetscOptionsBool("-snapshots", "Write coarse.h5/coarse.xmf with the final state (on failure: the last converged one)", "StaticLoadSpec", snap,
                             &snap, NULL));
  PetscCall(PetscOptionsReal("-softening_cosine",
                             "Localisation: a material point softened at a converged load level when the cosine of the angle between its increments of "
                             "the second Piola-Kirchhoff stress and the Green-Lagrange strain since the last level is below this (Hill's second-order "
                             "work dS:dE < 0 at 0), in [-1, 0]",
                             "StaticLoadSpec", softening_cosine, &softening_cosine, NULL));
  PetscCall(PetscOptionsBool("-stop_at_localisation",
                             "End the run (status localised) at the first converged load level at which a material point softened, or beyond which one "
                             "finds no equilibrium (its evaluation fails down to -fe2_static_min_increment)",
                             "StaticLoadSpec", stop, &stop, NULL));
  PetscOptionsEnd();
  PetscCheck(softening_cosine >= -1 && softening_cosine <= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_softening_cosine = %g: must be in [-1, 0]",
             (double)softening_cosine);
  stop_at_localisation = stop;
  PetscCheck(load_steps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_load_steps = %" PetscInt_FMT ": must be >= 1", load_steps);
  PetscCheck(min_increment > 0 && min_increment <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_min_increment = %g: must be in (0, 1]",
             (double)min_increment);
  snapshot = snap;
  PetscFunctionReturn(PETSC_SUCCESS);
}

FE2StaticRun::~FE2StaticRun()
{
  PetscCallVoid(SNESDestroy(&snes_));
  PetscCallVoid(MatDestroy(&K_));
  PetscCallVoid(MatDestroy(&J_));
  PetscCallVoid(ISDestroy(&is_u_));
  PetscCallVoid(ISDestroy(&is_v_));
  for (Vec *v : {&U_, &Udot_, &Ffull_, &x_, &x_conv_, &x_affine_}) PetscCallVoid(VecDestroy(v));
}

PetscErrorCode FE2StaticRun::SetFromOptions()
{
  PetscMPIInt size;
  KSP         ksp;
  PC          pc;
  PetscFunctionBeginUser;
  /* the output directory first: an option refused below then leaves a summary.json that says so */
  PetscCall(PrepareOutputDirectory()); /* not prepared under -help */
  /* as -mode fe2: an RVE's Psi-tc tolerance 1e-9 unless -rve_psi_atol says otherwise */
  model_.Pool().SetDefaultTolerance(1e-9);
  /* v = 0: the damping C (from D^v) never enters the static system, so its 3 perturbed
     material evaluations per point are not made */
  model_.Pool().Tangent().viscosity = false;
  PetscCall(load_.SetFromOptions(comm_));
  PetscCall(load_.RequireUnscheduled(comm_, "fe2_static"));
  model_.SetLoad(load_);
  PetscCall(model_.SetFromOptions());
  PetscCall(spec_.SetFromOptions(comm_));
  PetscCall(monitor_.SetFromOptions("fe2_static_", "converged load levels", "load_factor"));
  /* the nonlinear solver, with defaults through the API (the user's -fe2_static_snes_* win at
     SNESSetFromOptions in SetUp): Newton with full steps, the load cut-back being its
     globalisation -- a line search on |R| (bt, PETSc's default) takes steps of 0.1 on a bending
     cantilever, whose axial residuals grow along a good bending step (65 Newton iterations and a
     cut-back where full steps take 4, docs/benchmarks.md); -fe2_static_snes_linesearch_type cp
     (a critical point of the energy along the step) does large loads in fewer increments -- and a
     direct solve of the stiffness as -mode fe2 does (PCREDUNDANT on several ranks: the same result
     run to run) */
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(SNESCreate(comm_, &snes_));
  PetscCall(SNESSetOptionsPrefix(snes_, "fe2_static_"));
  PetscCall(SNESSetType(snes_, SNESNEWTONLS));
  {
    SNESLineSearch ls;
    PetscCall(SNESGetLineSearch(snes_, &ls));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  }
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, size > 1 ? PCREDUNDANT : PCLU));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Displacement-only system. The model's state is [u, v] per vertex and its F(U, Udot = 0) =
   [-v; f_int - f_ext] with Jacobian [[0, -I], [K, C]] at shift 0 would serve as it is, but its
   displacement rows have no diagonal (an LU without pivoting, PETSc's own, breaks down; only a
   pivoting one, MUMPS, works), it doubles the unknowns, and v = 0 would be enforced by the solver
   rather than by construction. Here the unknowns are the free displacements x, U = [x; 0], the
   residual is the velocity rows of F (f_int - lambda f_ext) and the Jacobian is the K block of the
   model's matrix (MatCreateSubMatrix on the free u columns and v rows): the textbook static
   problem, symmetric for a hyperelastic material, that any PETSc solver (-fe2_static_pc_type
   cholesky, gamg, ...) takes. */
PetscErrorCode FE2StaticRun::SetUp()
{
  PetscInt  n;
  PetscReal scale[2];
  PetscFunctionBeginUser;
  PetscCheck(snes_, comm_, PETSC_ERR_ORDER, "SetFromOptions() must be called before SetUp()");
  PetscCall(RegisterLogStage("fe2_static setup", &stage_setup_));
  PetscCall(RegisterLogStage("fe2_static solve", &stage_solve_));
  PetscCall(PetscLogEventRegister("TgLoadIncrement", PETSC_OBJECT_CLASSID, &ev_increment_));
  PetscCall(PetscLogEventRegister("TgOutput", PETSC_OBJECT_CLASSID, &ev_output_));
  PetscCall(PetscLogStagePush(stage_setup_));
  PetscCall(model_.SetLoadFactor(0)); /* unloaded: the clamped vertices where they are (-coarse_boundary_gradient) */
  PetscCall(model_.SetUp());
  PetscCall(model_.CreateGlobalVector(&U_));
  PetscCall(PetscObjectSetName((PetscObject)U_, "state"));
  PetscCall(VecZeroEntries(U_));
  PetscCall(VecDuplicate(U_, &Udot_));
  PetscCall(VecZeroEntries(Udot_));
  PetscCall(VecDuplicate(U_, &Ffull_));
  PetscCall(MatDuplicate(model_.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &J_)); /* the model's pattern */
  PetscCall(model_.CreateFreeIS(&is_u_, &is_v_));
  PetscCall(ISGetLocalSize(is_u_, &n));
  PetscCall(VecCreateMPI(comm_, n, PETSC_DETERMINE, &x_));
  PetscCall(VecZeroEntries(x_));
  PetscCall(VecDuplicate(x_, &x_conv_));
  PetscCall(VecZeroEntries(x_conv_));
  PetscCall(MatCreateSubMatrix(J_, is_v_, is_u_, MAT_INITIAL_MATRIX, &K_));
  if (model_.Spec().HasBoundaryGradient()) { /* the increments' predictor: H X on the free nodes */
    const Tensor2 H = model_.Spec().boundary_gradient;
    std::string   missing;
    PetscCall(VecDuplicate(x_, &x_affine_));
    PetscCall(model_.NodeState(
      U_,
      [&H](const PetscReal X[2], PetscReal state[4]) {
        H.Apply(X, state);
        state[2] = state[3] = 0;
        return true;
      },
      &missing));
    PetscCall(VecISCopy(U_, is_u_, SCATTER_REVERSE, x_affine_));
    PetscCall(VecZeroEntries(U_));
  }
  {
    Vec r;
    PetscCall(VecDuplicate(x_, &r));
    PetscCall(SNESSetFunction(snes_, r, Residual, this));
    PetscCall(VecDestroy(&r));
  }
  PetscCall(SNESSetJacobian(snes_, K_, K_, Jacobian, this));
  /* the force scale of the problem, |f_ext| or, without a load, the material's own |f_int(0)|
     (an RVE's stress at rest): the absolute tolerance is 1e-10 of it, a floor under the relative
     one (1e-8 of each increment's initial residual) that tiny increments and round-off reach.
     With prescribed displacements the load's residual is found at a small load factor and scaled
     up: the whole boundary motion at once, the free nodes at rest, would strain the boundary
     elements far beyond what any increment does (an RVE may fail there). */
  {
    const bool      moved = model_.Spec().HasBoundaryGradient();
    const PetscReal probe = moved ? 1e-3 / (PetscReal)spec_.load_steps : 1;
    Vec             r0, r1;
    PetscCall(VecDuplicate(x_, &r0));
    PetscCall(VecDuplicate(x_, &r1));
    PetscCall(model_.SetLoadFactor(0));
    PetscCall(Residual(snes_, x_, r0, this));
    PetscCall(model_.SetLoadFactor(probe));
    PetscCall(Residual(snes_, x_, r1, this));
    if (moved) PetscCall(model_.RevertMaterials()); /* the probe's trial states left behind */
    PetscCall(VecNorm(r0, NORM_2, &scale[0]));
    PetscCall(VecAXPY(r1, -1.0, r0));
    PetscCall(VecNorm(r1, NORM_2, &scale[1]));
    scale[1] /= probe;
    PetscCall(VecDestroy(&r0));
    PetscCall(VecDestroy(&r1));
    PetscCheck(std::isfinite(scale[0]), comm_, PETSC_ERR_NOT_CONVERGED, "The material fails at rest (F = I)");
    force_scale_ = PetscMax(scale[0], scale[1]);
  }
  PetscCall(SNESSetTolerances(snes_, force_scale_ > 0 ? 1e-10 * force_scale_ : PETSC_DEFAULT, 1e-8, PETSC_DEFAULT, 25, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(snes_));
  PetscCall(SNESSetConvergenceHistory(snes_, NULL, NULL, PETSC_DECIDE, PETSC_TRUE)); /* each solve's initial residual */
  {
    PetscReal atol, rtol, stol;
    PetscInt  maxit, maxf;
    PetscCall(SNESGetTolerances(snes_, &atol, &rtol, &stol, &maxit, &maxf));
    PetscCheck(std::isfinite(atol) && atol >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_snes_atol = %g: must be finite and >= 0", (double)atol);
    PetscCheck(std::isfinite(rtol) && rtol >= 0 && rtol < 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_snes_rtol = %g: must be in [0, 1)",
               (double)rtol);
    PetscCheck(maxit >= 1, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -fe2_static_snes_max_it = %" PetscInt_FMT ": must be >= 1", maxit);
  }
  {
    PetscMPIInt rank, size;
    SNESType    type;
    PetscReal   atol, rtol;
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCall(SNESGetType(snes_, &type));
    PetscCall(SNESGetTolerances(snes_, &atol, &rtol, NULL, NULL, NULL));
    PetscCall(PetscPrintf(comm_,
                          "turgor fe2_static: %" PetscInt_FMT " elements, %" PetscInt_FMT " material points (%s, %s), %d MPI ranks in %" PetscInt_FMT
                          " material-point groups\n",
                          model_.NumElements(), model_.NumMaterialPoints(), model_.Pool().MaterialName(), model_.QuadratureDescription(), size,
                          model_.Pool().NumGroups()));
    PetscCall(model_.Pool().Model().View(PETSC_VIEWER_STDOUT_(comm_)));
    PetscCall(
      PetscPrintf(comm_,
                  "Static equilibrium f_int(u) = lambda f_ext, body force (%g, %g) µm/µs^2 x rho0 %.6g ng/µm^2 (|f_ext| = %.4g µN, |f_int(0)| = %.4g µN), "
                  "lambda in increments of 1/%" PetscInt_FMT " (at least %g); SNES %s, rtol = %g, atol = %g\n",
                  (double)load_.body_acceleration[0], (double)load_.body_acceleration[1], (double)model_.ReferenceDensity(), (double)scale[1], (double)scale[0],
                  spec_.load_steps, (double)spec_.min_increment, type, (double)rtol, (double)atol));
    if (model_.Spec().HasBoundaryGradient()) {
      const Tensor2 &H = model_.Spec().boundary_gradient;
      PetscCall(PetscPrintf(comm_,
                            "  and the clamped vertices at lambda H X, H = [%g %g; %g %g] (-coarse_boundary_gradient): |f_ext| is the residual of the "
                            "whole load with the free nodes at rest\n",
                            (double)H(0, 0), (double)H(0, 1), (double)H(1, 0), (double)H(1, 1)));
    }
    if (rank == 0 && HasOutputDirectory())
      PetscCall(tip_csv_.Open(PETSC_COMM_SELF, OutputPath("tip.csv"),
                              {"load_factor", "tip_displacement_y", "snes_its", "tip_displacement_x", "mean_s11", "mean_s22", "mean_s12", "softening_cosine"}));
  }
  if (spec_.snapshot && HasOutputDirectory()) PetscCall(fields_.Open(model_, OutputDir(), "coarse"));
  PetscCall(monitor_.SetUp(model_, HasOutputDirectory() ? OutputDir() : std::string()));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2StaticRun::ToState(Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(VecISCopy(U_, is_u_, SCATTER_FORWARD, x)); /* the velocity part of U_ stays 0 */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* r = f_int(u) - lambda f_ext on the free dofs; NaN and a domain error when a material point fails
   (the increment is then cut back). */
PetscErrorCode FE2StaticRun::Residual(SNES snes, Vec x, Vec r, void *ctx)
{
  return TURGOR_GUARDED({
    FE2StaticRun *run = (FE2StaticRun *)ctx;
    PetscBool     ok;
    PetscFunctionBeginUser;
    PetscCall(run->ToState(x));
    PetscCall(run->model_.IFunction(run->U_, run->Udot_, run->Ffull_, &ok));
    if (ok) PetscCall(VecISCopy(run->Ffull_, run->is_v_, SCATTER_REVERSE, r));
    else {
      PetscCall(VecSet(r, NAN));
      PetscCall(SNESSetFunctionDomainError(snes));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* K = d f_int / d u from the materials' tangents (the model's Jacobian at shift 0, its K block). */
PetscErrorCode FE2StaticRun::Jacobian(SNES snes, Vec x, Mat A, Mat B, void *ctx)
{
  return TURGOR_GUARDED({
    FE2StaticRun *run = (FE2StaticRun *)ctx;
    PetscBool     ok;
    PetscFunctionBeginUser;
    PetscCall(run->ToState(x));
    PetscCall(run->model_.IJacobian(run->U_, 0.0, run->J_, &ok));
    if (!ok) PetscCall(SNESSetJacobianDomainError(snes));
    PetscCall(MatCreateSubMatrix(run->J_, run->is_v_, run->is_u_, MAT_REUSE_MATRIX, &B));
    if (A != B) {
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* Newton from the last converged displacements at load factor lambda. On success the material
   points are at the solution (evaluated there last) and committed; on failure reverted. */
PetscErrorCode FE2StaticRun::SolveAt(PetscReal lambda, bool *converged, std::string *why)
{
  SNESConvergedReason reason;
  PetscInt            its, lits;
  char                where[64];
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_increment_, 0, 0, 0, 0));
  PetscCall(PetscSNPrintf(where, sizeof where, "at load factor %.6g", (double)lambda));
  model_.SetEvaluationWhere(where);
  PetscCall(model_.SetLoadFactor(lambda));
  const PetscInt failures = model_.Counters().failures, stress_failures = model_.StressFailures();
  PetscCall(VecCopy(x_conv_, x_));
  if (x_affine_) PetscCall(VecAXPY(x_, lambda - lambda_, x_affine_)); /* the clamped vertices' motion, carried through */
  PetscCall(SNESSolve(snes_, NULL, x_));
  PetscCall(SNESGetConvergedReason(snes_, &reason));
  PetscCall(SNESGetIterationNumber(snes_, &its));
  PetscCall(SNESGetLinearSolveIterations(snes_, &lits));
  solves_++;
  snes_its_ += its;
  ksp_its_ += lits;
  *converged = reason > 0;
  if (reason == SNES_CONVERGED_SNORM_RELATIVE) {
    /* a step below -snes_stol of the solution: Newton at the round-off (or an RVE's accuracy)
       floor, or a line search that stalled far from it; only the first is a solution */
    PetscReal *hist;
    PetscInt   nhist;
    PetscReal  fnorm, atol;
    Vec        F;
    PetscCall(SNESGetConvergenceHistory(snes_, &hist, NULL, &nhist));
    PetscCall(SNESGetFunction(snes_, &F, NULL, NULL));
    PetscCall(VecNorm(F, NORM_2, &fnorm)); /* at the final iterate (the history stops one short) */
    PetscCall(SNESGetTolerances(snes_, &atol, NULL, NULL, NULL, NULL));
    /* the floor: 1e-4 of where the increment started, or the residual the last converged state
       reached (the RVEs' relaxation accuracy, which no Newton step lowers: an increment that
       starts there, as a zero load's does, cannot fall by 1e-4) */
    const PetscReal floor = PetscMax(PetscMax(atol, 1e-4 * (nhist > 0 ? hist[0] : 0)), 2 * residual_conv_);
    if (nhist > 0 && !(fnorm <= floor)) {
      *converged = false;
      char buf[256];
      PetscCall(PetscSNPrintf(buf, sizeof buf, "the Newton steps stalled (SNES CONVERGED_SNORM_RELATIVE) at residual %.3g, %.2g of the initial %.3g",
                              (double)fnorm, (double)(fnorm / hist[0]), (double)hist[0]));
      *why = buf;
    }
  }
  if (*converged) {
    /* the material points' current states must be the solution's (the last evaluation normally
       is; the cache makes this free then) */
    PetscBool   ok;
    std::string what;
    PetscCall(ToState(x_));
    PetscCall(model_.EvaluateMaterials(U_, false, &ok, &what));
    *converged = ok;
    if (!ok) *why = "material points failed at the converged state: " + what;
  } else if (reason <= 0)
    *why = std::string(model_.Counters().failures > failures ? "material points failed, " : "") + "SNES " + SNESConvergedReasons[reason] + " after " +
           std::to_string(its) + " iterations";
  if (*converged) {
    Vec F;
    PetscCall(SNESGetFunction(snes_, &F, NULL, NULL));
    PetscCall(VecNorm(F, NORM_2, &residual_conv_));
    PetscCall(model_.CommitMaterials());
    /* at the converged state, evaluated last: 1e-6 of |S| is well above the materials' accuracy
       (an RVE relaxed to 1e-9) and well below a softening point's stress drop */
    PetscCall(model_.SofteningSinceLast(1e-6, &softening_cosine_, &softening_element_));
    PetscCall(model_.MeanStress(mean_stress_));
  } else {
    failed_solves_++;
    failed_in_material_ = model_.StressFailures() > stress_failures; /* a relaxation failed (a tangent failing at a found equilibrium does not count) */
    PetscCall(model_.RevertMaterials());
  }
  PetscCall(PetscLogEventEnd(ev_increment_, 0, 0, 0, 0));
  if (*converged) PetscCall(Record(lambda, its));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2StaticRun::Record(PetscReal lambda, PetscInt its)
{
  PetscFunctionBeginUser;
  PetscCall(ToState(x_));
  PetscCall(VecCopy(x_, x_conv_));
  lambda_ = lambda;
  PetscCall(model_.TipDisplacement(U_, &tip_, &tip_x_));
  if (tip_csv_.IsOpen()) PetscCall(tip_csv_.Row({lambda, tip_, (PetscReal)its, tip_x_, mean_stress_[0], mean_stress_[1], mean_stress_[2], softening_cosine_}));
  PetscCall(CheckOutputError(comm_, tip_csv_.Error())); /* rank 0 writes it */
  PetscCall(PetscPrintf(comm_, "  load factor %-10.6g (increment %.4g): %2" PetscInt_FMT " Newton iterations, tip displacement %.8g µm\n", (double)lambda,
                        (double)increment_, its, (double)tip_));
  softening_min_ = PetscMin(softening_min_, softening_cosine_);
  if (localisation_load_factor_ < 0 && softening_cosine_ < spec_.softening_cosine) {
    localisation_load_factor_ = lambda;
    localisation_element_     = softening_element_;
    localisation_cosine_      = softening_cosine_;
    localisation_criterion_   = "softening";
    PetscCall(PetscPrintf(comm_,
                          "  load factor %g: localisation: a material point of element %" PetscInt_FMT
                          " softened (its stress fell along its strain increment: cos(dS, dE) = %.3g < %g)%s\n",
                          (double)lambda, softening_element_, (double)softening_cosine_, (double)spec_.softening_cosine,
                          spec_.stop_at_localisation ? "; stopping (-fe2_static_stop_at_localisation)" : ""));
  }
  PetscCall(monitor_.Check(levels_++, lambda, U_)); /* level 0: the load factor 0 */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2StaticRun::ConvergedState(Vec U)
{
  PetscFunctionBeginUser;
  PetscCall(ToState(x_conv_));
  PetscCall(VecCopy(U_, U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Load stepping. lambda = 0 first: the equilibrium without load (none to find for a material that
   is stress-free at rest; an RVE's stress at rest may deform the tissue). Then increments of
   1/load_steps: a failed one (SNES diverged, a material point failed) is halved and retried from
   the last converged state; after two converged increments in a row the increment doubles again,
   up to 1/load_steps; below -fe2_static_min_increment the run fails. */
PetscErrorCode FE2StaticRun::Solve()
{
  bool        ok;
  std::string why;
  PetscFunctionBeginUser;
  PetscCall(PetscLogStagePush(stage_solve_));
  solving_ = true;
  PetscCall(PetscTime(&t0_));
  increment_ = 0;
  PetscCall(SolveAt(0.0, &ok, &why));
  if (!ok) {
    PetscCall(PetscTime(&wall_));
    wall_ -= t0_;
    last_failure_ = why;
    SETERRQ(comm_, PETSC_ERR_NOT_CONVERGED,
            "The fe2_static solve failed without load (load factor 0: the equilibrium under the material's own stress at rest): %s; try "
            "-fe2_static_snes_max_it, -fe2_static_snes_linesearch_type, or a material point that is stress-free at rest",
            why.c_str());
  }
  const PetscReal max_increment = 1.0 / (PetscReal)spec_.load_steps;
  PetscReal       dl            = max_increment;
  PetscInt        streak        = 0;
  while (lambda_ < 1) {
    PetscBool stop;
    if (spec_.stop_at_localisation && localisation_load_factor_ >= 0) {
      localised_ = true;
      break;
    }
    PetscCall(InterruptRequestedAll(comm_, &stop));
    if (stop) {
      interrupted_ = true;
      PetscCall(PetscPrintf(comm_, "Interrupted at load factor %g: stopping\n", (double)lambda_));
      break;
    }
    PetscReal target = lambda_ + dl;
    if (target > 1 - 1e-12) target = 1; /* no sliver of an increment left by round-off */
    increment_ = target - lambda_;
    PetscCall(SolveAt(target, &ok, &why));
    if (ok) {
      increments_++;
      if (++streak >= 2 && dl < max_increment) {
        dl     = PetscMin(2 * dl, max_increment);
        streak = 0;
      }
      continue;
    }
    cutbacks_++;
    streak        = 0;
    last_failure_ = why;
    dl            = 0.5 * (target - lambda_);
    PetscCall(PetscPrintf(comm_, "  load factor %-10.6g failed (%s): back to %g, increment halved to %.4g\n", (double)target, why.c_str(), (double)lambda_,
                          (double)dl));
    if (dl < spec_.min_increment && failed_in_material_ && localisation_load_factor_ < 0) {
      /* a material point finds no equilibrium near its last one however small the step: a limit
         point of its response (an RVE that gives way with no state near the last: the stress
         branch it followed ends) -- localisation too, at the last converged level */
      localisation_load_factor_ = lambda_;
      localisation_element_     = model_.LastFailedElement();
      localisation_criterion_   = "no_equilibrium";
      PetscCall(PetscPrintf(comm_,
                            "  load factor %g: localisation: a material point of element %" PetscInt_FMT
                            " finds no equilibrium beyond it (its evaluation fails at every increment down to -fe2_static_min_increment)%s\n",
                            (double)lambda_, localisation_element_, spec_.stop_at_localisation ? "; stopping (-fe2_static_stop_at_localisation)" : ""));
      if (spec_.stop_at_localisation) {
        localised_ = true;
        break;
      }
    }
    if (dl < spec_.min_increment) {
      PetscCall(PetscTime(&wall_));
      wall_ -= t0_;
      if (spec_.snapshot) { /* the last converged state, for a look at what went wrong */
        PetscBool sok;
        PetscCall(ToState(x_conv_));
        PetscCall(model_.EvaluateCellStress(U_, &sok));
        PetscCall(fields_.Write(model_, U_, lambda_));
      }
      SETERRQ(comm_, PETSC_ERR_NOT_CONVERGED,
              "The fe2_static solve reached load factor %g of 1 (tip displacement %g µm): the increment to %g failed (%s) and halving it would go "
              "below -fe2_static_min_increment = %g; the material-point failures printed above (if any) say where; try more -fe2_static_load_steps "
              "or a smaller -fe2_static_min_increment",
              (double)lambda_, (double)tip_, (double)target, why.c_str(), (double)spec_.min_increment);
    }
  }
  /* found at the last level (load factor 1): the run ends there either way, localised */
  if (spec_.stop_at_localisation && localisation_load_factor_ >= 0 && !interrupted_) localised_ = true;
  PetscCall(PetscTime(&wall_));
  wall_ -= t0_;
  if (spec_.snapshot) {
    PetscBool sok;
    PetscCall(PetscLogEventBegin(ev_output_, 0, 0, 0, 0));
    PetscCall(ToState(x_conv_));
    PetscCall(model_.EvaluateCellStress(U_, &sok));
    PetscCall(fields_.Write(model_, U_, lambda_));
    PetscCall(PetscLogEventEnd(ev_output_, 0, 0, 0, 0));
  }
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The keys a run reports completed or not; not collective (rank-local counts where it matters). */
PetscErrorCode FE2StaticRun::AddSummary(JsonObject &js)
{
  PetscMPIInt size;
  PetscReal   atol = 0, rtol = 0, stol = 0;
  PetscInt    maxit = 0, maxf = 0;
  SNESType    type = NULL;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  js.Set("material", model_.Pool().MaterialName());
  js.Set("element", model_.ElementName());
  js.Set("quadrature", model_.QuadratureName());
  js.Set("n_elements", model_.NumElements());
  js.Set("n_material_points", model_.NumMaterialPoints());
  js.Set("mpi_ranks", (PetscInt)size);
  js.Set("body_force", std::vector<PetscReal>{load_.body_acceleration[0], load_.body_acceleration[1]});
  if (snes_) {
    PetscCall(SNESGetType(snes_, &type));
    PetscCall(SNESGetTolerances(snes_, &atol, &rtol, &stol, &maxit, &maxf));
  }
  js.Set("snes_type", type ? type : "");
  js.Set("snes_rtol", rtol);
  js.Set("snes_atol", atol);
  js.Set("snes_stol", stol);
  js.Set("snes_max_it", maxit);
  js.Set("load_steps", spec_.load_steps);
  js.Set("min_increment", spec_.min_increment);
  js.Set("load_factor_final", lambda_);
  js.Set("load_increments", increments_);
  js.Set("load_cutbacks", cutbacks_);
  js.Set("nonlinear_solves", solves_);
  js.Set("failed_nonlinear_solves", failed_solves_);
  js.Set("snes_its", snes_its_);
  js.Set("ksp_its", ksp_its_);
  js.Set("rhs_evals", model_.Counters().residuals);
  js.Set("jacobian_evals", model_.Counters().tangent_evals);
  js.Set("material_evaluations", model_.Counters().material_evals);
  js.Set("material_failures", model_.Counters().failures);
  js.Set("force_scale", force_scale_);
  js.Set("tip_displacement_final", tip_);
  js.Set("tip_displacement_x_final", tip_x_);
  js.Set("wall_time_s", (PetscReal)wall_);
  js.Set("snapshots", fields_.Count());
  js.Set("mean_stress_final", std::vector<PetscReal>{mean_stress_[0], mean_stress_[1], mean_stress_[2]});
  js.Set("softening_cosine_threshold", spec_.softening_cosine);
  js.Set("softening_min_cosine", softening_min_);
  js.Set("localisation_load_factor", localisation_load_factor_);
  js.Set("localisation_element", localisation_element_);
  js.Set("localisation_cosine", localisation_cosine_);
  js.Set("localisation_criterion", localisation_criterion_);
  if (monitor_.Active()) monitor_.AddSummary(js);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2StaticRun::WriteSummary()
{
  JsonObject       js;
  MaterialCounters rc;
  PetscFunctionBeginUser;
  PetscCall(Summary(js, interrupted_ ? "interrupted" : localised_ ? "localised" : "completed"));
  if (interrupted_) js.Set("reason", "interrupted (SIGINT/SIGTERM): load_factor_final is below 1");
  else if (localised_) {
    char why[256];
    if (localisation_criterion_ == "softening")
      PetscCall(PetscSNPrintf(why, sizeof why,
                              "localisation (-fe2_static_stop_at_localisation): a material point of element %" PetscInt_FMT
                              " softened at load factor %g (cos(dS, dE) = %.3g)",
                              localisation_element_, (double)localisation_load_factor_, (double)localisation_cosine_));
    else
      PetscCall(PetscSNPrintf(why, sizeof why,
                              "localisation (-fe2_static_stop_at_localisation): a material point of element %" PetscInt_FMT
                              " finds no equilibrium beyond load factor %g",
                              localisation_element_, (double)localisation_load_factor_));
    js.Set("reason", why);
  }
  PetscCall(model_.Pool().GlobalCounters(&rc));
  PetscCall(model_.Pool().DescribePoints(js, model_.NumMaterialPoints()));
  js.Set("rve_solves", rc.solves);
  js.Set("rve_tangent_solves", rc.tangent_solves);
  js.Set("rve_output_solves", rc.output_solves);
  js.Set("psi_tc_iterations", rc.iterations);
  js.Set("rve_predicted_solves", rc.predicted_solves);
  js.Set("rve_skipped_solves", rc.skipped_solves);
  js.Set("rve_failures", rc.failures);
  PetscCall(CloseOutput(tip_csv_));
  PetscCall(monitor_.CloseOutputs());
  PetscCall(WriteSummaryFile(js));
  PetscCall(PetscPrintf(comm_,
                        "%s: load factor %g in %" PetscInt_FMT " increments (%" PetscInt_FMT " cut back), %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT
                        " function and %" PetscInt_FMT " Jacobian evaluations, %" PetscInt_FMT " RVE solves, %.3f s wall; final tip displacement %.8g µm\n"
                        "Outputs in %s: %s\n",
                        interrupted_ ? "Interrupted"
                        : localised_ ? "Localised"
                                     : "Done",
                        (double)lambda_, increments_, cutbacks_, snes_its_, model_.Counters().residuals, model_.Counters().tangent_evals, rc.solves,
                        (double)wall_, (double)tip_, OutputDir().c_str(), OutputFiles().c_str()));
  if (monitor_.Active()) PetscCall(PetscPrintf(comm_, "Stability monitor: %s\n", monitor_.Report().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FE2StaticRun::AddFailure(const std::string &reason, JsonObject &js)
{
  PetscFunctionBeginUser;
  if (solving_) {
    js.Set("last_failure", last_failure_);
    js.Set("partial_outputs", OutputFilesIn(OutputDir(), false));
  }
  tip_csv_.Finish(); /* what it holds; its own failure is the reason already */
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
