static const char help[] = "The am TS type (variable-order Adams-Moulton with functional iteration) against exact solutions:\n"
                           "(1) the observed order with the order held fixed at q = 1..5 and fixed steps, and of TSInterpolate;\n"
                           "(2) adaptive runs at rtol = atol = 1e-3, 1e-6, 1e-9 on Van der Pol (mu = 1, against radauiia at 1e-13)\n"
                           "and Kepler's problem (e = 0.5, exact); (3) TSInterpolate inside every step of the Kepler runs;\n"
                           "(4) the exact final time (MATCHSTEP and INTERPOLATE); (5) a stiff\n"
                           "problem, y' = -1e4 (y - cos t); (6) fixed-point failures with one iteration allowed; (7) an\n"
                           "IFunction is refused; (8) TSSetFunctionDomainError rejections; (9) TSRollBack; (10) the TSAMSet*() defaults:\n"
                           "used, overridden by -ts_am_* options, checked, and a no-op on another TS type.\n";
#include "test_util.h"
#include "ode_util.h"
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/radau_iia.h>

namespace {

enum class Kind {
  forced,
  kepler,
  relax,
  vdp
};

/* forced: y' = A (y - g(t)) + g'(t), A = [[-1, 1], [-1, -1]], g = (sin t, cos 2t), y(0) = g(0):
   y = g, and errors decay like exp(-t), so start-up errors vanish from long fixed-step runs.
   kepler: q'' = -q/|q|^3, q(0) = (1 - e, 0), p(0) = (0, sqrt((1 + e)/(1 - e))), e = 0.5; with the
   eccentric anomaly E - e sin E = t: q = (cos E - e, sqrt(1 - e^2) sin E), p = q' = (-sin E,
   sqrt(1 - e^2) cos E) / (1 - e cos E).
   relax: y' = -lambda (y - cos t), y(0) = 1: y = (lambda^2 cos t + lambda sin t)/(lambda^2 + 1) + c exp(-lambda t).
   vdp: Van der Pol, y1' = y2, y2' = mu (1 - y1^2) y2 - y1, mu = 1, y(0) = (2, 0); no closed form (Exact()
   gives only y(0)): compared with a tight radauiia solution. */
struct Problem {
  Kind      kind   = Kind::forced;
  PetscReal ecc    = 0.5;
  PetscReal lambda = 1e4;
  PetscReal hlim   = 0; /* > 0: the domain-error callback rejects steps longer than this */
  PetscInt  nf     = 0;
  /* dense-output sampling inside steps after t_sample */
  PetscBool sample     = PETSC_FALSE;
  PetscReal t_sample   = 0;
  PetscReal interp_err = 0; /* max over components of |error| / (atol + rtol |y|) if scaled, else |error| */
  PetscReal step_err   = 0; /* the same at the step points */
  PetscBool scaled     = PETSC_FALSE;
  PetscReal tol        = 1;
  Vec       X          = NULL;

