static const char help[] = "TS verlet's handling of a step that goes wrong, on x'' = -x (one degree of freedom):\n"
                           "1. a step whose end is not finite (the acceleration NaN below x = xnan) fails the solve with\n"
                           "   PETSC_ERR_FP, with no domain check set: the step's own loops check what they write;\n"
                           "2. a step that the user's domain check (TSSetFunctionDomainError) rejects ends the solve with\n"
                           "   TS_DIVERGED_STEP_REJECTED (-ts_error_if_step_fails false) at the step's start, whose state\n"
                           "   is recovered from the end to round-off;\n"
                           "3. with neither, the run follows x = cos t, v = -sin t (within 2e-5 at t = 1, h = 0.01).\n";
#include "test_util.h"
#include <turgor/ts/velocity_verlet.h>
#include <limits>

namespace {

struct Oscillator {
  PetscReal xnan   = PETSC_MIN_REAL; /* the acceleration is NaN below this x */
  PetscReal reject = PETSC_MAX_REAL; /* the domain check rejects a step ending after this time */
};

PetscErrorCode Position(TS, PetscReal, Vec V, Vec Xdot, void *)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(V, Xdot));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Momentum(TS, PetscReal, Vec X, Vec A, void *ctx)
{
  const Oscillator  *o = (const Oscillator *)ctx;
  const PetscScalar *x;
  PetscScalar       *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(A, &a));
  a[0] = x[0] < o->xnan ? std::numeric_limits<PetscReal>::quiet_NaN() : -x[0];
  PetscCall(VecRestoreArray(A, &a));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Domain(TS ts, PetscReal t, Vec, PetscBool *accept)
{
  void *ctx;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &ctx));
  *accept = t > ((const Oscillator *)ctx)->reject ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct Outcome {
  PetscErrorCode    ierr = 0;
  TSConvergedReason reason;
  PetscReal         t = 0, x = 0, v = 0;
};

/* from x = 1, v = 0, steps of h to T */
PetscErrorCode Run(Oscillator &o, PetscReal h, PetscReal T, bool domain, Outcome *out)
{
  TS           ts;
  Vec          U;
  IS           is_x, is_v;
  PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2, &U));
  PetscCall(VecGetArray(U, &u));
  u[0] = 1, u[1] = 0;
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 1, 0, 1, &is_x));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, 1, 1, 1, &is_v));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSVERLET));
  PetscCall(TSSetApplicationContext(ts, &o));
  PetscCall(TSRHSSplitSetIS(ts, "position", is_x));
  PetscCall(TSRHSSplitSetIS(ts, "momentum", is_v));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "position", NULL, Position, &o));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "momentum", NULL, Momentum, &o));
  if (domain) PetscCall(TSSetFunctionDomainError(ts, Domain));
  PetscCall(TSSetTimeStep(ts, h));
  PetscCall(TSSetMaxTime(ts, T));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetErrorIfStepFails(ts, PETSC_FALSE));
  PetscCall(TSSetSolution(ts, U));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  out->ierr = TSSolve(ts, U);
  PetscCall(PetscPopErrorHandler());
  PetscCall(TSGetConvergedReason(ts, &out->reason));
  PetscCall(TSGetTime(ts, &out->t));
  PetscCall(VecGetArray(U, &u));
  out->x = PetscRealPart(u[0]), out->v = PetscRealPart(u[1]);
  PetscCall(VecRestoreArray(U, &u));
  PetscCall(TSDestroy(&ts));
  PetscCall(ISDestroy(&is_v));
  PetscCall(ISDestroy(&is_x));
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  const PetscReal h = 0.01;
  { /* 3: the reference, and the scheme's error */
    Oscillator o;
    Outcome    r;
    PetscCall(Run(o, h, 1.0, false, &r));
    TG_CHECK(!r.ierr && r.reason > 0, "a plain run failed: error %d, reason %s", (int)r.ierr, TSConvergedReasons[r.reason]);
    TG_CHECK(std::fabs(r.x - std::cos(r.t)) < 2e-5 && std::fabs(r.v + std::sin(r.t)) < 2e-5, "x = %.12g, v = %.12g at t = %g against cos, -sin", (double)r.x,
             (double)r.v, (double)r.t);
  }
  { /* 1: x = cos t falls below 0 at t = pi/2; a NaN acceleration there, no domain check */
    Oscillator o;
    Outcome    r;
    o.xnan = 0;
    PetscCall(Run(o, h, 3.0, false, &r));
    TG_CHECK(r.ierr == PETSC_ERR_FP, "a step ending in NaN: error %d (expected PETSC_ERR_FP = %d), reason %s, t = %g, x = %g", (int)r.ierr, (int)PETSC_ERR_FP,
             TSConvergedReasons[r.reason], (double)r.t, (double)r.x);
    TG_CHECK(std::fabs(r.t - 0.5 * PETSC_PI) < 2 * h, "the NaN step was taken at t = %g, not near pi/2", (double)r.t);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "a step ending in NaN near t = pi/2: the solve fails with PETSC_ERR_FP at t = %g\n", (double)r.t));
  }
  { /* 2: the domain check rejects the step that ends after t = 1 */
    Oscillator o;
    Outcome    r, ref;
    o.reject = 1.0;
    PetscCall(Run(o, h, 3.0, true, &r));
    TG_CHECK(!r.ierr && r.reason == TS_DIVERGED_STEP_REJECTED, "a rejected step: error %d, reason %s", (int)r.ierr, TSConvergedReasons[r.reason]);
    TG_CHECK(r.t <= 1.0 && r.t > 1.0 - 1.5 * h, "the rejected step started at t = %g, not just before 1", (double)r.t);
    Oscillator plain;
    PetscCall(Run(plain, h, r.t, false, &ref));
    TG_CHECK(std::fabs(ref.t - r.t) < 1e-12, "the reference ended at t = %g, not %g", (double)ref.t, (double)r.t);
    TG_CHECK(std::fabs(r.x - ref.x) < 1e-14 && std::fabs(r.v - ref.v) < 1e-14,
             "the state after the rejection (%.17g, %.17g) is not the step's start (%.17g, %.17g)", (double)r.x, (double)r.v, (double)ref.x, (double)ref.v);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "a step rejected by the domain check: back at t = %g, state off by %.2e, %.2e\n", (double)r.t,
                          (double)std::fabs(r.x - ref.x), (double)std::fabs(r.v - ref.v)));
  }
  PetscCall(PetscFinalize());
  return 0;
}
