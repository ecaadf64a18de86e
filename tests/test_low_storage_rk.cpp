static const char help[] = "The lsrk TS type (RK4(3)5[3S*], three registers) against theory and exact solutions:\n"
                           "(1) the order conditions of its reconstructed Butcher tableau: order 4, the embedded pair order 3 (and not 4);\n"
                           "(2) the observed order with fixed steps on a forced linear system and on Kepler's problem, of the step\n"
                           "and of TSInterpolate inside the steps; (3) adaptive runs at rtol = atol = 1e-4 .. 1e-10 on Kepler's problem:\n"
                           "the error follows the tolerance, and against DOPRI's at the same tolerance; (4) the linear stability\n"
                           "function against exp(z) and its real stability limit; (5) TSSetFunctionDomainError rejections;\n"
                           "(6) TSRollBack; (7) the work vectors: three state-size vectors (DOPRI's TSRK: 15);\n"
                           "(8) interpolation reuses f(u_{n+1}) as the next step's first stage, and the run is bitwise the same\n"
                           "as one without interpolation; (9) a problem in implicit form (TSSetIFunction) is refused.\n";
#include "test_util.h"
#include "ode_util.h"
#include <turgor/ts/low_storage_rk.h>
#include <vector>

namespace {

/* forced: y' = A (y - g(t)) + g'(t), A = [[-1, 1], [-1, -1]], g = (sin t, cos 2t), y(0) = g(0): y = g.
   kepler: q'' = -q/|q|^3, e = 0.5, exact through Kepler's equation. */
struct Problem {
  bool      kepler = false;
  PetscReal ecc    = 0.5;
  PetscReal hlim   = 0; /* > 0: the domain check rejects stages more than hlim past the step's start */
  PetscInt  nf     = 0;
  PetscInt  Size() const { return kepler ? 4 : 2; }
  void      Exact(PetscReal t, PetscReal y[]) const
  {
    if (kepler) turgor_test::KeplerExact(ecc, t, y);
    else turgor_test::ForcedExact(t, y);
  }
};

PetscErrorCode RHSFunction(TS, PetscReal t, Vec Y, Vec F, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *y;
  PetscScalar       *f;
  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  if (p->kepler) turgor_test::KeplerRHS(y, f);
  else turgor_test::ForcedRHS(t, y, f);
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct Result {
  PetscReal              err = 0, interp_err = 0, step_err = 0; /* max |error| at the end, of TSInterpolate at 0.3 and 0.7 of every step, at every step's end */
  PetscInt               steps = 0, rejects = 0, nf = 0, stage_evals = 0, interp_evals = 0;
  PetscReal              hmax = 0;
  std::vector<PetscReal> final;
};

struct Monitor {
  Problem  *p;
  bool      interpolate;
  Vec       X;
  PetscReal interp_err = 0, step_err = 0, hmax = 0;
};

PetscErrorCode StepMonitor(TS ts, PetscInt step, PetscReal t1, Vec, void *ctx)
{
  Monitor  *m = (Monitor *)ctx;
  PetscReal t0, ye[4];
  PetscFunctionBeginUser;
  if (step == 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSGetPrevTime(ts, &t0));
  m->hmax = PetscMax(m->hmax, t1 - t0);
  if (!m->interpolate) PetscFunctionReturn(PETSC_SUCCESS);
  {
    const PetscScalar *x;
    Vec                U;
    PetscCall(TSGetSolution(ts, &U));
    m->p->Exact(t1, ye);
    PetscCall(VecGetArrayRead(U, &x));
    for (PetscInt i = 0; i < m->p->Size(); i++) m->step_err = PetscMax(m->step_err, std::fabs(PetscRealPart(x[i]) - ye[i]));
    PetscCall(VecRestoreArrayRead(U, &x));
  }
  for (PetscReal s : {0.3, 0.7}) {
    const PetscReal    t = t0 + s * (t1 - t0);
    const PetscScalar *x;
    PetscCall(TSInterpolate(ts, t, m->X));
    m->p->Exact(t, ye);
    PetscCall(VecGetArrayRead(m->X, &x));
    for (PetscInt i = 0; i < m->p->Size(); i++) m->interp_err = PetscMax(m->interp_err, std::fabs(PetscRealPart(x[i]) - ye[i]));
    PetscCall(VecRestoreArrayRead(m->X, &x));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* tf with fixed steps dt (tol = 0) or adaptively at rtol = atol = tol, with lsrk or another TS type */
PetscErrorCode Run(Problem p, PetscReal tf, PetscReal dt, PetscReal tol, bool interpolate, Result *r, const char *type = TSLSRK)
{
  TS        ts;
  Vec       U;
  PetscReal y0[4], ye[4];
  PetscFunctionBeginUser;
  p.Exact(0, y0);
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, p.Size(), &U));
  for (PetscInt i = 0; i < p.Size(); i++) PetscCall(VecSetValue(U, i, y0[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, type));
  if (!std::string(type).compare(TSRK)) PetscCall(TSRKSetType(ts, TSRK5DP));
  PetscCall(TSSetApplicationContext(ts, &p));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
  PetscCall(TSSetFunctionDomainError(ts, turgor_test::RejectBeyondStepLimit<Problem>));
  PetscCall(TSSetMaxTime(ts, tf));
  PetscCall(TSSetMaxSteps(ts, 10000000));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTimeStep(ts, dt));
  Monitor m{&p, interpolate, NULL};
  PetscCall(VecDuplicate(U, &m.X));
  PetscCall(TSMonitorSet(ts, StepMonitor, &m, NULL));
  PetscCall(TSSetFromOptions(ts));
  if (tol > 0) PetscCall(TSSetTolerances(ts, tol, NULL, tol, NULL));
  else {
    TSAdapt adapt;
    PetscCall(TSGetAdapt(ts, &adapt));
    PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  }
  PetscCall(TSSolve(ts, U));
  TSConvergedReason reason;
  PetscCall(TSGetConvergedReason(ts, &reason));
  TG_CHECK(reason > 0, "%s run diverged (%s)", type, TSConvergedReasons[reason]);
  PetscCall(TSGetStepNumber(ts, &r->steps));
  PetscCall(TSGetStepRejections(ts, &r->rejects));
  PetscReal t;
  PetscCall(TSGetTime(ts, &t));
  p.Exact(t, ye);
  const PetscScalar *u;
  PetscCall(VecGetArrayRead(U, &u));
  r->err = 0;
  r->final.assign(p.Size(), 0);
  for (PetscInt i = 0; i < p.Size(); i++) {
    r->err      = PetscMax(r->err, std::fabs(PetscRealPart(u[i]) - ye[i]));
    r->final[i] = PetscRealPart(u[i]);
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  r->interp_err = m.interp_err;
  r->step_err   = m.step_err;
  r->hmax       = m.hmax;
  r->nf         = p.nf;
  if (!std::string(type).compare(TSLSRK)) PetscCall(TSLSRKGetCounters(ts, &r->stage_evals, &r->interp_evals));
  PetscCall(VecDestroy(&m.X));
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (1) Butcher's order conditions up to order 4 (the eight trees), as residuals */
void OrderResiduals(PetscInt s, const PetscReal *A, const PetscReal *b, const PetscReal *c, PetscReal res[8])
{
  std::vector<PetscReal> Ac(s, 0), Ac2(s, 0), AAc(s, 0);
  for (PetscInt i = 0; i < s; i++)
    for (PetscInt j = 0; j < s; j++) {
      Ac[i] += A[i * s + j] * c[j];
      Ac2[i] += A[i * s + j] * c[j] * c[j];
    }
  for (PetscInt i = 0; i < s; i++)
    for (PetscInt j = 0; j < s; j++) AAc[i] += A[i * s + j] * Ac[j];
  PetscReal sum[8] = {0};
  for (PetscInt i = 0; i < s; i++) {
    sum[0] += b[i];
    sum[1] += b[i] * c[i];
    sum[2] += b[i] * c[i] * c[i];
    sum[3] += b[i] * Ac[i];
    sum[4] += b[i] * c[i] * c[i] * c[i];
    sum[5] += b[i] * c[i] * Ac[i];
    sum[6] += b[i] * Ac2[i];
    sum[7] += b[i] * AAc[i];
  }
  const PetscReal want[8] = {1, 1.0 / 2, 1.0 / 3, 1.0 / 6, 1.0 / 4, 1.0 / 8, 1.0 / 12, 1.0 / 24};
  for (int k = 0; k < 8; k++) res[k] = std::fabs(sum[k] - want[k]);
}

PetscErrorCode CheckTableau()
{
  TS               ts;
  PetscInt         s, order, embedded;
  const PetscReal *A, *b, *bh, *c;
  PetscReal        res[8], resh[8];
  PetscFunctionBeginUser;
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSLSRK));
  PetscCall(TSLSRKGetTableau(ts, &s, &A, &b, &bh, &c, &order, &embedded));
  TG_CHECK(s == 5 && order == 4 && embedded == 3, "RK4(3)5: s = %d, orders %d(%d)", (int)s, (int)order, (int)embedded);
  for (PetscInt i = 0; i < s; i++)
    for (PetscInt j = i; j < s; j++)
      TG_CHECK(A[i * s + j] == 0, "A[%d][%d] = %g: an explicit method is strictly lower triangular", (int)i, (int)j, (double)A[i * s + j]);
  OrderResiduals(s, A, b, c, res);
  OrderResiduals(s, A, bh, c, resh);
  PetscReal worst = 0, worsth = 0, order4h = 0;
  for (int k = 0; k < 8; k++) worst = PetscMax(worst, res[k]);
  for (int k = 0; k < 4; k++) worsth = PetscMax(worsth, resh[k]);
  for (int k = 4; k < 8; k++) order4h = PetscMax(order4h, resh[k]);
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "(1) tableau: c = %.6f %.6f %.6f %.6f %.6f; order conditions: 4th-order method %.2e, embedded to 3rd %.2e, embedded 4th %.2e\n",
                        (double)c[0], (double)c[1], (double)c[2], (double)c[3], (double)c[4], (double)worst, (double)worsth, (double)order4h));
  TG_CHECK(worst < 1e-13, "order conditions to 4 violated by %g", (double)worst);
  TG_CHECK(worsth < 1e-13, "the embedded method's conditions to 3 violated by %g", (double)worsth);
  TG_CHECK(order4h > 1e-4, "the embedded method is of order 4 (%g): it would estimate no error", (double)order4h);
  /* (4) the stability function against exp(z), and the real-axis limit */
  PetscReal yr, yi, dev[2];
  for (int k = 0; k < 2; k++) { /* at z and z/2 */
    const PetscReal zr = -0.2 / (1 + k), zi = 0.1 / (1 + k);
    PetscCall(TSComputeLinearStability(ts, zr, zi, &yr, &yi));
    dev[k] = std::hypot(yr - std::exp(zr) * std::cos(zi), yi - std::exp(zr) * std::sin(zi));
  }
  const PetscReal zorder = std::log2(dev[0] / dev[1]);
  PetscReal       lo = 0.5, hi = 20;
  for (int it = 0; it < 60; it++) {
    const PetscReal mid = 0.5 * (lo + hi);
    PetscCall(TSComputeLinearStability(ts, -mid, 0, &yr, &yi));
    (std::hypot(yr, yi) <= 1 ? lo : hi) = mid;
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "(4) |R(z) - exp(z)| at z = -0.2 + 0.1i and z/2: %.2e, %.2e (order %.2f, 5 expected); real stability limit %.4f (DOPRI 3.31, classic "
                        "RK4 2.79)\n",
                        (double)dev[0], (double)dev[1], (double)zorder, (double)lo));
  TG_CHECK(zorder > 4.7 && zorder < 5.3, "R(z) - exp(z) falls as z^%g, not z^5", (double)zorder);
  TG_CHECK(lo > 2.5 && lo < 6, "real stability limit %g", (double)lo);
  PetscCall(TSDestroy(&ts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (2) fixed-step orders */
PetscErrorCode CheckOrders()
{
  PetscFunctionBeginUser;
  for (bool kepler : {false, true}) {
    Problem p;
    p.kepler           = kepler;
    const PetscReal tf = kepler ? 6 : 4;
    Result          r[3];
    const PetscReal dts[3] = {0.1, 0.05, 0.025};
    for (int k = 0; k < 3; k++) PetscCall(Run(p, tf, dts[k] / (kepler ? 2 : 1), 0, true, &r[k]));
    const PetscReal o1 = std::log2(r[1].err / r[2].err), oi = std::log2(r[1].interp_err / r[2].interp_err);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "(2) %s, fixed steps: errors %.3e %.3e %.3e (order %.2f), interpolation %.3e %.3e %.3e (order %.2f)\n",
                          kepler ? "Kepler" : "forced", (double)r[0].err, (double)r[1].err, (double)r[2].err, (double)o1, (double)r[0].interp_err,
                          (double)r[1].interp_err, (double)r[2].interp_err, (double)oi));
    TG_CHECK(o1 > 3.7 && o1 < 4.4, "observed order %g of a fourth-order method", (double)o1);
    TG_CHECK(oi > 3.5, "observed order %g of the cubic Hermite interpolant (4 expected)", (double)oi);
    /* evaluations: 5 a step, 2 for each interpolated step, less the end rate each next step reuses */
    TG_CHECK(r[2].nf == r[2].stage_evals + r[2].interp_evals, "evaluations %d = %d + %d", (int)r[2].nf, (int)r[2].stage_evals, (int)r[2].interp_evals);
    TG_CHECK(r[2].stage_evals == 5 * r[2].steps - (r[2].steps - 1), "stage evaluations %d for %d steps whose first stages after the first were reused",
             (int)r[2].stage_evals, (int)r[2].steps);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (3) adaptive runs: lsrk and DOPRI at the same tolerance; (8) the same steps and bits with and without interpolation */
PetscErrorCode CheckAdaptive()
{
  Problem p;
  p.kepler = true;
  PetscFunctionBeginUser;
  PetscReal prev = 0;
  for (PetscReal tol : {1e-6, 1e-8, 1e-10}) {
    Result r, rd, rq;
    PetscCall(Run(p, 4 * PETSC_PI, 1e-3, tol, true, &r));
    PetscCall(Run(p, 4 * PETSC_PI, 1e-3, tol, false, &rq));
    PetscCall(Run(p, 4 * PETSC_PI, 1e-3, tol, false, &rd, TSRK));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "(3) Kepler, 2 orbits, tol %.0e: lsrk error %.3e (%.1f tol), %d steps (%d rejected), %d evaluations (+%d interpolating); largest at "
                          "steps %.3e, "
                          "interpolated %.3e; DOPRI %.3e, %d steps, %d evaluations\n",
                          (double)tol, (double)r.err, (double)(r.err / tol), (int)r.steps, (int)r.rejects, (int)r.stage_evals, (int)r.interp_evals,
                          (double)r.step_err, (double)r.interp_err, (double)rd.err, (int)rd.steps, (int)rd.nf));
    TG_CHECK(r.err < 300 * tol, "error %g at tol %g", (double)r.err, (double)tol);
    TG_CHECK(prev == 0 || r.err < prev / 10, "error %g at tol %g did not fall from %g", (double)r.err, (double)tol, (double)prev);
    TG_CHECK(r.interp_err < 3 * r.step_err + tol, "interpolation error %g against the steps' %g", (double)r.interp_err, (double)r.step_err);
    TG_CHECK(r.steps == rq.steps && r.rejects == rq.rejects, "interpolation changed the steps: %d (%d) vs %d (%d)", (int)r.steps, (int)r.rejects, (int)rq.steps,
             (int)rq.rejects);
    for (size_t i = 0; i < r.final.size(); i++)
      TG_CHECK(r.final[i] == rq.final[i], "interpolation changed the solution's bits: %.17g vs %.17g", (double)r.final[i], (double)rq.final[i]);
    prev = r.err;
  }
  /* a first step far too long: the error test rejects it (and others) and the run still ends accurate */
  Result r;
  PetscCall(Run(p, 4 * PETSC_PI, 0.5, 1e-6, false, &r));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(3) first step 0.5 at tol 1e-6: %d steps, %d rejected, error %.3e\n", (int)r.steps, (int)r.rejects, (double)r.err));
  TG_CHECK(r.rejects > 0 && r.err < 300 * 1e-6, "rejections %d, error %g", (int)r.rejects, (double)r.err);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (5) stages more than hlim past the step's start are refused by the domain check: every accepted
   step's last stage, at c_5 h, is within hlim */
PetscErrorCode CheckDomain()
{
  Problem p;
  p.kepler = true;
  p.hlim   = 0.02;
  Result           r;
  TS               ts;
  const PetscReal *c;
  PetscFunctionBeginUser;
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSLSRK));
  PetscCall(TSLSRKGetTableau(ts, NULL, NULL, NULL, NULL, &c, NULL, NULL));
  const PetscReal c_last = c[4];
  PetscCall(TSDestroy(&ts));
  PetscCall(Run(p, 2, 0.1, 1e-3, false, &r));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "(5) domain check rejecting stages > 0.02 into a step: %d steps, %d rejected, longest %.4f (c_5 h = %.4f), error %.2e\n", (int)r.steps,
                        (int)r.rejects, (double)r.hmax, (double)(c_last * r.hmax), (double)r.err));
  TG_CHECK(r.rejects > 0 && c_last * r.hmax <= 0.02 * (1 + 1e-12), "rejections %d, longest step %g", (int)r.rejects, (double)r.hmax);
  TG_CHECK(r.err < 1e-4, "error %g after rejections", (double)r.err);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (6) TSRollBack returns to the step's start, bit for bit; (7) the work vectors */