  PetscInt Size() const { return kind == Kind::kepler ? 4 : (kind == Kind::forced || kind == Kind::vdp) ? 2 : 1; }
  void     Exact(PetscReal t, PetscReal y[]) const
  {
    if (kind == Kind::forced) turgor_test::ForcedExact(t, y);
    else if (kind == Kind::kepler) turgor_test::KeplerExact(ecc, t, y);
    else if (kind == Kind::vdp) {
      y[0] = 2;
      y[1] = 0;
    } else {
      const PetscReal l = lambda, l2 = l * l, c = 1 - l2 / (l2 + 1);
      y[0] = (l2 * std::cos(t) + l * std::sin(t)) / (l2 + 1) + c * std::exp(-l * t);
    }
  }
};

PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec Y, Vec F, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *y;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  if (p->kind == Kind::forced) turgor_test::ForcedRHS(t, y, f);
  else if (p->kind == Kind::kepler) turgor_test::KeplerRHS(y, f);
  else if (p->kind == Kind::vdp) {
    turgor_test::VanDerPol(1, y, f);
  } else f[0] = -p->lambda * (y[0] - std::cos(t));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Van der Pol's Jacobian, for the radauiia reference solution */
PetscErrorCode VdPJacobian(TS ts, PetscReal t, Vec Y, Mat A, Mat B, void *ctx)
{
  const PetscScalar *y;
  PetscScalar        v[4];

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(Y, &y));
  turgor_test::VanDerPolJacobian(1, y, v);
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(turgor_test::SetDenseMatrix(B, 2, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* after each step: the dense output at interior points against the exact solution */
PetscErrorCode SampleInterior(TS ts)
{
  Problem           *p;
  PetscReal          t0, t1, ye[4];
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &p));
  PetscCall(TSGetPrevTime(ts, &t0));
  PetscCall(TSGetTime(ts, &t1));
  if (!p->sample || t0 < p->t_sample) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscReal s : {0.2, 0.5, 0.8, 1.0}) {
    const PetscReal t   = t0 + s * (t1 - t0);
    PetscReal      *err = s < 1 ? &p->interp_err : &p->step_err;
    Vec             U   = p->X;
    if (s < 1) PetscCall(TSInterpolate(ts, t, p->X));
    else PetscCall(TSGetSolution(ts, &U));
    p->Exact(t, ye);
    PetscCall(VecGetArrayRead(U, &x));
    for (PetscInt i = 0; i < p->Size(); i++) {
      const PetscReal e = std::fabs(PetscRealPart(x[i]) - ye[i]);
      *err              = PetscMax(*err, p->scaled ? e / (p->tol + p->tol * std::fabs(ye[i])) : e);
    }
    PetscCall(VecRestoreArrayRead(U, &x));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct RunSpec {
  PetscReal              tf = 1, dt = 0.1, tol = 1e-6;
  PetscBool              fixed_steps = PETSC_FALSE;
  TSExactFinalTimeOption final       = TS_EXACTFINALTIME_MATCHSTEP;
  /* defaults for this run only, set with TSAMSet*() (0: the type's own); -ts_am_* options override them */
  PetscInt         max_order = 0, max_it = 0, max_conv_fails = 0;
  PetscBool        fixed_order = PETSC_FALSE;
  PetscBool        domain = PETSC_FALSE, ifunction = PETSC_FALSE;
  const PetscReal *reference = NULL; /* the solution at tf, if Exact() has none */
};

/* A run to tf at rtol = atol = tol with the first step dt (0: PETSc's automatic choice). */
RunSpec Spec(PetscReal tf, PetscReal dt, PetscReal tol)
{
  RunSpec s;
  s.tf  = tf;
  s.dt  = dt;
  s.tol = tol;
  return s;
}

/* y' = -lambda (y - cos t) */
Problem Relaxation(PetscReal lambda)
{
  Problem p;
  p.kind   = Kind::relax;
  p.lambda = lambda;
  return p;
}

struct Result {
  TSConvergedReason reason;
  PetscReal         t, solve_time, err_max, err_scaled;
  PetscInt          steps, rejects, its, fails, order, nf;
  PetscBool         finite;
};

PetscErrorCode Run(Problem &p, const RunSpec &spec, Result *res)
{
  TS                 ts;
  Vec                Y;
  PetscReal          y0[4], ye[4];
  const PetscScalar *y;

  PetscFunctionBeginUser;
  p.nf         = 0;
  p.interp_err = 0;
  p.step_err   = 0;
  p.tol        = spec.tol;
  p.Exact(0, y0);
  PetscCall(turgor_test::CreateSeqVec(p.Size(), y0, &Y));
  PetscCall(VecDuplicate(Y, &p.X));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetApplicationContext(ts, &p));
  PetscCall(TSSetType(ts, TSAM));
  if (spec.max_order > 0) PetscCall(TSAMSetMaxOrder(ts, spec.max_order));
  if (spec.fixed_order) PetscCall(TSAMSetFixedOrder(ts, PETSC_TRUE));
  if (spec.max_it > 0) PetscCall(TSAMSetMaxIterations(ts, spec.max_it));
  if (spec.max_conv_fails > 0) PetscCall(TSAMSetMaxConvergenceFailures(ts, spec.max_conv_fails));
  if (spec.ifunction) PetscCall(TSSetIFunction(ts, NULL, turgor_test::ZeroRateIFunction, &p));
  else PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
  if (spec.domain) PetscCall(TSSetFunctionDomainError(ts, turgor_test::RejectBeyondStepLimit<Problem>));
  PetscCall(TSSetTime(ts, 0));
  if (spec.dt > 0) PetscCall(TSSetTimeStep(ts, spec.dt));
  PetscCall(TSSetMaxTime(ts, spec.tf));
  PetscCall(TSSetMaxSteps(ts, 10000000));
  PetscCall(TSSetExactFinalTime(ts, spec.final));
  PetscCall(TSSetTolerances(ts, spec.tol, NULL, spec.tol, NULL));
  PetscCall(TSSetMaxStepRejections(ts, 100));
  PetscCall(TSSetErrorIfStepFails(ts, PETSC_FALSE)); /* a diverged solve is checked through its reason */
  PetscCall(TSSetPostStep(ts, SampleInterior));
  PetscCall(TSSetFromOptions(ts));
  if (spec.fixed_steps) {
    TSAdapt adapt;
    PetscCall(TSGetAdapt(ts, &adapt));
    PetscCall(TSAdaptSetType(adapt, TSADAPTNONE)); /* command-line adapters apply to the adaptive runs only */
  }
  /* a refused setup, such as (7)'s IFunction, is returned to the caller after freeing the run */
  if (PetscErrorCode ierr = TSSolve(ts, Y)) {
    PetscCall(TSDestroy(&ts));
    PetscCall(VecDestroy(&Y));
    PetscCall(VecDestroy(&p.X));
    PetscCall(ierr); /* returns it, with this frame in the traceback */
  }
  PetscCall(TSGetConvergedReason(ts, &res->reason));
  PetscCall(TSGetTime(ts, &res->t));
  PetscCall(TSGetSolveTime(ts, &res->solve_time));
  PetscCall(TSGetStepNumber(ts, &res->steps));
  PetscCall(TSGetStepRejections(ts, &res->rejects));
  PetscCall(TSAMGetCounters(ts, &res->its, &res->fails, &res->order));
  res->nf = p.nf;
  if (spec.reference)
    for (PetscInt i = 0; i < p.Size(); i++) ye[i] = spec.reference[i];
  else p.Exact(res->solve_time, ye);
  PetscCall(VecGetArrayRead(Y, &y));
  res->err_max = res->err_scaled = 0;
  res->finite                    = PETSC_TRUE;
  for (PetscInt i = 0; i < p.Size(); i++) {
    const PetscReal e = std::fabs(PetscRealPart(y[i]) - ye[i]);
    if (PetscIsInfOrNanScalar(y[i])) res->finite = PETSC_FALSE;
    res->err_max    = PetscMax(res->err_max, e);
    res->err_scaled = PetscMax(res->err_scaled, e / (spec.tol + spec.tol * std::fabs(ye[i])));
  }
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&p.X));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PrintRun(const char *what, const Result &r)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "%s: %s at t = %g, steps %" PetscInt_FMT ", rejected %" PetscInt_FMT " (fixed point %" PetscInt_FMT "), f evals %" PetscInt_FMT
                        ", fixed-point its %" PetscInt_FMT ", final order %" PetscInt_FMT ", error %.3e (%.3g x tol)\n",
                        what, TSConvergedReasons[r.reason], (double)r.t, r.steps, r.rejects, r.fails, r.nf, r.its, r.order, (double)r.err_max,
                        (double)r.err_scaled));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (1) */
