/* TS type "verlet": kick-drift-kick velocity Verlet (include/turgor/ts/velocity_verlet.h). */
#include <turgor/ts/velocity_verlet.h>
#include <petsc/private/tsimpl.h>
#include "ts_types_internal.h"
#include <turgor/core/finite_scan.h>
#include <turgor/core/vector_clones.h>
#include <cstdint>
#include <utility>

namespace {

struct Verlet {
  IS               is_q = NULL, is_p = NULL;
  TS               subts_q = NULL, subts_p = NULL;
  Vec              A0 = NULL, A1 = NULL;      /* accelerations at the step's ends (A1 also holds the drift's rate) */
  PetscBool        have_a1     = PETSC_FALSE; /* A1 holds a(x) at the solution of time t_a1, state state_a1 */
  PetscReal        t_a1        = 0;
  PetscObjectState state_a1    = 0;
  PetscInt         evaluations = 0, reused = 0;
  PetscInt         room     = 0;            /* TSVerletSetAccelerationRoom */
  PetscScalar     *array[2] = {NULL, NULL}; /* A0's and A1's with that room */
  /* The step's views of the solution's two parts, where each is a contiguous range of every rank's
     part (turgor's [x | v]): placed on the solution's array at offsets off_q, off_p. VecGetSubVector
     makes and destroys a Vec per call, about 20 000 instructions a step: 40 % of a step of the
     102-node chain. */
  Vec          view_q = NULL, view_p = NULL;
  PetscInt     off_q = 0, off_p = 0;
  PetscScalar *sol_array                                    = NULL;
  PetscErrorCode (*impose)(TS, PetscReal, Vec, Vec, void *) = NULL; /* TSVerletSetConstraints */
  void *impose_ctx                                          = NULL;
};

/* y += a x on this rank's values: VecAXPY's bits (y + a x, value by value, as the reference BLAS's
   daxpy), in a loop the compiler vectorises (AVX2 where the CPU has it): the step's kicks and drift,
   about a quarter of a small tissue's step beyond its forces through daxpy. */
TURGOR_VECTOR_CLONES void AxpyLoop(PetscInt n, PetscScalar a, const PetscScalar *__restrict x, PetscScalar *__restrict y)
{
  for (PetscInt i = 0; i < n; i++) y[i] += a * x[i];
}

/* ... and whether the values written are finite (core/finite_scan.h), in the same loop: a separate
   scan of the step's end read x and v again, about a tenth of a small tissue's step beyond its
   forces */
TURGOR_VECTOR_CLONES std::uint64_t AxpyLoopCarries(PetscInt n, PetscScalar a, const PetscScalar *__restrict x, PetscScalar *__restrict y)
{
  std::uint64_t carries = 0;
  for (PetscInt i = 0; i < n; i++) {
    const PetscScalar yi = y[i] + a * x[i];
    y[i]                 = yi;
    carries |= turgor::ExponentCarry(yi);
  }
  return carries;
}

/* y += a x; with carries, also OR in the carries of the values written */
PetscErrorCode Axpy(Vec y, PetscScalar a, Vec x, std::uint64_t *carries = nullptr)
{
  const PetscScalar *xa;
  PetscScalar       *ya;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(y, &n));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  if (carries) *carries |= AxpyLoopCarries(n, a, xa, ya);
  else AxpyLoop(n, a, xa, ya);
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscLogFlops(2.0 * n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The solution's parts q, p for a step: the views placed on its array, or sub-vectors. */
PetscErrorCode GetParts(TS ts, Verlet *vv, Vec *q, Vec *p)
{
  PetscFunctionBeginUser;
  if (vv->view_q) {
    PetscCall(VecGetArray(ts->vec_sol, &vv->sol_array));
    PetscCall(VecPlaceArray(vv->view_q, vv->sol_array + vv->off_q));
    PetscCall(VecPlaceArray(vv->view_p, vv->sol_array + vv->off_p));
    *q = vv->view_q, *p = vv->view_p;
  } else {
    PetscCall(VecGetSubVector(ts->vec_sol, vv->is_q, q));
    PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, p));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ... and back (the solution's state increases: it was changed) */
PetscErrorCode RestoreParts(TS ts, Verlet *vv, Vec *q, Vec *p)
{
  PetscFunctionBeginUser;
  if (vv->view_q) {
    PetscCall(VecResetArray(vv->view_p));
    PetscCall(VecResetArray(vv->view_q));
    PetscCall(VecRestoreArray(ts->vec_sol, &vv->sol_array));
    *q = *p = NULL;
  } else {
    PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, p));
    PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_q, q));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The views, where both splits are contiguous ranges of every rank's part of the solution (the same
   decision on every rank: creating a Vec is collective). */
