/* TS type "lsrk": an adaptive explicit Runge-Kutta pair in three registers (include/turgor/ts/low_storage_rk.h). */
#include <turgor/ts/low_storage_rk.h>
#include <petsc/private/tsimpl.h>
#include "ts_types_internal.h"
#include <cmath>
#include <complex>
#include <vector>

namespace {

/* A 3S* method (Ketcheson 2010): stage i (0-based) updates S2 += delta[i] S1 and
   S1 = gamma[i][0] S1 + gamma[i][1] S2 + gamma[i][2] S3 + beta[i] h f(S1); delta[s], delta[s + 1]
   weigh S1 and S3 in the embedded solution. */
struct Scheme {
  const char *name;
  PetscInt    s, order, embedded_order;
  const PetscReal (*gamma)[3], *beta, *delta; /* [s][3], [s], [s + 2] */
};

/* RK4(3)5[3S*], Ketcheson (2010) table 5, to the 15 digits published: its order conditions hold to
   about 1e-15 (test_low_storage_rk checks them on the tableau reconstructed below). */
constexpr PetscReal kRK435Gamma[5][3] = {
  {0.0,                1.0,                0.0              },
  {-0.497531095840104, 1.384996869124138,  0.0              },
  {1.010070514199942,  3.878155713328178,  0.0              },
  {-3.196559004608766, -2.324512951813145, 1.642598936063715},
  {1.717835630267259,  -0.514633322274467, 0.188295940828347},
};
constexpr PetscReal kRK435Beta[5] = {0.075152045700771, 0.211361016946069, 1.100713347634329, 0.728537814675568, 0.393172889823198};
constexpr PetscReal kRK435Delta[7] =
  {1.0, 0.081252332929194, -1.083849060586449, -1.096110881845602, 2.859440022030827, -0.655568367959557, -0.194421504490852};
constexpr Scheme kRK435 = {"RK4(3)5[3S*]", 5, 4, 3, kRK435Gamma, kRK435Beta, kRK435Delta};

struct LSRK {
  const Scheme *scheme = &kRK435;
  /* the Butcher form of the scheme (TSLSRKGetTableau; c also gives the stage times) */
  std::vector<PetscReal> A, b, bembed, c;
  PetscReal              delta_sum = 0;
  Vec                    S2 = NULL, S3 = NULL, F = NULL; /* the registers besides the solution (S1) */
  PetscInt               room     = 0;                   /* TSLSRKSetRateRoom */
  PetscScalar           *array[2] = {NULL, NULL};        /* S2's and F's with that room */
  /* the last accepted step, [t_prev, t_prev + h_prev]: S3 holds its start until the next step */
  PetscBool have_step = PETSC_FALSE;
  PetscReal t_prev = 0, h_prev = 0;
  /* the end's and the start's rates of the last step, evaluated by TSInterpolate (in F and S2) */
  PetscBool        have_rates    = PETSC_FALSE;
  PetscObjectState state_end     = 0; /* the solution's state when F received f(u_{n+1}) */
  PetscBool        f_is_end      = PETSC_FALSE;
  PetscBool        have_embedded = PETSC_FALSE; /* S2 holds the attempt's embedded solution */
  PetscInt         n_stage = 0, n_interp = 0;
};

/* The tableau of the register recurrence: each register as a combination of u_n (index 0) and the
   stage increments h k_j (index 1 + j), run through the recurrence symbolically. */
void Reconstruct(LSRK *lk)
{
  const Scheme          &m = *lk->scheme;
  const int              s = (int)m.s, n = s + 1;
  std::vector<PetscReal> S1(n, 0), S2(n, 0), S3(n, 0);
  S1[0] = S3[0] = 1;
  lk->A.assign(s * s, 0);
  lk->c.assign(s, 0);
  for (int i = 0; i < s; i++) {
    for (int j = 0; j < s; j++) lk->A[i * s + j] = S1[1 + j]; /* stage i is S1 as it stands */
    for (int k = 0; k < n; k++) S2[k] += m.delta[i] * S1[k];
    for (int k = 0; k < n; k++) S1[k] = m.gamma[i][0] * S1[k] + m.gamma[i][1] * S2[k] + m.gamma[i][2] * S3[k];
    S1[1 + i] += m.beta[i];
  }
  lk->delta_sum = 0;
  for (int i = 0; i < s + 2; i++) lk->delta_sum += m.delta[i];
  lk->b.assign(S1.begin() + 1, S1.end());
  lk->bembed.assign(s, 0);
  for (int j = 0; j < s; j++) lk->bembed[j] = (S2[1 + j] + m.delta[s] * S1[1 + j] + m.delta[s + 1] * S3[1 + j]) / lk->delta_sum;
  for (int i = 0; i < s; i++)
    for (int j = 0; j < s; j++) lk->c[i] += lk->A[i * s + j];
}

PetscErrorCode TSReset_LSRK(TS ts)
{
  LSRK *lk = (LSRK *)ts->data;
  PetscFunctionBeginUser;
  for (Vec *v : {&lk->S2, &lk->S3, &lk->F}) PetscCall(VecDestroy(v));
  for (PetscScalar *&a : lk->array) PetscCall(PetscFree(a));
  lk->have_step = lk->have_rates = lk->f_is_end = lk->have_embedded = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSDestroy_LSRK(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSReset_LSRK(ts));
  delete (LSRK *)ts->data;
  ts->data = NULL;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSLSRKGetTableau_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSLSRKGetCounters_C", NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetUp_LSRK(TS ts)
{
  LSRK   *lk = (LSRK *)ts->data;
  TSAdapt adapt;
  PetscFunctionBeginUser;
  {
    /* U' = f(t, U) only: with an implicit form F(t, U, U') = 0 alone, TSComputeRHSFunction would
       return 0 and the run integrate nothing */
    TSIFunction   ifunction;
    TSRHSFunction rhs;
    PetscCall(TSGetIFunction(ts, NULL, &ifunction, NULL));
    PetscCall(TSGetRHSFunction(ts, NULL, &rhs, NULL));
    PetscCheck(!ifunction, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
               "TS lsrk integrates U' = f(t, U) given by TSSetRHSFunction(); this problem is given in implicit form (TSSetIFunction), which an explicit method "
               "cannot use");
    PetscCheck(rhs, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS lsrk: no right-hand side (TSSetRHSFunction)");
  }
  PetscCall(TSReset_LSRK(ts));
  PetscCall(TurgorVecDuplicateWithRoom(ts->vec_sol, lk->room, &lk->S2, &lk->array[0]));
  PetscCall(VecDuplicate(ts->vec_sol, &lk->S3));
  PetscCall(TurgorVecDuplicateWithRoom(ts->vec_sol, lk->room, &lk->F, &lk->array[1]));
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptCandidatesClear(adapt));
  PetscCall(TSAdaptCandidateAdd(adapt, lk->scheme->name, lk->scheme->order, 1, 1.0, (PetscReal)lk->scheme->s, PETSC_TRUE));
  lk->n_stage = lk->n_interp = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSStep_LSRK(TS ts)
{
  LSRK         *lk = (LSRK *)ts->data;
  const Scheme &m  = *lk->scheme;
  Vec           S1 = ts->vec_sol;
  TSAdapt       adapt;
  PetscInt      rejections = 0;
  PetscBool     accept     = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  const PetscReal  t0 = ts->ptime;
  PetscObjectState state;
  PetscCall(PetscObjectStateGet((PetscObject)S1, &state));
  /* the rate at u_n: the one an interpolation of the last step evaluated at its end, if the
     solution has not changed since (first attempt only: later stages overwrite F) */
  bool first_in_F = lk->f_is_end && lk->have_step && t0 == lk->t_prev + lk->h_prev && state == lk->state_end;
  PetscCall(VecCopy(S1, lk->S3));
  lk->have_step = lk->have_rates = lk->f_is_end = PETSC_FALSE; /* S3 no longer holds the last step's start */
  while (!ts->reason) {
    const PetscReal h     = ts->time_step;
    PetscBool       stage = PETSC_TRUE;
    lk->have_embedded     = PETSC_FALSE;
    for (PetscInt i = 0; i < m.s; i++) {
      const PetscReal ti = t0 + lk->c[i] * h;
      PetscCall(TSPreStage(ts, ti));
      PetscCall(TSPostStage(ts, ti, i, &S1));
      PetscCall(TSAdaptCheckStage(adapt, ts, ti, S1, &stage));
      if (!stage) break;
      if (!(i == 0 && first_in_F)) {
        PetscCall(TSComputeRHSFunction(ts, ti, S1, lk->F));
        lk->n_stage++;
      }
      first_in_F = false;
      if (i == 0) { /* S2 = delta_1 u_n (S2's old values, possibly not finite, not read) */
        PetscCall(VecCopy(S1, lk->S2));
        if (m.delta[0] != 1) PetscCall(VecScale(lk->S2, m.delta[0]));
      } else PetscCall(VecAXPY(lk->S2, m.delta[i], S1));
      PetscCall(VecAXPBYPCZ(S1, m.gamma[i][1], m.gamma[i][2], m.gamma[i][0], lk->S2, lk->S3));
      PetscCall(VecAXPY(S1, m.beta[i] * h, lk->F));
    }
    if (stage) {
      /* the embedded solution, in S2 (TSEvaluateWLTE compares it with S1) */
      const PetscReal w = 1 / lk->delta_sum;
      PetscCall(VecAXPBYPCZ(lk->S2, w * m.delta[m.s], w * m.delta[m.s + 1], w, S1, lk->S3));
      lk->have_embedded = PETSC_TRUE;
      PetscReal next_h  = h;
      PetscCall(TSAdaptChoose(adapt, ts, h, NULL, &next_h, &accept));
      lk->have_embedded = PETSC_FALSE;
      if (accept) {
        ts->ptime     = t0 + h;
        ts->time_step = next_h;
        lk->t_prev    = t0;
        lk->h_prev    = h;
        lk->have_step = PETSC_TRUE;
        break;
      }
      ts->time_step = next_h;
    }                               /* else TSAdaptCheckStage() has reduced ts->time_step */
    PetscCall(VecCopy(lk->S3, S1)); /* back to u_n */
    ts->reject++;
    if (++rejections > ts->max_reject && ts->max_reject >= 0) {
      ts->reason = TS_DIVERGED_STEP_REJECTED;
      PetscCall(
        PetscInfo(ts, "Step %" PetscInt_FMT " at t = %g: %" PetscInt_FMT " rejections, more than -ts_max_reject allows\n", ts->steps, (double)t0, rejections));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ||u_{n+1} - u_hat|| in TSAdapt's weighted norm: O(h^4), order 4 for the controller */
PetscErrorCode TSEvaluateWLTE_LSRK(TS ts, NormType wnormtype, PetscInt *order, PetscReal *wlte)
{
  LSRK     *lk = (LSRK *)ts->data;
  PetscReal wltea, wlter;
  PetscFunctionBeginUser;
  PetscCheck(lk->have_embedded, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS lsrk: the error estimate exists only while a step is chosen");
  if (order) *order = lk->scheme->order;
  PetscCall(TSErrorWeightedNorm(ts, ts->vec_sol, lk->S2, wnormtype, wlte, &wltea, &wlter));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Cubic Hermite over the last step; its two end rates are evaluated once a step, into S2 (start)
   and F (end, kept for the next step's first stage) */
PetscErrorCode TSInterpolate_LSRK(TS ts, PetscReal t, Vec X)
{
  LSRK *lk = (LSRK *)ts->data;
  PetscFunctionBeginUser;
  PetscCheck(lk->have_step, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS lsrk: no step to interpolate in");
  PetscCheck(X != ts->vec_sol, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_IDN, "TS lsrk: cannot interpolate into the solution itself");
  const PetscReal h = lk->h_prev, t1 = lk->t_prev + h;
  if (!lk->have_rates) {
    PetscCall(TSComputeRHSFunction(ts, t1, ts->vec_sol, lk->F));
    PetscCall(PetscObjectStateGet((PetscObject)ts->vec_sol, &lk->state_end));
    lk->f_is_end = PETSC_TRUE;
    PetscCall(TSComputeRHSFunction(ts, lk->t_prev, lk->S3, lk->S2));
    lk->n_interp += 2;
    lk->have_rates = PETSC_TRUE;
  }
  const PetscReal s   = (t - lk->t_prev) / h;
  const PetscReal h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  PetscCall(VecCopy(lk->S3, X)); /* (X's old values not read) */
  PetscCall(VecScale(X, h00));
  PetscCall(VecAXPBYPCZ(X, h01, h * h10, 1.0, ts->vec_sol, lk->S2));
  PetscCall(VecAXPY(X, h * h11, lk->F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* back to the start of the last step (S3 holds it until the next step) */
PetscErrorCode TSRollBack_LSRK(TS ts)
{
  LSRK *lk = (LSRK *)ts->data;
  PetscFunctionBeginUser;
  PetscCheck(lk->have_step, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS lsrk: no step to roll back");
  PetscCall(VecCopy(lk->S3, ts->vec_sol));
  ts->ptime     = lk->t_prev;
  lk->have_step = lk->have_rates = lk->f_is_end = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSView_LSRK(TS ts, PetscViewer viewer)
{
  LSRK     *lk = (LSRK *)ts->data;
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "  low-storage Runge-Kutta %s (order %" PetscInt_FMT ", embedded %" PetscInt_FMT
                                     "), 3 registers + 1 rate vector: %" PetscInt_FMT " stage evaluations, %" PetscInt_FMT " for interpolation\n",
                                     lk->scheme->name, lk->scheme->order, lk->scheme->embedded_order, lk->n_stage, lk->n_interp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y' = lambda y: the stability function R(z) = 1 + z b^T (I - z A)^-1 1, explicit: by the stages */
PetscErrorCode TSComputeLinearStability_LSRK(TS ts, PetscReal xr, PetscReal xi, PetscReal *yr, PetscReal *yi)
{
  using Complex           = std::complex<double>;
  LSRK                *lk = (LSRK *)ts->data;
  const PetscInt       s  = lk->scheme->s;
  const Complex        z(xr, xi);
  std::vector<Complex> y(s);
  Complex              r = 1;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < s; i++) { /* the stage values for y_n = 1 */
    y[i] = 1;
    for (PetscInt j = 0; j < i; j++) y[i] += lk->A[i * s + j] * z * y[j];
    r += lk->b[i] * z * y[i];
  }
  *yr = (PetscReal)r.real();
  *yi = (PetscReal)r.imag();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSLSRKGetTableau_LSRK(TS ts, PetscInt *s, const PetscReal **A, const PetscReal **b, const PetscReal **bembed, const PetscReal **c,
                                     PetscInt *order, PetscInt *embedded_order)
{
  LSRK *lk = (LSRK *)ts->data;
  PetscFunctionBeginUser;
  if (s) *s = lk->scheme->s;
  if (A) *A = lk->A.data();
  if (b) *b = lk->b.data();
  if (bembed) *bembed = lk->bembed.data();
  if (c) *c = lk->c.data();
  if (order) *order = lk->scheme->order;
  if (embedded_order) *embedded_order = lk->scheme->embedded_order;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSLSRKGetCounters_LSRK(TS ts, PetscInt *stage_evaluations, PetscInt *interpolation_evaluations)
{
  LSRK *lk = (LSRK *)ts->data;
  PetscFunctionBeginUser;
  if (stage_evaluations) *stage_evaluations = lk->n_stage;
  if (interpolation_evaluations) *interpolation_evaluations = lk->n_interp;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode TSLSRKGetTableau(TS ts, PetscInt *s, const PetscReal **A, const PetscReal **b, const PetscReal **bembed, const PetscReal **c, PetscInt *order,
                                PetscInt *embedded_order)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSLSRKGetTableau_C",
                 (TS, PetscInt *, const PetscReal **, const PetscReal **, const PetscReal **, const PetscReal **, PetscInt *, PetscInt *),
                 (ts, s, A, b, bembed, c, order, embedded_order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSLSRKGetCounters(TS ts, PetscInt *stage_evaluations, PetscInt *interpolation_evaluations)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSLSRKGetCounters_C", (TS, PetscInt *, PetscInt *), (ts, stage_evaluations, interpolation_evaluations));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSLSRKSetRateRoom(TS ts, PetscInt extra)
{
  PetscBool is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSLSRK, &is));
  PetscCheck(is, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONG, "TSLSRKSetRateRoom: the TS is not of type lsrk");
  PetscCheck(extra >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSLSRKSetRateRoom: extra = %" PetscInt_FMT " < 0", extra);
  LSRK *lk = (LSRK *)ts->data;
  PetscCheck(!lk->F, PetscObjectComm((PetscObject)ts), PETSC_ERR_ORDER, "TSLSRKSetRateRoom: call before TSSetUp");
  lk->room = extra;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* registered by TurgorTSRegisterAll() (ts_register.cpp) */
PetscErrorCode TSCreate_LSRK(TS ts)
{
  LSRK *lk = new LSRK();
  PetscFunctionBeginUser;
  Reconstruct(lk);
  ts->data                 = lk;
  ts->ops->setup           = TSSetUp_LSRK;
  ts->ops->step            = TSStep_LSRK;
  ts->ops->evaluatewlte    = TSEvaluateWLTE_LSRK;
  ts->ops->interpolate     = TSInterpolate_LSRK;
  ts->ops->rollback        = TSRollBack_LSRK;
  ts->ops->reset           = TSReset_LSRK;
  ts->ops->destroy         = TSDestroy_LSRK;
  ts->ops->view            = TSView_LSRK;
  ts->ops->linearstability = TSComputeLinearStability_LSRK;
  ts->usessnes             = PETSC_FALSE;
  /* a PI controller: an explicit particle run's step sits at the stability limit, where the basic
     controller's accept-grow-reject cycle rejected 2 836 of 3 200 steps of the fine bending bar
     (DSP: 1, and 38 % fewer evaluations than DOPRI) */
  ts->default_adapt_type = TSADAPTDSP;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSLSRKGetTableau_C", TSLSRKGetTableau_LSRK));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSLSRKGetCounters_C", TSLSRKGetCounters_LSRK));
  PetscFunctionReturn(PETSC_SUCCESS);
}