PetscErrorCode CheckOrders()
{
  const PetscReal T = 40, hs[4] = {0.2, 0.1, 0.05, 0.025};

  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "(1) fixed order q, fixed steps, forced linear problem on [0, %g] (start-up errors decay like exp(-t)); max error at the step points "
                        "in [20, 40] and of TSInterpolate at 0.2, 0.5, 0.8 of those steps\n",
                        (double)T));
  for (PetscInt q = 1; q <= 5; q++) {
    PetscReal e[4], ie[4];
    for (int k = 0; k < 4; k++) {
      Problem p;
      RunSpec s = Spec(T, hs[k], 1e-12); /* only the fixed-point test sees the tolerance: iterate to convergence (the AM corrector itself) */
      Result  r;
      p.kind        = Kind::forced;
      p.sample      = PETSC_TRUE;
      p.t_sample    = 20;
      s.fixed_steps = PETSC_TRUE;
      s.max_order   = q;
      s.fixed_order = PETSC_TRUE;
      s.max_it      = 40;
      PetscCall(Run(p, s, &r));
      const PetscInt N = (PetscInt)std::lround(T / hs[k]);
      TG_CHECK(r.reason > 0 && r.steps == N && r.fails == 0,
               "q = %" PetscInt_FMT ", h = %g: %s after %" PetscInt_FMT " steps (expected %" PetscInt_FMT "), %" PetscInt_FMT " fixed-point failures", q,
               (double)hs[k], TSConvergedReasons[r.reason], r.steps, N, r.fails);
      TG_CHECK(r.order == q, "the order must be held at %" PetscInt_FMT ", got %" PetscInt_FMT, q, r.order);
      e[k]  = p.step_err;
      ie[k] = p.interp_err;
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "    q = %" PetscInt_FMT ", h = %.3f (%4" PetscInt_FMT " steps, %5" PetscInt_FMT " f evals): error %.3e, interpolation error %.3e",
                            q, (double)hs[k], r.steps, r.nf, (double)e[k], (double)ie[k]));
      if (k) PetscCall(PetscPrintf(PETSC_COMM_SELF, "  order %.3f, dense %.3f", (double)std::log2(e[k - 1] / e[k]), (double)std::log2(ie[k - 1] / ie[k])));
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n"));
    }
    const PetscReal order = std::log2(e[2] / e[3]), order2 = std::log2(e[1] / e[2]), dense = std::log2(ie[2] / ie[3]);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "    q = %" PetscInt_FMT ": observed order %.3f (h 0.05 -> 0.025), %.3f (0.1 -> 0.05); dense output %.3f\n", q,
                          (double)order, (double)order2, (double)dense));
    TG_CHECK(std::fabs(order - q) <= 0.3 && std::fabs(order2 - q) <= 0.3, "order %" PetscInt_FMT ": observed %g and %g", q, (double)order, (double)order2);
    TG_CHECK(std::fabs(dense - q) <= 0.3, "order %" PetscInt_FMT ": dense output order %g (the interpolant carries the global error, O(h^q))", q,
             (double)dense);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The Van der Pol reference at t = tf: radauiia at rtol = atol = 1e-13, checked against 1e-12. */