PetscErrorCode CreateViews(TS ts, Verlet *vv)
{
  PetscInt  lo, hi, first[2] = {0, 0};
  PetscBool contiguous[2];
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(ts->vec_sol, &lo, &hi));
  PetscCall(ISContiguousLocal(vv->is_q, lo, hi, &first[0], &contiguous[0]));
  PetscCall(ISContiguousLocal(vv->is_p, lo, hi, &first[1], &contiguous[1]));
  PetscMPIInt all = contiguous[0] && contiguous[1];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_LAND, PetscObjectComm((PetscObject)ts)));
  if (!all) PetscFunctionReturn(PETSC_SUCCESS);
  const IS is[2]   = {vv->is_q, vv->is_p};
  Vec     *view[2] = {&vv->view_q, &vv->view_p};
  for (int k = 0; k < 2; k++) {
    Vec      part;
    PetscInt n, N, bs;
    PetscCall(VecGetSubVector(ts->vec_sol, is[k], &part));
    PetscCall(VecGetLocalSize(part, &n));
    PetscCall(VecGetSize(part, &N));
    PetscCall(VecGetBlockSize(part, &bs));
    PetscCall(VecRestoreSubVector(ts->vec_sol, is[k], &part));
    PetscCall(VecCreateMPIWithArray(PetscObjectComm((PetscObject)ts), bs, n, N, NULL, view[k]));
  }
  vv->off_q = first[0], vv->off_p = first[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSReset_Verlet(TS ts)
{
  Verlet *vv = (Verlet *)ts->data;
  PetscFunctionBeginUser;
  for (Vec *v : {&vv->A0, &vv->A1, &vv->view_q, &vv->view_p}) PetscCall(VecDestroy(v));
  for (PetscScalar *&a : vv->array) PetscCall(PetscFree(a));
  vv->have_a1 = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSDestroy_Verlet(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSReset_Verlet(ts));
  delete (Verlet *)ts->data;
  ts->data = NULL;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSVerletGetCounters_C", NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetUp_Verlet(TS ts)
{
  Verlet *vv = (Verlet *)ts->data;
  Vec     p;
  PetscFunctionBeginUser;
  PetscCall(TSRHSSplitGetIS(ts, "position", &vv->is_q));
  PetscCall(TSRHSSplitGetIS(ts, "momentum", &vv->is_p));
  PetscCheck(vv->is_q && vv->is_p, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER,
             "TS verlet needs the splits \"position\" and \"momentum\" (TSRHSSplitSetIS), as basicsymplectic does");
  PetscCall(TSRHSSplitGetSubTS(ts, "position", &vv->subts_q));
  PetscCall(TSRHSSplitGetSubTS(ts, "momentum", &vv->subts_p));
  PetscCheck(vv->subts_q && vv->subts_p, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER,
             "TS verlet needs the right-hand sides of the splits \"position\" and \"momentum\" (TSRHSSplitSetRHSFunction)");
  PetscCall(TSReset_Verlet(ts));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, &p));
  PetscCall(TurgorVecDuplicateWithRoom(p, vv->room, &vv->A0, &vv->array[0]));
  PetscCall(TurgorVecDuplicateWithRoom(p, vv->room, &vv->A1, &vv->array[1]));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, &p));
  PetscCall(CreateViews(ts, vv));
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptCandidatesClear(ts->adapt)); /* a fixed step */
  vv->evaluations = vv->reused = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a(x) at time t into A, for the positions q of the solution */