PetscErrorCode CheckRollBackAndStorage()
{
  Problem p;
  p.kepler = true;
  TS             ts;
  Vec            U, U0;
  PetscLogDouble before, after;
  PetscReal      y0[4];
  PetscFunctionBeginUser;
  p.Exact(0, y0);
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 4, &U));
  for (PetscInt i = 0; i < 4; i++) PetscCall(VecSetValue(U, i, y0[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(VecDuplicate(U, &U0));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSLSRK));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
  PetscCall(TSSetTimeStep(ts, 0.01));
  PetscCall(TSSetMaxTime(ts, 1));
  PetscCall(TSSetSolution(ts, U));
  PetscCall(TSSetUp(ts));
  PetscCall(TSStep(ts));
  PetscCall(VecCopy(U, U0));
  PetscReal t1, t2;
  PetscCall(TSGetTime(ts, &t1));
  PetscCall(TSStep(ts));
  PetscCall(TSGetTime(ts, &t2));
  PetscCall(TSRollBack(ts));
  PetscReal tb, d;
  PetscCall(TSGetTime(ts, &tb));
  PetscCall(VecAXPY(U0, -1, U));
  PetscCall(VecNorm(U0, NORM_INFINITY, &d));
  PetscCall(
    PetscPrintf(PETSC_COMM_SELF, "(6) TSRollBack from t = %.4f: t = %.4f (was %.4f), state differs by %g\n", (double)t2, (double)tb, (double)t1, (double)d));
  TG_CHECK(tb == t1 && d == 0, "rollback to t = %g (want %g), state off by %g", (double)tb, (double)t1, (double)d);
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U0));
  PetscCall(VecDestroy(&U));

  /* (7) the memory TSSetUp takes for a state of n values, lsrk against DOPRI */
  const PetscInt n = 200000;
  PetscReal      bytes[2];
  int            k = 0;
  for (const char *type : {TSLSRK, TSRK}) {
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &U));
    PetscCall(VecSet(U, 1));
    PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
    PetscCall(TSSetType(ts, type));
    if (k == 1) PetscCall(TSRKSetType(ts, TSRK5DP));
    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
    PetscCall(TSSetSolution(ts, U));
    PetscCall(PetscMallocGetCurrentUsage(&before));
    PetscCall(TSSetUp(ts));
    PetscCall(PetscMallocGetCurrentUsage(&after));
    TG_CHECK(after > before, "no allocation seen: run with -malloc_debug (PETSc's malloc tracing)");
    bytes[k++] = (after - before) / (8.0 * n);
    PetscCall(TSDestroy(&ts));
    PetscCall(VecDestroy(&U));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(7) work vectors allocated by TSSetUp, in state-size vectors: lsrk %.3f, DOPRI (rk 5dp) %.3f\n", (double)bytes[0],
                        (double)bytes[1]));
  TG_CHECK(bytes[0] < 3.01, "lsrk allocates %g state vectors (3 expected)", (double)bytes[0]);
  TG_CHECK(bytes[1] > 4 * bytes[0], "DOPRI %g against lsrk %g: the comparison measures nothing", (double)bytes[1], (double)bytes[0]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (9) U' = 0 in implicit form: an explicit method would see a zero right-hand side and integrate
   nothing, so it must refuse */
PetscErrorCode CheckImplicitRefused()
{
  TS             ts;
  Vec            U;
  std::string    msg;
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2, &U));
  PetscCall(VecSet(U, 1));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSLSRK));
  PetscCall(TSSetIFunction(ts, NULL, turgor_test::ZeroRateIFunction, NULL));
  PetscCall(TSSetMaxTime(ts, 1));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(turgor_test::PushMessageCatcher(&msg));
  ierr = TSSolve(ts, U);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(9) an IFunction: %s\n", msg.c_str()));
  TG_CHECK(ierr && msg.find("implicit form") != std::string::npos, "an implicit problem was not refused (%d)", (int)ierr);
  PetscCall(TSDestroy(&ts));
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  PetscCall(CheckTableau());
  PetscCall(CheckOrders());
  PetscCall(CheckAdaptive());
  PetscCall(CheckDomain());
  PetscCall(CheckRollBackAndStorage());
  PetscCall(CheckImplicitRefused());
  PetscCall(PetscFinalize());
  return 0;
}