PetscErrorCode VdPReference(PetscReal tf, PetscReal ref[2])
{
  PetscReal r[2][2];

  PetscFunctionBeginUser;
  for (int k = 0; k < 2; k++) {
    Problem            p;
    TS                 ts;
    Vec                Y;
    Mat                J;
    PetscReal          y0[2];
    const PetscScalar *y;
    p.kind = Kind::vdp;
    p.Exact(0, y0);
    PetscCall(turgor_test::CreateSeqVec(2, y0, &Y));
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, NULL, &J));
    PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
    PetscCall(TSSetType(ts, TSRADAUIIA));
    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
    PetscCall(TSSetRHSJacobian(ts, J, J, VdPJacobian, &p));
    PetscCall(TSSetTimeStep(ts, 1e-4));
    PetscCall(TSSetMaxTime(ts, tf));
    PetscCall(TSSetMaxSteps(ts, 1000000));
    PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
    PetscCall(TSSetTolerances(ts, k ? 1e-12 : 1e-13, NULL, k ? 1e-12 : 1e-13, NULL));
    PetscCall(TSSolve(ts, Y));
    PetscCall(VecGetArrayRead(Y, &y));
    r[k][0] = PetscRealPart(y[0]);
    r[k][1] = PetscRealPart(y[1]);
    PetscCall(VecRestoreArrayRead(Y, &y));
    PetscCall(TSDestroy(&ts));
    PetscCall(MatDestroy(&J));
    PetscCall(VecDestroy(&Y));
  }
  const PetscReal d = PetscMax(std::fabs(r[0][0] - r[1][0]), std::fabs(r[0][1] - r[1][1]));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    radauiia reference y(%g) = (%.15f, %.15f), differs by %.1e from radauiia at 1e-12\n", (double)tf, (double)r[0][0],
                        (double)r[0][1], (double)d));
  TG_CHECK(d < 1e-10, "the radauiia reference is not converged: %g", (double)d);
  ref[0] = r[0][0];
  ref[1] = r[0][1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (2), (3), (4) */
PetscErrorCode CheckAdaptive()
{
  const PetscReal tols[3] = {1e-3, 1e-6, 1e-9};
  PetscReal       err[3], ref[2];

  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(2) adaptive, Van der Pol mu = 1 on [0, 2], automatic first step\n"));
  PetscCall(VdPReference(2, ref));
  for (int k = 0; k < 3; k++) {
    Problem p;
    RunSpec s = Spec(2, 0, tols[k]);
    Result  r;
    char    what[64];
    p.kind      = Kind::vdp;
    s.reference = ref;
    PetscCall(Run(p, s, &r));
    PetscCall(PetscSNPrintf(what, sizeof(what), "    rtol = atol = %g", (double)tols[k]));
    PetscCall(PrintRun(what, r));
    TG_CHECK(r.reason > 0 && std::fabs(r.t - 2) <= 1e-14, "(4) MATCHSTEP must end at t = 2 exactly: %s at t = %.17g", TSConvergedReasons[r.reason],
             (double)r.t);
    TG_CHECK(r.err_scaled <= 100, "error %g x tolerance", (double)r.err_scaled);
    TG_CHECK(r.nf == r.its + 2, "f evaluations: %" PetscInt_FMT " by the application, expected %" PetscInt_FMT " fixed-point iterations + 2 at the start", r.nf,
             r.its);
    err[k] = r.err_max;
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    error ratios per factor 1000 in tolerance: %.3g, %.3g\n", (double)(err[0] / err[1]), (double)(err[1] / err[2])));
  TG_CHECK(err[1] < err[0] / 10 && err[2] < err[1] / 10, "tolerance proportionality: errors %g, %g, %g for tolerances 1e-3, 1e-6, 1e-9", (double)err[0],
           (double)err[1], (double)err[2]);

  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "    Kepler e = 0.5 on [0, pi] (perihelion to aphelion) against the exact orbit; (3) TSInterpolate at 0.2, 0.5, 0.8 of every step\n"));
  for (int k = 0; k < 3; k++) {
    Problem p;
    RunSpec s = Spec(PETSC_PI, 0, tols[k]);
    Result  r;
    char    what[64];
    p.kind   = Kind::kepler;
    p.sample = PETSC_TRUE;
    p.scaled = PETSC_TRUE;
    PetscCall(Run(p, s, &r));
    PetscCall(PetscSNPrintf(what, sizeof(what), "    rtol = atol = %g", (double)tols[k]));
    PetscCall(PrintRun(what, r));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "        largest error at the step points %.3g x tol, of TSInterpolate inside the steps %.3g x tol\n",
                          (double)p.step_err, (double)p.interp_err));
    TG_CHECK(r.reason > 0 && std::fabs(r.t - PETSC_PI) <= 1e-14, "(4) MATCHSTEP must end at t = pi exactly: %s at t = %.17g", TSConvergedReasons[r.reason],
             (double)r.t);
    TG_CHECK(p.step_err <= 300, "error %g x tolerance", (double)p.step_err);
    TG_CHECK(p.interp_err <= 2 * p.step_err + 1, "(3) the dense output (%g x tol) must be about as accurate as the steps (%g x tol)", (double)p.interp_err,
             (double)p.step_err);
    err[k] = p.step_err * tols[k];
  }
  TG_CHECK(err[1] < err[0] / 10 && err[2] < err[1] / 10, "tolerance proportionality: errors %g, %g, %g for tolerances 1e-3, 1e-6, 1e-9", (double)err[0],
           (double)err[1], (double)err[2]);

  /* (4) INTERPOLATE: the solution returned at max_time comes from the dense output */
  {
    Problem p;
    RunSpec s = Spec(2.5, 0, 1e-6);
    Result  r;
    p.kind  = Kind::kepler;
    s.final = TS_EXACTFINALTIME_INTERPOLATE;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("(4) Kepler, INTERPOLATE to t = 2.5, rtol = atol = 1e-6", r));
    TG_CHECK(r.reason > 0 && r.solve_time == 2.5 && r.t > 2.5, "INTERPOLATE: solve time %.17g, last step ends at %.17g", (double)r.solve_time, (double)r.t);
    TG_CHECK(r.err_scaled <= 300, "INTERPOLATE: error at t = 2.5 is %g x tolerance", (double)r.err_scaled);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (5), (6) */