PetscErrorCode Accelerate(TS ts, Verlet *vv, PetscReal t, Vec q, Vec A)
{
  PetscFunctionBeginUser;
  PetscCall(TSComputeRHSFunction(vv->subts_p, t, q, A));
  vv->evaluations++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The state at the start of the last step, from its end: no copy of the state is kept (32 B a
   particle). The step's own operations undone in reverse, v+ = v_{n+1} - h/2 a(x_{n+1}),
   x_n = x_{n+1} - h v+, v_n = v+ - h/2 a(x_n): exact but for round-off (within an ulp or so of
   x_{n+1} and v_{n+1}), which is all the interpolation of outputs and the rollback of a rejected
   step (whose state ends the run) need. A component whose drift the position right-hand side
   prescribes instead of v+ (turgor's velocity controls) comes back as x_{n+1} - h v+: the fine
   run imposes those components at every output's time anyway (Controls::Impose). Y: the solution
   itself, or a work vector. */
PetscErrorCode StepBack(TS ts, Verlet *vv, Vec Y)
{
  const PetscReal h = ts->time_step;
  Vec             q, p;
  PetscFunctionBeginUser;
  if (Y != ts->vec_sol) PetscCall(VecCopy(ts->vec_sol, Y));
  PetscCall(VecGetSubVector(Y, vv->is_q, &q));
  PetscCall(VecGetSubVector(Y, vv->is_p, &p));
  PetscCall(VecAXPY(p, -0.5 * h, vv->A1));
  PetscCall(VecAXPY(q, -h, p));
  PetscCall(VecAXPY(p, -0.5 * h, vv->A0));
  PetscCall(VecRestoreSubVector(Y, vv->is_p, &p));
  PetscCall(VecRestoreSubVector(Y, vv->is_q, &q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether the step's end is finite on every rank (one rank: no reduction), from the carries of the
   values its drift and last kick wrote. The constraints' values and a post-stage hook's are the caller's and not scanned. */
PetscErrorCode EndIsFinite(TS ts, std::uint64_t carries, PetscBool *finite)
{
  PetscMPIInt size, ok = turgor::CarriesFinite(carries);
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ts), &size));
  if (size > 1) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, PetscObjectComm((PetscObject)ts)));
  *finite = ok ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSStep_Verlet(TS ts)
{
  Verlet          *vv = (Verlet *)ts->data;
  const PetscReal  h = ts->time_step, t0 = ts->ptime;
  Vec              q, p;
  PetscObjectState state;
  PetscBool        ok;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectStateGet((PetscObject)ts->vec_sol, &state));
  /* the acceleration at x_n: the previous step's last one, unless the solution was changed since */
  const bool reuse = vv->have_a1 && vv->t_a1 == t0 && vv->state_a1 == state;
  PetscCall(TSPreStage(ts, t0));
  PetscCall(GetParts(ts, vv, &q, &p));
  if (reuse) { /* the two Vecs trade places (they share a layout and a room): no values copied */
    std::swap(vv->A0, vv->A1);
    std::swap(vv->array[0], vv->array[1]);
    vv->reused++;
  } else {
    if (vv->impose) PetscCall(vv->impose(ts, t0, q, p, vv->impose_ctx));
    PetscCall(Accelerate(ts, vv, t0, q, vv->A0));
  }
  PetscCall(Axpy(p, 0.5 * h, vv->A0)); /* kick */
  /* drift: dx/dt = v+, into A1, free until a(x_{n+1}) (one work vector fewer: 16 B a particle) */
  vv->have_a1           = PETSC_FALSE;
  std::uint64_t carries = 0; /* whether the step's end is finite, as its loops write it */
  PetscCall(TSComputeRHSFunction(vv->subts_q, t0, p, vv->A1));
  PetscCall(Axpy(q, h, vv->A1, &carries));
  if (vv->impose) PetscCall(vv->impose(ts, t0 + h, q, p, vv->impose_ctx)); /* the second kick leaves them: their accelerations are 0 */
  PetscCall(Accelerate(ts, vv, t0 + h, q, vv->A1));                        /* a(x_{n+1}), reused by the next step */
  PetscCall(Axpy(p, 0.5 * h, vv->A1, &carries));                           /* kick */
  PetscCall(RestoreParts(ts, vv, &q, &p));
  ts->ptime = t0 + h;
  PetscCall(TSPostStage(ts, ts->ptime, 0, &ts->vec_sol));
  PetscCall(EndIsFinite(ts, carries, &ok));
  if (ok) PetscCall(TSAdaptCheckStage(ts->adapt, ts, ts->ptime, ts->vec_sol, &ok)); /* (with the user's domain check, TSSetFunctionDomainError) */
  if (!ok) { /* back to the start of the step (to round-off); a fixed-step integrator cannot retry smaller */
    PetscReal norm;
    ts->time_step = h; /* TSAdaptCheckStage shrank it on the rejection: the step taken was h */
    PetscCall(StepBack(ts, vv, ts->vec_sol));
    PetscCall(VecNorm(ts->vec_sol, NORM_INFINITY, &norm));
    PetscCheck(!PetscIsInfOrNanReal(norm), PetscObjectComm((PetscObject)ts), PETSC_ERR_FP,
               "TS verlet: the step from t = %g was rejected and its start cannot be recovered from a non-finite end (the step h = %g is likely "
               "above the stability limit: lower it)",
               (double)t0, (double)h);
    ts->ptime   = t0;
    vv->have_a1 = PETSC_FALSE;
    ts->reason  = TS_DIVERGED_STEP_REJECTED;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscObjectStateGet((PetscObject)ts->vec_sol, &vv->state_a1));
  vv->t_a1    = ts->ptime;
  vv->have_a1 = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cubic Hermite over [t_n, t_{n+1}]: x from (x, v) at both ends, v from (v, a) at both ends; the
   start's (x_n, v_n) recovered from the end (StepBack) into X, then combined there in place. */
PetscErrorCode TSInterpolate_Verlet(TS ts, PetscReal t, Vec X)
{
  Verlet         *vv = (Verlet *)ts->data;
  const PetscReal h = ts->time_step, s = (t - (ts->ptime - h)) / h;
  const PetscReal h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  Vec             q1, p1, q, p;
  PetscFunctionBeginUser;
  PetscCheck(vv->have_a1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ORDER, "TS verlet: nothing to interpolate before the first step");
  PetscCheck(X != ts->vec_sol, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_IDN, "TS verlet: cannot interpolate into the solution itself");
  PetscCall(StepBack(ts, vv, X)); /* X = (x_n, v_n) */
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_q, &q1));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, &p1));
  PetscCall(VecGetSubVector(X, vv->is_q, &q));
  PetscCall(VecGetSubVector(X, vv->is_p, &p));
  /* the velocities are dx/dt: v+ would be the drift's; the ends' v are used */
  PetscCall(VecAXPBYPCZ(q, h01, h10 * h, h00, q1, p)); /* q = h00 x_n + h01 x_{n+1} + h h10 v_n */
  PetscCall(VecAXPY(q, h11 * h, p1));
  PetscCall(VecAXPBYPCZ(p, h01, h10 * h, h00, p1, vv->A0)); /* p = h00 v_n + h01 v_{n+1} + h h10 a_n */
  PetscCall(VecAXPY(p, h11 * h, vv->A1));
  PetscCall(VecRestoreSubVector(X, vv->is_p, &p));
  PetscCall(VecRestoreSubVector(X, vv->is_q, &q));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, &p1));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_q, &q1));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSView_Verlet(TS ts, PetscViewer viewer)
{
  Verlet   *vv = (Verlet *)ts->data;
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  kick-drift-kick velocity Verlet: %" PetscInt_FMT " force evaluations, %" PetscInt_FMT " reused\n",
                                     vv->evaluations, vv->reused));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSVerletGetCounters_Verlet(TS ts, PetscInt *evaluations, PetscInt *reused)
{
  Verlet *vv = (Verlet *)ts->data;
  PetscFunctionBeginUser;
  if (evaluations) *evaluations = vv->evaluations;
  if (reused) *reused = vv->reused;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* x'' = -w^2 x: the amplification matrix of one step has eigenvalues on the unit circle for
   |w h| <= 2; PETSc asks for the linear stability of y' = lambda y, which for this splitting
   scheme is not defined: report the symplectic Euler value as basicsymplectic does. */
PetscErrorCode TSComputeLinearStability_Verlet(TS ts, PetscReal xr, PetscReal xi, PetscReal *yr, PetscReal *yi)
{
  PetscFunctionBeginUser;
  *yr = 1.0 + xr;
  *yi = xi;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode TSVerletGetCounters(TS ts, PetscInt *evaluations, PetscInt *reused)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSVerletGetCounters_C", (TS, PetscInt *, PetscInt *), (ts, evaluations, reused));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCreate_Verlet(TS ts)
{
  PetscFunctionBeginUser;
  ts->data                 = new Verlet();
  ts->ops->setup           = TSSetUp_Verlet;
  ts->ops->step            = TSStep_Verlet;
  ts->ops->reset           = TSReset_Verlet;
  ts->ops->destroy         = TSDestroy_Verlet;
  ts->ops->view            = TSView_Verlet;
  ts->ops->interpolate     = TSInterpolate_Verlet;
  ts->ops->linearstability = TSComputeLinearStability_Verlet;
  ts->usessnes             = PETSC_FALSE;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSVerletGetCounters_C", TSVerletGetCounters_Verlet));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSVerletGetLastAcceleration(TS ts, Vec *A1, PetscBool *have)
{
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSVerletGetLastAcceleration: the TS is not of type verlet");
  Verlet *vv = (Verlet *)ts->data;
  *A1        = vv->A1;
  *have      = vv->have_a1 && vv->t_a1 == ts->ptime ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSVerletSetLastAcceleration(TS ts, Vec A1)
{
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSVerletSetLastAcceleration: the TS is not of type verlet");
  Verlet *vv = (Verlet *)ts->data;
  PetscCheck(vv->A1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ORDER, "TSVerletSetLastAcceleration: call after TSSetUp");
  PetscCall(VecCopy(A1, vv->A1));
  PetscCall(PetscObjectStateGet((PetscObject)ts->vec_sol, &vv->state_a1));
  vv->t_a1    = ts->ptime;
  vv->have_a1 = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSVerletSetConstraints(TS ts, PetscErrorCode (*impose)(TS, PetscReal, Vec, Vec, void *), void *ctx)
{
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSVerletSetConstraints: the TS is not of type verlet");
  Verlet *vv     = (Verlet *)ts->data;
  vv->impose     = impose;
  vv->impose_ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSVerletSetAccelerationRoom(TS ts, PetscInt extra)
{
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSVerletSetAccelerationRoom: the TS is not of type verlet");
  PetscCheck(extra >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSVerletSetAccelerationRoom: extra = %" PetscInt_FMT " < 0", extra);
  Verlet *vv = (Verlet *)ts->data;
  PetscCheck(!vv->A0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ORDER, "TSVerletSetAccelerationRoom: call before TSSetUp");
  vv->room = extra;
  PetscFunctionReturn(PETSC_SUCCESS);
}
