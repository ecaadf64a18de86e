/* TS type "verlet": kick-drift-kick velocity Verlet (include/turgor/ts/velocity_verlet.h). */
#include <turgor/ts/velocity_verlet.h>
#include <petsc/private/tsimpl.h>
#include "ts_types_internal.h"

namespace {

struct Verlet {
  IS               is_q = NULL, is_p = NULL;
  TS               subts_q = NULL, subts_p = NULL;
  Vec              X0 = NULL, A0 = NULL, A1 = NULL; /* state and accelerations at the step's ends (A1 also holds the drift's rate) */
  PetscBool        have_a1     = PETSC_FALSE;       /* A1 holds a(x) at the solution of time t_a1, state state_a1 */
  PetscReal        t_a1        = 0;
  PetscObjectState state_a1    = 0;
  PetscInt         evaluations = 0, reused = 0;
};

PetscErrorCode TSReset_Verlet(TS ts)
{
  Verlet *vv = (Verlet *)ts->data;
  PetscFunctionBeginUser;
  for (Vec *v : {&vv->X0, &vv->A0, &vv->A1}) PetscCall(VecDestroy(v));
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
  PetscCall(VecDuplicate(ts->vec_sol, &vv->X0));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, &p));
  PetscCall(VecDuplicate(p, &vv->A0));
  PetscCall(VecDuplicate(p, &vv->A1));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, &p));
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

PetscErrorCode TSStep_Verlet(TS ts)
{
  Verlet          *vv = (Verlet *)ts->data;
  const PetscReal  h = ts->time_step, t0 = ts->ptime;
  Vec              q, p;
  PetscObjectState state;
  PetscBool        ok;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(ts->vec_sol, vv->X0));
  PetscCall(PetscObjectStateGet((PetscObject)ts->vec_sol, &state));
  /* the acceleration at x_n: the previous step's last one, unless the solution was changed since */
  const bool reuse = vv->have_a1 && vv->t_a1 == t0 && vv->state_a1 == state;
  PetscCall(TSPreStage(ts, t0));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_q, &q));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, &p));
  if (reuse) {
    PetscCall(VecSwap(vv->A0, vv->A1));
    vv->reused++;
  } else PetscCall(Accelerate(ts, vv, t0, q, vv->A0));
  PetscCall(VecAXPY(p, 0.5 * h, vv->A0)); /* kick */
  /* drift: dx/dt = v+, into A1, free until a(x_{n+1}) (one work vector fewer: 16 B a particle) */
  vv->have_a1 = PETSC_FALSE;
  PetscCall(TSComputeRHSFunction(vv->subts_q, t0, p, vv->A1));
  PetscCall(VecAXPY(q, h, vv->A1));
  PetscCall(Accelerate(ts, vv, t0 + h, q, vv->A1)); /* a(x_{n+1}), reused by the next step */
  PetscCall(VecAXPY(p, 0.5 * h, vv->A1));           /* kick */
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, &p));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_q, &q));
  ts->ptime = t0 + h;
  PetscCall(TSPostStage(ts, ts->ptime, 0, &ts->vec_sol));
  PetscCall(TSAdaptCheckStage(ts->adapt, ts, ts->ptime, ts->vec_sol, &ok));
  if (ok) PetscCall(TSFunctionDomainError(ts, ts->ptime, ts->vec_sol, &ok));
  if (!ok) { /* back to the start of the step; a fixed-step integrator cannot retry smaller */
    PetscCall(VecCopy(vv->X0, ts->vec_sol));
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

/* Cubic Hermite over [t_n, t_{n+1}]: x from (x, v) at both ends, v from (v, a) at both ends. */
PetscErrorCode TSInterpolate_Verlet(TS ts, PetscReal t, Vec X)
{
  Verlet         *vv = (Verlet *)ts->data;
  const PetscReal h = ts->time_step, s = (t - (ts->ptime - h)) / h;
  const PetscReal h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  Vec             q0, p0, q1, p1, q, p;
  PetscFunctionBeginUser;
  PetscCheck(vv->have_a1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ORDER, "TS verlet: nothing to interpolate before the first step");
  PetscCall(VecGetSubVector(vv->X0, vv->is_q, &q0));
  PetscCall(VecGetSubVector(vv->X0, vv->is_p, &p0));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_q, &q1));
  PetscCall(VecGetSubVector(ts->vec_sol, vv->is_p, &p1));
  PetscCall(VecGetSubVector(X, vv->is_q, &q));
  PetscCall(VecGetSubVector(X, vv->is_p, &p));
  PetscCall(VecAXPBYPCZ(q, h00, h01, 0.0, q0, q1)); /* the velocities are dx/dt: v+ would be the drift's; the ends' v are used */
  PetscCall(VecAXPBYPCZ(q, h10 * h, h11 * h, 1.0, p0, p1));
  PetscCall(VecAXPBYPCZ(p, h00, h01, 0.0, p0, p1));
  PetscCall(VecAXPBYPCZ(p, h10 * h, h11 * h, 1.0, vv->A0, vv->A1));
  PetscCall(VecRestoreSubVector(X, vv->is_p, &p));
  PetscCall(VecRestoreSubVector(X, vv->is_q, &q));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_p, &p1));
  PetscCall(VecRestoreSubVector(ts->vec_sol, vv->is_q, &q1));
  PetscCall(VecRestoreSubVector(vv->X0, vv->is_p, &p0));
  PetscCall(VecRestoreSubVector(vv->X0, vv->is_q, &q0));
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