PetscErrorCode CheckStiff()
{
  PetscFunctionBeginUser;
  {
    Problem p = Relaxation(1e4);
    RunSpec s = Spec(1, 0, 1e-6);
    Result  r;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("(5) stiff y' = -1e4 (y - cos t) on [0, 1], rtol = atol = 1e-6", r));
    TG_CHECK(r.finite, "the state must stay finite");
    TG_CHECK(r.reason > 0 || r.reason == TS_DIVERGED_NONLINEAR_SOLVE || r.reason == TS_DIVERGED_STEP_REJECTED, "unexpected reason %s",
             TSConvergedReasons[r.reason]);
    if (r.reason > 0) {
      TG_CHECK(std::fabs(r.t - 1) < 1e-14, "t = %g", (double)r.t);
      TG_CHECK(r.err_scaled <= 100, "error %g x tolerance", (double)r.err_scaled);
      TG_CHECK(r.steps >= 1000, "%" PetscInt_FMT " steps: an explicit corrector iteration cannot take steps much above 1/lambda = 1e-4", r.steps);
    }
  }
  {
    Problem p = Relaxation(50);
    RunSpec s = Spec(2, 0, 1e-6);
    Result  r;
    s.max_it = 1;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("(6) y' = -50 (y - cos t) on [0, 2], TSAMSetMaxIterations(ts, 1)", r));
    TG_CHECK(r.reason > 0 && std::fabs(r.t - 2) < 1e-14, "%s at t = %g", TSConvergedReasons[r.reason], (double)r.t);
    TG_CHECK(r.fails > 0 && r.rejects >= r.fails,
             "one iteration per attempt must produce counted fixed-point failures: %" PetscInt_FMT " failures, %" PetscInt_FMT " rejections", r.fails,
             r.rejects);
    TG_CHECK(r.err_scaled <= 100, "error %g x tolerance", (double)r.err_scaled);
  }
  {
    /* a first step of 1 on the stiff problem needs 7 cuts by 4 before the iteration contracts */
    Problem p = Relaxation(1e4);
    RunSpec s = Spec(1, 1, 1e-6);
    Result  r;
    s.max_conv_fails = 3;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("(6) stiff, first step 1, TSAMSetMaxConvergenceFailures(ts, 3)", r));
    TG_CHECK(r.reason == TS_DIVERGED_NONLINEAR_SOLVE && r.fails == 3 && r.steps == 0 && r.finite,
             "expected DIVERGED_NONLINEAR_SOLVE after 3 fixed-point failures in the first step: %s, %" PetscInt_FMT " failures, %" PetscInt_FMT " steps",
             TSConvergedReasons[r.reason], r.fails, r.steps);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (7), (8) */
PetscErrorCode CheckErrorsAndDomain()
{
  PetscFunctionBeginUser;
  {
    Problem        p;
    RunSpec        s;
    Result         r;
    PetscErrorCode ierr;
    s.ifunction = PETSC_TRUE;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = Run(p, s, &r);
    PetscCall(PetscPopErrorHandler());
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "(7) an IFunction only: error code %d (PETSC_ERR_SUP = %d)\n", (int)ierr, (int)PETSC_ERR_SUP));
    TG_CHECK(ierr == PETSC_ERR_SUP, "an IFunction must be refused with PETSC_ERR_SUP, got %d", (int)ierr);
  }
  {
    Problem p;
    RunSpec s = Spec(2, 0.5, 1e-6);
    Result  r;
    p.kind   = Kind::kepler;
    p.hlim   = 0.02;
    s.domain = PETSC_TRUE;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("(8) Kepler, TSSetFunctionDomainError rejects steps longer than 0.02 (first step 0.5)", r));
    TG_CHECK(r.reason > 0 && std::fabs(r.t - 2) < 1e-14, "%s at t = %g", TSConvergedReasons[r.reason], (double)r.t);
    TG_CHECK(r.rejects >= 5 && r.steps >= 100, "%" PetscInt_FMT " rejections, %" PetscInt_FMT " steps: steps beyond 0.02 were accepted", r.rejects, r.steps);
    TG_CHECK(r.err_scaled <= 300, "error %g x tolerance (the bound used for Kepler in (2))", (double)r.err_scaled);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (9) TSRollBack returns to the previous step exactly; the retried step reproduces it */
PetscErrorCode CheckRollBack()
{
  Problem   p;
  TS        ts;
  Vec       Y, Y2, Y3;
  PetscReal t, t2, d2, d3, y0[4];

  PetscFunctionBeginUser;
  p.kind = Kind::kepler;
  p.Exact(0, y0);
  PetscCall(turgor_test::CreateSeqVec(4, y0, &Y));
  PetscCall(VecDuplicate(Y, &Y2));
  PetscCall(VecDuplicate(Y, &Y3));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetApplicationContext(ts, &p));
  PetscCall(TSSetType(ts, TSAM));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
  PetscCall(TSSetTimeStep(ts, 1e-3));
  PetscCall(TSSetMaxTime(ts, 10));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, 1e-8, NULL, 1e-8, NULL));
  PetscCall(TSSetSolution(ts, Y));
  PetscCall(TSSetUp(ts));
  for (int i = 0; i < 30; i++) PetscCall(TSStep(ts));
  PetscCall(TSGetTime(ts, &t2));
  PetscCall(VecCopy(Y, Y2));
  PetscCall(TSStep(ts));
  PetscCall(VecCopy(Y, Y3));
  PetscCall(TSRollBack(ts));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(VecAXPY(Y2, -1.0, Y));
  PetscCall(VecNorm(Y2, NORM_INFINITY, &d2));
  TG_CHECK(t == t2 && d2 == 0, "TSRollBack: t = %g (expected %g), |U - U_prev| = %g", (double)t, (double)t2, (double)d2);
  PetscCall(TSStep(ts));
  PetscCall(VecAXPY(Y3, -1.0, Y));
  PetscCall(VecNorm(Y3, NORM_INFINITY, &d3));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(9) TSRollBack after 31 steps: back to t = %g exactly; the retried step differs by %.2e\n", (double)t2, (double)d3));
  TG_CHECK(d3 < 1e-14, "the retried step differs by %g", (double)d3); /* h = (t0 + h) - t0 after the rollback */
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&Y));
  PetscCall(VecDestroy(&Y2));
  PetscCall(VecDestroy(&Y3));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (10) */
PetscErrorCode CheckSetters()
{
  TS           ts;
  PetscOptions opts;
  PetscInt     q, its, fails;
  PetscBool    fixed;
  void (*method)(void);

  PetscFunctionBeginUser;
  /* a private, empty options database: the command line must not change what is checked here */
  PetscCall(PetscOptionsCreate(&opts));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(PetscObjectSetOptions((PetscObject)ts, opts));
  PetscCall(TSSetType(ts, TSAM));
  PetscCall(TSAMSetMaxOrder(ts, 5));
  PetscCall(TSAMSetFixedOrder(ts, PETSC_TRUE));
  PetscCall(TSAMSetMaxIterations(ts, 7));
  PetscCall(TSAMSetMaxConvergenceFailures(ts, 4));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSAMGetMaxOrder(ts, &q));
  PetscCall(TSAMGetFixedOrder(ts, &fixed));
  PetscCall(TSAMGetMaxIterations(ts, &its));
  PetscCall(TSAMGetMaxConvergenceFailures(ts, &fails));
  TG_CHECK(q == 5 && fixed && its == 7 && fails == 4,
           "set before TSSetFromOptions(): max order %" PetscInt_FMT ", fixed %d, iterations %" PetscInt_FMT ", failures %" PetscInt_FMT
           " (expected 5, 1, 7, 4)",
           q, (int)fixed, its, fails);
  /* options given for the TS still win over the values set in code */
  PetscCall(PetscOptionsSetValue(opts, "-ts_am_max_order", "3"));
  PetscCall(PetscOptionsSetValue(opts, "-ts_am_max_iterations", "2"));
  PetscCall(TSAMSetMaxOrder(ts, 5));
  PetscCall(TSAMSetMaxIterations(ts, 7));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSAMGetMaxOrder(ts, &q));
  PetscCall(TSAMGetMaxIterations(ts, &its));
  TG_CHECK(q == 3 && its == 2, "-ts_am_max_order 3 -ts_am_max_iterations 2 must override the values set in code: %" PetscInt_FMT ", %" PetscInt_FMT, q, its);
  /* out of range is an error, and changes nothing */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  const PetscErrorCode e_order = TSAMSetMaxOrder(ts, 13), e_its = TSAMSetMaxIterations(ts, 0), e_fails = TSAMSetMaxConvergenceFailures(ts, 0);
  PetscCall(PetscPopErrorHandler());
  TG_CHECK(e_order == PETSC_ERR_ARG_OUTOFRANGE && e_its == PETSC_ERR_ARG_OUTOFRANGE && e_fails == PETSC_ERR_ARG_OUTOFRANGE,
           "out-of-range values must fail with PETSC_ERR_ARG_OUTOFRANGE: %d %d %d", (int)e_order, (int)e_its, (int)e_fails);
  PetscCall(TSAMGetMaxOrder(ts, &q));
  TG_CHECK(q == 3, "a rejected value changed the maximum order to %" PetscInt_FMT, q);
  /* another type ignores the setters */
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSAMSetMaxOrder(ts, 2));
  PetscCall(TSAMSetFixedOrder(ts, PETSC_TRUE));
  PetscCall(TSAMSetMaxIterations(ts, 1));
  PetscCall(TSAMSetMaxConvergenceFailures(ts, 1));
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, "TSAMGetMaxOrder_C", &method));
  TG_CHECK(!method, "a TS changed to rk still has TSAMGetMaxOrder_C");
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscOptionsDestroy(&opts));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(10) TSAMSetMaxOrder/FixedOrder/MaxIterations/MaxConvergenceFailures before TSSetFromOptions() are used; -ts_am_* "
                                         "options override them; 13, 0, 0 are rejected; no-op on rk\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  PetscCall(CheckOrders());
  PetscCall(CheckAdaptive());
  PetscCall(CheckStiff());
  PetscCall(CheckErrorsAndDomain());
  PetscCall(CheckRollBack());
  PetscCall(CheckSetters());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_adams_moulton: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
