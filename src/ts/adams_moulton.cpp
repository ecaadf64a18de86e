/* Variable-order, variable-step Adams-Moulton with functional iteration, as the PETSc TS type "am"
   (docs/adams_moulton.md). The method is that of SUNDIALS CVODE with CV_ADAMS and functional
   iteration; the step size is chosen by TSAdapt.

   Problem: U' = f(t, U) from TSSetRHSFunction(). No Jacobian is used.

   Representation: the Nordsieck array z_j = h^j U^(j)(t_n) / j!, j = 0..q, of the polynomial p_n
   of degree q whose derivative interpolates f at t_n, ..., t_{n-q+1} and with p_n(t_n) = U_n. A
   step of size h (order q):
     predict   z(0) = Pascal(z_{n-1} rescaled to h)          (Adams-Bashforth of order q)
     correct   z_n  = z(0) + l Delta,  Delta = U_n - U_n(0)   (Adams-Moulton of order q)
   where l holds the coefficients of the polynomial Lambda(s) of degree q with Lambda(0) = 1,
   Lambda(-1) = 0 and Lambda'(-xi_j) = 0, j = 1..q-1, xi_j = (t_n - t_{n-j}) / h: adding
   Delta Lambda keeps the old interpolation conditions and the value at t_{n-1}. The corrector
   equation z_n[1] = h f(t_n, U_n) is solved for Delta by fixed-point iteration on f.
   All coefficients are derived at each step from the actual step history (variable-coefficient
   Adams), from integrals over [-1, 0] of products of (s + xi_j). */
#include <turgor/ts/adams_moulton.h>
#include "ts_types_internal.h"
#include <petsc/private/tsimpl.h>
#include <algorithm>
#include <cmath>
#include <utility>

namespace {

constexpr PetscInt kMaxOrder = 12; /* CVODE's limit for Adams */

/* CVODE's safety factors (bias) on the error estimates at orders q-1, q and q+1 when the next order
   is chosen, and the guard added to each step ratio. */
constexpr PetscReal kBiasDown = 6, kBiasSame = 6, kBiasUp = 10, kAddon = 1e-6;
/* CVODE's lower bound on the convergence rate estimate from one iteration to the next, and the
   divergence test (a correction more than twice the previous one). */
constexpr PetscReal kRateDecay = 0.3, kDivergence = 2;
/* Error-test failures in one step after which the order is lowered (CVODE's MXNEF1). */
constexpr PetscInt kErrFailsLowerOrder = 3;

/* The accepted Nordsieck array's description. Everything needed to continue from it, so that
   TSRollBack() can return to it. */
struct History {
  PetscReal t = 0, h = 0;             /* z[0] is U(t); z is scaled with h */
  PetscInt  q                  = 1;   /* degree of the polynomial: z[0..q] */
  PetscInt  q_next             = 1;   /* order for the next step (a pending order change) */
  PetscInt  qwait              = 2;   /* accepted steps before an order change is considered again */
  PetscReal tau[kMaxOrder + 2] = {0}; /* tau[1], tau[2], ...: the last accepted step sizes, newest first */
  PetscInt  ntau               = 0;
  /* Delta of the step before, kept when the next step may consider order q+1 */
  PetscBool have_prev = PETSC_FALSE;
  PetscInt  prev_q    = 0;
  PetscReal prev_h = 0, prev_econst = 0;
  /* a pending raise of the order: econst of the step whose Delta (in prev_delta) sets the new column */
  PetscReal raise_econst = 0;
};

/* Step coefficients for order q: l (the corrector polynomial Lambda), the error constants that turn
   Delta (order q), z_q (order q-1) and the difference of Deltas (order q+1) into local error
   estimates, and econst, proportional to Delta / (h^(q+1) U^(q+1)). */
struct Coefficients {
  PetscReal l[kMaxOrder + 1];
  PetscReal tq_down = 0, tq = 0, tq_up = 0, econst = 0;
};

struct AM {
  /* options */
  PetscInt  max_order        = kMaxOrder; /* CVODE's default for Adams */
  PetscInt  max_it           = 3;
  PetscInt  max_conv_fails   = 10;
  PetscReal conv_coef        = 0.1;
  PetscReal conv_fail_factor = 0.25;
  PetscBool fixed_order      = PETSC_FALSE;
  PetscBool auto_h0 = PETSC_FALSE, auto_h0_set = PETSC_FALSE, dt_option = PETSC_FALSE;

  /* two Nordsieck arrays: zb[cur] is the accepted one, the other receives the attempt */
  Vec     *zb[2] = {NULL, NULL};
  int      cur   = 0;
  Vec      delta = NULL, work = NULL, diff = NULL, y = NULL, fval = NULL, ewt = NULL, scratch = NULL, prev_delta = NULL;
  PetscInt N = 0;

  History   acc, acc_saved; /* acc_saved: the state the last step started from (TSRollBack) */
  PetscBool started = PETSC_FALSE, can_rollback = PETSC_FALSE;

  /* the attempt in progress */
  PetscReal    t0 = 0, h = 0;
  PetscInt     q = 1;
  Coefficients co;
  PetscReal    acnrm      = 0; /* WRMS norm of Delta */
  PetscBool    wlte_valid = PETSC_FALSE;
  NormType     wlte_type  = NORM_2;
  PetscReal    wlte       = -1;

  /* counters (reset at the first step of a TSSolve) */
  PetscInt n_fp_its = 0, n_fp_fail = 0, n_err_fail = 0, n_domain = 0, n_rhs = 0, n_up = 0, n_down = 0;
  PetscInt steps_at[kMaxOrder + 1] = {0};
};

enum class FixedPoint {
  converged,
  failed,
  nonfinite
};

/* ---------------------------------------------------------------------------------------------
   Coefficients. P_k(s) = prod_{j=1..k} (1 + s/xi_j) (normalised, P(0) = 1: the xi grow with k and
   the unnormalised product would only change common factors). */
void PolyProduct(const PetscReal xi[], PetscInt k, PetscReal c[])
{
  c[0] = 1;
  for (PetscInt i = 1; i <= k; i++) c[i] = 0;
  for (PetscInt j = 1; j <= k; j++)
    for (PetscInt i = j; i >= 1; i--) c[i] += c[i - 1] / xi[j];
}

/* integral over [-1, 0] of s^p sum_i c_i s^i, p = 0 or 1 */
PetscReal IntegralMinusOneZero(const PetscReal c[], PetscInt k, PetscInt p)
{
  PetscReal s = 0;
  for (PetscInt i = 0; i <= k; i++) s += c[i] * (((i + p) % 2) ? -1.0 : 1.0) / (PetscReal)(i + p + 1);
  return s;
}

/* xi_j = (t_n - t_{n-j}) / h for j = 1..jmax, t_n = the end of the step of size h that follows
   the steps tau[1..]. Missing history (never needed by the order rules) is taken as h. */
void StepRatios(PetscReal h, const History &H, PetscInt jmax, PetscReal xi[])
{
  PetscReal sum = h;
  xi[0]         = 0;
  for (PetscInt j = 1; j <= jmax; j++) {
    xi[j] = sum / h;
    sum += (j <= H.ntau) ? H.tau[j] : h;
  }
}

/* Derivation (docs/adams_moulton.md): with the exact solution, the Adams-Bashforth predictor and the
   Adams-Moulton corrector of order q have local errors
     AB: h^(q+1) U^(q+1)/q! int_{-1}^0 prod_{j=1..q}   (s + xi_j) ds
     AM: h^(q+1) U^(q+1)/q! int_{-1}^0 s prod_{j=1..q-1} (s + xi_j) ds
   so Delta = AB - AM = h^(q+1) U^(q+1)/q! xi_q int prod_{j<q}(s + xi_j), and the AM error is
   tq Delta with tq = |int s prod_{j<q}| / (xi_q int prod_{j<q}) (Milne's device). */
void ComputeCoefficients(PetscInt q, PetscReal h, const History &H, Coefficients *co)
{
  PetscReal xi[kMaxOrder + 2], c[kMaxOrder + 2];

  StepRatios(h, H, q, xi);
  /* Lambda'(s) is proportional to P_{q-1}(s); Lambda(-1) = 0, Lambda(0) = 1 */
  PolyProduct(xi, q - 1, c);
  const PetscReal A0 = IntegralMinusOneZero(c, q - 1, 0);
  co->l[0]           = 1;
  for (PetscInt i = 1; i <= q; i++) co->l[i] = c[i - 1] / (i * A0);
  co->tq         = PetscAbsReal(IntegralMinusOneZero(c, q - 1, 1)) / (xi[q] * PetscAbsReal(A0));
  PetscReal prod = 1; /* prod_{j=1..q-1} xi_j: P_{q-1} is normalised, the AB-AM difference is not */
  for (PetscInt j = 1; j <= q - 1; j++) prod *= xi[j];
  co->econst = xi[q] * A0 * prod;
  /* order q-1 from z_q = h^q U^(q)/q!: error = q z_q int_{-1}^0 s prod_{j=1..q-2} (s + xi_j) ds */
  co->tq_down = 0;
  if (q >= 2) {
    PetscReal c2[kMaxOrder + 2], prod2 = 1;
    PolyProduct(xi, q - 2, c2);
    for (PetscInt j = 1; j <= q - 2; j++) prod2 *= xi[j];
    co->tq_down = q * PetscAbsReal(IntegralMinusOneZero(c2, q - 2, 1)) * prod2;
  }
  /* order q+1 from Delta_n - (E_n/E_{n-1}) Delta_{n-1} ~ E_n h U^(q+2), E = Delta/U^(q+1):
     error = (that) |int s P_q| / ((q+1) |int P_{q-1}|) */
  if (q < kMaxOrder) {
    PetscReal c3[kMaxOrder + 2];
    StepRatios(h, H, q + 1, xi);
    PolyProduct(xi, q, c3);
    co->tq_up = PetscAbsReal(IntegralMinusOneZero(c3, q, 1)) / ((q + 1) * PetscAbsReal(A0));
  } else co->tq_up = 0;
}

PetscReal Binomial(PetscInt n, PetscInt k)
{
  PetscReal b = 1;
  for (PetscInt i = 1; i <= k; i++) b = b * (n - k + i) / i;
  return b;
}

/* ---------------------------------------------------------------------------------------------
   Norms: CVODE's weighted RMS with weights 1/(atol + rtol |U_{n-1}|), fixed for the step. */
PetscErrorCode AMWeights(TS ts, AM *am, Vec U)
{
  PetscReal atol, rtol, wmin;
  Vec       vatol, vrtol;

  PetscFunctionBeginUser;
  PetscCall(TSGetTolerances(ts, &atol, &vatol, &rtol, &vrtol));
  PetscCall(VecCopy(U, am->ewt));
  PetscCall(VecAbs(am->ewt));
  if (vrtol) PetscCall(VecPointwiseMult(am->ewt, am->ewt, vrtol));
  else PetscCall(VecScale(am->ewt, rtol));
  if (vatol) PetscCall(VecAXPY(am->ewt, 1.0, vatol));
  else PetscCall(VecShift(am->ewt, atol));
  PetscCall(VecMin(am->ewt, NULL, &wmin));
  PetscCheck(wmin > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TS am: the error weights atol + rtol |U| must be positive (at t = %g a component is 0 with atol = 0; set -ts_atol > 0)", (double)ts->ptime);
  PetscCall(VecReciprocal(am->ewt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AMNorm(AM *am, Vec v, NormType type, PetscReal *nrm)
{
  PetscFunctionBeginUser;
  PetscCall(VecPointwiseMult(am->scratch, v, am->ewt));
  if (type == NORM_INFINITY) PetscCall(VecNorm(am->scratch, NORM_INFINITY, nrm));
  else {
    PetscCall(VecNorm(am->scratch, NORM_2, nrm));
    *nrm /= PetscSqrtReal((PetscReal)am->N);
  }
  if (PetscIsInfOrNanReal(*nrm)) *nrm = PETSC_INFINITY;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AMRHS(TS ts, AM *am, PetscReal t, Vec U, Vec F)
{
  PetscFunctionBeginUser;
  PetscCall(TSComputeRHSFunction(ts, t, U, F)); /* counted in ts->rhsfuncs as well */
  am->n_rhs++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------------------------------------------------------------------------------------------
   Changes of the accepted array. */

/* Coefficients d[0..Q] of D_Q(s) = Q int_0^s u prod_{j=1..Q-2} (u + xi_j) du for the array at H.t
   (xi_j = (t - t_{-j})/h): D_Q has degree Q, leading coefficient 1, D_Q(0) = 0 and D_Q' = 0 at
   the Q-1 newest nodes t, t_{-1}, ..., t_{-(Q-2)}. Adding multiples of it to a polynomial of
   degree < Q keeps U(t) and the interpolated derivatives there. */
void NordsieckD(const History &H, PetscInt Q, PetscReal d[])
{
  PetscReal g[kMaxOrder + 2] = {0}, sum = 0;

  /* g(u) = u prod_{j=1..Q-2} (u + xi_j), coefficients g[1..Q-1] */
  g[1] = 1;
  for (PetscInt j = 1; j <= Q - 2; j++) {
    sum += (j <= H.ntau) ? H.tau[j] : H.h;
    const PetscReal xi = sum / H.h;
    for (PetscInt i = j + 1; i >= 1; i--) g[i] = g[i] * xi + g[i - 1];
  }
  for (PetscInt i = 0; i <= Q; i++) d[i] = 0;
  for (PetscInt i = 1; i <= Q - 1; i++) d[i + 1] = Q * g[i] / (i + 1);
}

/* Order q -> q-1 (CVODE): subtract z_q D_q(s), which removes the degree-q term and keeps the
   interpolation conditions of order q-1. */
PetscErrorCode AMLowerOrder(History &H, Vec *z)
{
  const PetscInt q = H.q;
  PetscReal      d[kMaxOrder + 2];

  PetscFunctionBeginUser;
  if (q < 2) PetscFunctionReturn(PETSC_SUCCESS);
  NordsieckD(H, q, d);
  for (PetscInt j = 2; j < q; j++) PetscCall(VecAXPY(z[j], -d[j], z[q]));
  H.q--;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Order q -> q+1: add c D_{q+1}(s) with c = h^(q+1) U^(q+1)/(q+1)! estimated from the last step's
   Delta = econst h^(q+1) U^(q+1)/q!, i.e. c = Delta / ((q+1) econst). The polynomial keeps all its
   interpolation conditions, so the corrector is exactly Adams-Moulton of order q+1, and the new
   top column makes the first predictor of order q+1 as well. (CVODE's Adams starts the column at
   zero; its BDF does what is done here.) */
PetscErrorCode AMRaiseOrder(History &H, Vec *z, Vec delta)
{
  const PetscInt Q = H.q + 1;
  PetscReal      d[kMaxOrder + 2];

  PetscFunctionBeginUser;
  NordsieckD(H, Q, d);
  PetscCall(VecCopy(delta, z[Q]));
  PetscCall(VecScale(z[Q], H.raise_econst != 0 ? 1 / (Q * H.raise_econst) : 0.0));
  for (PetscInt j = 2; j < Q; j++) PetscCall(VecAXPY(z[j], d[j], z[Q]));
  H.q = Q;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Apply a pending order change (chosen after the last step) to the accepted array. */
PetscErrorCode AMApplyOrderChange(AM *am)
{
  History &H = am->acc;
  Vec     *z = am->zb[am->cur];

  PetscFunctionBeginUser;
  if (H.q_next < H.q) PetscCall(AMLowerOrder(H, z));
  else if (H.q_next > H.q) PetscCall(AMRaiseOrder(H, z, am->prev_delta));
  H.q_next = H.q;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------------------------------------------------------------------------------------------
   Start: order 1 from (t0, U0) with z = [U0, h f(t0, U0)]. */

/* Hairer, Norsett & Wanner, Solving ODEs I, §II.4 ("starting step size"), for a method of order
   p = 1, in the weighted RMS norm: h0 = 0.01 |U0|/|f0| (1e-6 if either is tiny), one explicit
   Euler step to estimate |U''| by d2 = |f(t0 + h0, U0 + h0 f0) - f0| / h0, then
   h = min(100 h0, (0.01 / max(|f0|, d2))^(1/2)). One extra f evaluation. */
PetscErrorCode AMInitialStep(TS ts, AM *am, PetscReal t0, Vec U0, Vec f0, PetscReal *h)
{
  PetscReal d0, d1, d2, h0, h1;

  PetscFunctionBeginUser;
  PetscCall(AMNorm(am, U0, NORM_2, &d0));
  PetscCall(AMNorm(am, f0, NORM_2, &d1));
  h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  PetscCall(VecWAXPY(am->y, h0, f0, U0));
  PetscCall(AMRHS(ts, am, t0 + h0, am->y, am->work));
  PetscCall(VecAXPY(am->work, -1.0, f0));
  PetscCall(AMNorm(am, am->work, NORM_2, &d2));
  d2 /= h0;
  if (d2 >= PETSC_INFINITY) *h = h0; /* f not finite at the trial point: keep the cautious h0 */
  else {
    const PetscReal dm = PetscMax(d1, d2);
    h1                 = dm <= 1e-15 ? PetscMax(1e-6, 1e-3 * h0) : PetscSqrtReal(0.01 / dm);
    *h                 = PetscMin(100 * h0, h1);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode AMStart(TS ts, AM *am)
{
  Vec      *z = am->zb[am->cur];
  PetscReal h = ts->time_step, fnorm, hmin, hmax;
  PetscBool isnone, autoh;

  PetscFunctionBeginUser;
  if (ts->steps == 0) {
    am->n_fp_its = am->n_fp_fail = am->n_err_fail = am->n_domain = am->n_rhs = am->n_up = am->n_down = 0;
    for (PetscInt i = 0; i <= kMaxOrder; i++) am->steps_at[i] = 0;
  }
  PetscCall(AMWeights(ts, am, ts->vec_sol));
  PetscCall(AMRHS(ts, am, ts->ptime, ts->vec_sol, am->fval));
  PetscCall(VecNorm(am->fval, NORM_INFINITY, &fnorm));
  PetscCheck(!PetscIsInfOrNanReal(fnorm), PetscObjectComm((PetscObject)ts), PETSC_ERR_FP, "TS am: f(t0, U0) is not finite at t0 = %g", (double)ts->ptime);
  /* PETSc does not record whether a step size was set; its default (0.1 from TSCreate) unless
     -ts_dt was given counts as "not set" (see -ts_am_initial_step_auto) */
  PetscCall(PetscObjectTypeCompare((PetscObject)ts->adapt, TSADAPTNONE, &isnone));
  autoh = am->auto_h0_set ? am->auto_h0 : (PetscBool)(!isnone && !am->dt_option && h == 0.1);
  if (autoh) {
    PetscCall(AMInitialStep(ts, am, ts->ptime, ts->vec_sol, am->fval, &h));
    PetscCall(TSAdaptGetStepLimits(ts->adapt, &hmin, &hmax));
    h = PetscMin(PetscMax(h, hmin), hmax);
    if (ts->max_time > ts->ptime && ts->max_time < PETSC_MAX_REAL) h = PetscMin(h, ts->max_time - ts->ptime);
    PetscCall(PetscInfo(ts, "Automatic initial step %g\n", (double)h));
  }
  PetscCheck(h > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TS am: the time step must be positive (got %g); backward integration is not supported", (double)h);
  PetscCall(VecCopy(ts->vec_sol, z[0]));
  PetscCall(VecCopy(am->fval, z[1]));
  PetscCall(VecScale(z[1], h));
  am->acc          = History();
  am->acc.t        = ts->ptime;
  am->acc.h        = h;
  am->acc.q        = 1;
  am->acc.q_next   = 1;
  am->acc.qwait    = 2; /* q + 1 */
  am->can_rollback = PETSC_FALSE;
  ts->time_step    = h;
  am->started      = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------------------------------------------------------------------------------------------
   One attempt. */

/* zn = Pascal(zo rescaled by eta = h / H.h): the Taylor expansion of the old polynomial at t + h. */
PetscErrorCode AMPredict(AM *am, Vec *zo, Vec *zn, PetscInt q, PetscReal eta)
{
  PetscScalar a[kMaxOrder + 1];

  PetscFunctionBeginUser;
  for (PetscInt j = 0; j <= q; j++) {
    PetscCall(VecCopy(zo[j], zn[j]));
    PetscCall(VecScale(zn[j], PetscPowRealInt(eta, j)));
    for (PetscInt k = j + 1; k <= q; k++) a[k - j - 1] = Binomial(k, j) * PetscPowRealInt(eta, k);
    if (q > j) PetscCall(VecMAXPY(zn[j], q - j, a, zo + j + 1));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Functional iteration on the corrector z(0)[1] + l_1 Delta = h f(t, z(0)[0] + Delta):
   Delta <- (h f(t, U(0) + Delta) - z(0)[1]) / l_1, from Delta = 0. CVODE's test: with del the WRMS
   norm of the latest change of Delta and crate = max(0.3 crate, del/del_prev) (1 at first), stop
   when tq del min(1, crate) <= conv_coef, i.e. when the error the iteration leaves in the local
   error estimate is below conv_coef (0.1) of the tolerance. Fails after max_it iterations or when
   del more than doubles (from the third iteration on). */
PetscErrorCode AMFixedPoint(TS ts, AM *am, Vec *zn, FixedPoint *out)
{
  const PetscReal t = am->t0 + am->h, l1 = am->co.l[1];
  PetscReal       crate = 1, del = 0, delp = 0;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(zn[0], am->y));
  PetscCall(VecZeroEntries(am->delta));
  for (PetscInt m = 0;; m++) {
    PetscCall(AMRHS(ts, am, t, am->y, am->fval));
    /* work = (h f - z(0)[1]) / l1, the new Delta */
    PetscCall(VecWAXPY(am->work, -1.0 / am->h, zn[1], am->fval));
    PetscCall(VecScale(am->work, am->h / l1));
    PetscCall(VecWAXPY(am->diff, -1.0, am->delta, am->work));
    PetscCall(AMNorm(am, am->diff, NORM_2, &del));
    std::swap(am->delta, am->work);
    PetscCall(VecWAXPY(am->y, 1.0, zn[0], am->delta));
    am->n_fp_its++;
    if (del >= PETSC_INFINITY) {
      *out = FixedPoint::nonfinite;
      break;
    }
    if (m > 0) crate = PetscMax(kRateDecay * crate, del / delp);
    if (del * PetscMin(1.0, crate) * am->co.tq <= am->conv_coef) {
      if (m == 0) am->acnrm = del;
      else PetscCall(AMNorm(am, am->delta, NORM_2, &am->acnrm));
      *out = FixedPoint::converged;
      break;
    }
    if (m + 1 >= am->max_it || (m >= 1 && del > kDivergence * delp)) {
      *out = FixedPoint::failed;
      break;
    }
    delp = del;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* MATCHSTEP as TSAdaptChoose() applies it to an accepted step's successor, for step sizes changed
   here afterwards: land on max_time, avoiding a sliver of a last step. */
void AMMatchStep(TS ts, PetscReal t, PetscReal *h)
{
  const PetscReal tmax = ts->max_time, hmax = tmax - t;
  if (ts->exact_final_time != TS_EXACTFINALTIME_MATCHSTEP || t >= tmax) return;
  if (t + *h > tmax) *h = hmax;
  else if (*h * (1 + ts->adapt->matchstepfac[0]) > hmax) *h = hmax;
  else if (*h * ts->adapt->matchstepfac[1] > hmax) *h = hmax / 2;
}

/* CVODE's order selection after an accepted step (only when qwait reached 0): step ratios
   eta_k = 1/((bias_k err_k)^(1/(k+1)) + 1e-6) from the error estimates at orders q-1 (from z_q),
   q (from Delta) and q+1 (from the change of Delta since the last step); the largest wins, q on a
   tie. Returns the new order and eta_new/eta_q, by which TSAdapt's step for order q is scaled. */
PetscErrorCode AMChooseOrder(AM *am, Vec *zn, PetscInt *q_new, PetscReal *ratio)
{
  const PetscInt q = am->q;
  History       &H = am->acc;
  PetscReal      eta_q, eta_down = 0, eta_up = 0, nrm;

  PetscFunctionBeginUser;
  *q_new = q;
  *ratio = 1;
  eta_q  = 1 / (PetscPowReal(kBiasSame * am->co.tq * am->acnrm, 1.0 / (q + 1)) + kAddon);
  if (q > 1) {
    PetscCall(AMNorm(am, zn[q], NORM_2, &nrm));
    eta_down = 1 / (PetscPowReal(kBiasDown * am->co.tq_down * nrm, 1.0 / q) + kAddon);
  }
  if (q < am->max_order && H.have_prev && H.prev_q == q && H.prev_econst != 0) {
    const PetscReal cquot = (am->co.econst / H.prev_econst) * PetscPowRealInt(am->h / H.prev_h, q + 1);
    PetscCall(VecWAXPY(am->diff, -cquot, am->prev_delta, am->delta));
    PetscCall(AMNorm(am, am->diff, NORM_2, &nrm));
    eta_up = 1 / (PetscPowReal(kBiasUp * am->co.tq_up * nrm, 1.0 / (q + 2)) + kAddon);
  }
  if (eta_up > eta_q && eta_up >= eta_down) {
    *q_new = q + 1;
    *ratio = eta_up / eta_q;
  } else if (eta_down > eta_q) {
    *q_new = q - 1;
    *ratio = eta_down / eta_q;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSStep_AM(TS ts)
{
  AM       *am     = (AM *)ts->data;
  PetscInt  n_conv = 0, n_reject = 0;
  PetscBool accept = PETSC_TRUE, rejected = PETSC_FALSE, isnone;
  PetscReal next_h = ts->time_step;

  PetscFunctionBeginUser;
  if (!am->started || (ts->steprestart && !ts->steprollback)) PetscCall(AMStart(ts, am));
  Vec *zo = am->zb[am->cur], *zn = am->zb[1 - am->cur];
  PetscCall(VecCopy(ts->vec_sol, zo[0])); /* the application may have changed U between steps */
  PetscCall(AMApplyOrderChange(am));
  am->acc_saved = am->acc;
  PetscCall(AMWeights(ts, am, zo[0]));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts->adapt, TSADAPTNONE, &isnone));
  am->t0 = ts->ptime;

  while (!ts->reason) {
    FixedPoint fp;
    PetscBool  stage_ok = PETSC_TRUE;

    if (ts->exact_final_time == TS_EXACTFINALTIME_MATCHSTEP && am->t0 + ts->time_step > ts->max_time && ts->max_time > am->t0)
      ts->time_step = ts->max_time - am->t0;
    am->h = ts->time_step;
    if (!(am->h > 0) || am->t0 + am->h == am->t0) {
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT " t=%g: step size %g too small\n", ts->steps, (double)am->t0, (double)am->h));
      ts->reason = TS_DIVERGED_STEP_REJECTED;
      break;
    }
    am->q          = am->acc.q;
    am->wlte_valid = PETSC_FALSE;
    ComputeCoefficients(am->q, am->h, am->acc, &am->co);
    PetscCall(AMPredict(am, zo, zn, am->q, am->h / am->acc.h));
    PetscCall(TSPreStage(ts, am->t0 + am->h));
    PetscCall(AMFixedPoint(ts, am, zn, &fp));

    if (fp != FixedPoint::converged) {
      /* CVODE: a failed fixed point means h is too large for the iteration to contract; cut by 4 */
      am->n_fp_fail++;
      ts->num_snes_failures++; /* reported by TSGetSNESFailures(); limited by -ts_am_max_conv_fails */
      ts->time_step = am->h * am->conv_fail_factor;
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT " t=%g h=%g order %" PetscInt_FMT ": fixed point %s, retrying with h=%g\n", ts->steps, (double)am->t0,
                          (double)am->h, am->q, fp == FixedPoint::failed ? "did not converge" : "produced a non-finite value", (double)ts->time_step));
      ts->reject++;
      accept   = PETSC_FALSE;
      rejected = PETSC_TRUE;
      if (++n_conv >= am->max_conv_fails) {
        PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT ": %" PetscInt_FMT " fixed-point failures, -ts_am_max_conv_fails allows %" PetscInt_FMT "\n", ts->steps,
                            n_conv, am->max_conv_fails));
        ts->reason = TS_DIVERGED_NONLINEAR_SOLVE;
      }
      continue;
    }

    PetscCall(TSPostStage(ts, am->t0 + am->h, 0, &am->y));
    PetscCall(TSAdaptCheckStage(ts->adapt, ts, am->t0 + am->h, am->y, &stage_ok));
    if (!stage_ok) { /* TSAdaptCheckStage() has reduced ts->time_step */
      am->n_domain++;
      goto reject_step;
    }

    PetscCall(TSAdaptCandidatesClear(ts->adapt));
    PetscCall(TSAdaptCandidateAdd(ts->adapt, "am", am->q, 1, 1.0, 1.0, PETSC_TRUE));
    PetscCall(TSAdaptChoose(ts->adapt, ts, am->h, NULL, &next_h, &accept));
    if (!accept) {
      am->n_err_fail++;
      ts->time_step = next_h;
      /* CVODE: repeated error-test failures mean the higher derivatives are poorly represented:
         lower the order, or at order 1 refresh z_1 = h f(t, U) */
      if (++n_reject >= kErrFailsLowerOrder) {
        if (am->acc.q > 1 && !am->fixed_order) {
          PetscCall(AMLowerOrder(am->acc, zo));
          am->acc.q_next = am->acc.q;
          am->acc.qwait  = am->acc.q + 1;
          am->n_down++;
        } else if (am->acc.q == 1) {
          PetscCall(AMRHS(ts, am, am->acc.t, zo[0], zo[1]));
          PetscCall(VecScale(zo[1], am->acc.h));
        }
      }
      ts->reject++;
      rejected = PETSC_TRUE;
      if (!ts->reason && n_reject > ts->max_reject && ts->max_reject >= 0) {
        PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT ": %" PetscInt_FMT " rejections, more than -ts_max_reject allows\n", ts->steps, n_reject));
        ts->reason = TS_DIVERGED_STEP_REJECTED;
      }
      continue;
    }

    /* accepted: correct the whole array, z_n = z(0) + l Delta */
    for (PetscInt j = 0; j <= am->q; j++) PetscCall(VecAXPY(zn[j], am->co.l[j], am->delta));
    {
      History       &H     = am->acc;
      const PetscInt q     = am->q;
      PetscInt       q_new = q;
      PetscReal      ratio = 1;
      for (PetscInt i = PetscMin(H.ntau + 1, kMaxOrder + 1); i >= 2; i--) H.tau[i] = H.tau[i - 1];
      H.tau[1] = am->h;
      H.ntau   = PetscMin(H.ntau + 1, kMaxOrder + 1);
      H.t      = am->t0 + am->h;
      H.h      = am->h;
      H.qwait--;
      if (rejected) H.qwait = PetscMax(H.qwait, 2); /* CVODE: no change of order (or growth) right after a failure */
      else if (H.qwait <= 0) {
        if (am->fixed_order) {
          if (q < am->max_order) q_new = q + 1; /* ramp up to the fixed order, as fast as CVODE's start */
        } else {
          PetscCall(AMChooseOrder(am, zn, &q_new, &ratio));
        }
        H.qwait = q_new != q ? q_new + 1 : 2;
      }
      if (q_new > q) am->n_up++;
      if (q_new < q) am->n_down++;
      H.q_next = q_new;
      /* a raise of the order needs this step's Delta (AMRaiseOrder); so does the step after next
         if it may consider order q+1 */
      H.have_prev = PETSC_FALSE;
      if (q_new > q) {
        PetscCall(VecCopy(am->delta, am->prev_delta));
        H.raise_econst = am->co.econst;
      } else if (H.qwait == 1 && q < am->max_order && !am->fixed_order) {
        PetscCall(VecCopy(am->delta, am->prev_delta));
        H.have_prev   = PETSC_TRUE;
        H.prev_q      = q;
        H.prev_h      = am->h;
        H.prev_econst = am->co.econst;
      }
      am->steps_at[q]++;
      am->cur          = 1 - am->cur;
      am->can_rollback = PETSC_TRUE;
      PetscCall(VecCopy(zn[0], ts->vec_sol));
      ts->ptime += am->h;
      /* fixed steps (TSAdapt none): order changes do not change h */
      if (!isnone && (ratio != 1 || (rejected && next_h > am->h))) {
        PetscReal c0, c1, hmin, hmax;
        PetscCall(TSAdaptGetClip(ts->adapt, &c0, &c1));
        PetscCall(TSAdaptGetStepLimits(ts->adapt, &hmin, &hmax));
        next_h = PetscMin(PetscMax(next_h * ratio, c0 * am->h), c1 * am->h);
        if (rejected) next_h = PetscMin(next_h, am->h);
        next_h = PetscMin(PetscMax(next_h, hmin), hmax);
        AMMatchStep(ts, ts->ptime, &next_h);
      }
      ts->time_step = next_h;
    }
    break;

  reject_step:
    ts->reject++;
    accept   = PETSC_FALSE;
    rejected = PETSC_TRUE;
    if (!ts->reason && ++n_reject > ts->max_reject && ts->max_reject >= 0) {
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT ": %" PetscInt_FMT " rejections, more than -ts_max_reject allows\n", ts->steps, n_reject));
      ts->reason = TS_DIVERGED_STEP_REJECTED;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The Milne estimate tq Delta of the attempt's local error, in the weighted norm TSAdapt asks for;
   it is O(h^(q+1)), reported as order q+1 (TSAdaptBasic scales h by wlte^(-1/(q+1))). */
PetscErrorCode TSEvaluateWLTE_AM(TS ts, NormType wnormtype, PetscInt *order, PetscReal *wlte)
{
  AM       *am = (AM *)ts->data;
  PetscReal nrm;

  PetscFunctionBeginUser;
  if (order) *order = am->q + 1;
  if (!(am->wlte_valid && am->wlte_type == wnormtype)) {
    PetscCheck(am->h > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS am: no step to estimate the error of");
    if (wnormtype == NORM_2) nrm = am->acnrm;
    else PetscCall(AMNorm(am, am->delta, wnormtype, &nrm));
    am->wlte       = am->co.tq * nrm;
    am->wlte_type  = wnormtype;
    am->wlte_valid = PETSC_TRUE;
  }
  *wlte = am->wlte;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Dense output from the accepted Nordsieck array: U(t) = sum_j z_j s^j, s = (t - t_n)/h, by Horner.
   Exact for the polynomial of the last step, so its error is O(h^(q+1)) inside [t_{n-1}, t_n]. */
PetscErrorCode TSInterpolate_AM(TS ts, PetscReal t, Vec X)
{
  AM            *am = (AM *)ts->data;
  const History &H  = am->acc;
  Vec           *z  = am->zb[am->cur];

  PetscFunctionBeginUser;
  PetscCheck(am->started, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS am: no step to interpolate in");
  const PetscReal s = (t - H.t) / H.h;
  PetscCall(VecCopy(z[H.q], X));
  for (PetscInt j = H.q - 1; j >= 0; j--) PetscCall(VecAYPX(X, s, z[j]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRollBack_AM(TS ts)
{
  AM *am = (AM *)ts->data;

  PetscFunctionBeginUser;
  PetscCheck(am->can_rollback, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS am: no step to roll back");
  /* the array the step started from is intact in the other buffer */
  am->cur           = 1 - am->cur;
  am->acc           = am->acc_saved;
  am->acc.have_prev = PETSC_FALSE; /* prev_delta may belong to the undone step */
  am->can_rollback  = PETSC_FALSE;
  PetscCall(VecCopy(am->zb[am->cur][0], ts->vec_sol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSReset_AM(TS ts)
{
  AM *am = (AM *)ts->data;

  PetscFunctionBeginUser;
  for (int b = 0; b < 2; b++)
    if (am->zb[b]) PetscCall(VecDestroyVecs(kMaxOrder + 1, &am->zb[b]));
  for (Vec *v : {&am->delta, &am->work, &am->diff, &am->y, &am->fval, &am->ewt, &am->scratch, &am->prev_delta}) PetscCall(VecDestroy(v));
  am->started      = PETSC_FALSE;
  am->can_rollback = PETSC_FALSE;
  am->wlte_valid   = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetCounters_AM(TS ts, PetscInt *its, PetscInt *fails, PetscInt *order)
{
  AM *am = (AM *)ts->data;

  PetscFunctionBeginUser;
  if (its) *its = am->n_fp_its;
  if (fails) *fails = am->n_fp_fail;
  if (order) *order = am->started ? am->acc.q_next : 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The setters check what TSSetFromOptions_AM() checks for the options of the same values. */
PetscErrorCode TSAMSetMaxOrder_AM(TS ts, PetscInt max_order)
{
  PetscFunctionBeginUser;
  PetscCheck(max_order >= 1 && max_order <= kMaxOrder, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TSAMSetMaxOrder(): max_order = %" PetscInt_FMT " must be in 1..%" PetscInt_FMT, max_order, kMaxOrder);
  ((AM *)ts->data)->max_order = max_order;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxOrder_AM(TS ts, PetscInt *max_order)
{
  PetscFunctionBeginUser;
  *max_order = ((AM *)ts->data)->max_order;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetFixedOrder_AM(TS ts, PetscBool fixed)
{
  PetscFunctionBeginUser;
  ((AM *)ts->data)->fixed_order = fixed;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetFixedOrder_AM(TS ts, PetscBool *fixed)
{
  PetscFunctionBeginUser;
  *fixed = ((AM *)ts->data)->fixed_order;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetMaxIterations_AM(TS ts, PetscInt max_it)
{
  PetscFunctionBeginUser;
  PetscCheck(max_it >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSAMSetMaxIterations(): max_it = %" PetscInt_FMT " must be >= 1",
             max_it);
  ((AM *)ts->data)->max_it = max_it;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxIterations_AM(TS ts, PetscInt *max_it)
{
  PetscFunctionBeginUser;
  *max_it = ((AM *)ts->data)->max_it;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetMaxConvergenceFailures_AM(TS ts, PetscInt max_fails)
{
  PetscFunctionBeginUser;
  PetscCheck(max_fails >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TSAMSetMaxConvergenceFailures(): max_fails = %" PetscInt_FMT " must be >= 1", max_fails);
  ((AM *)ts->data)->max_conv_fails = max_fails;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxConvergenceFailures_AM(TS ts, PetscInt *max_fails)
{
  PetscFunctionBeginUser;
  *max_fails = ((AM *)ts->data)->max_conv_fails;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every function TSCreate_AM() composes (listed in adams_moulton.h), removed again on destroy so
   that a TS changed to another type no longer answers to them */
const char *const kComposedNames[] = {"TSAMGetCounters_C",
                                      "TSAMSetMaxOrder_C",
                                      "TSAMGetMaxOrder_C",
                                      "TSAMSetFixedOrder_C",
                                      "TSAMGetFixedOrder_C",
                                      "TSAMSetMaxIterations_C",
                                      "TSAMGetMaxIterations_C",
                                      "TSAMSetMaxConvergenceFailures_C",
                                      "TSAMGetMaxConvergenceFailures_C"};

PetscErrorCode TSDestroy_AM(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSReset_AM(ts));
  delete (AM *)ts->data;
  ts->data = NULL;
  for (const char *name : kComposedNames) PetscCall(PetscObjectComposeFunction((PetscObject)ts, name, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetUp_AM(TS ts)
{
  AM           *am = (AM *)ts->data;
  TSRHSFunction rhs;
  TSIFunction   ifunction;

  PetscFunctionBeginUser;
  PetscCall(TSGetIFunction(ts, NULL, &ifunction, NULL));
  PetscCheck(!ifunction, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
             "TS am integrates U' = f(t, U) given with TSSetRHSFunction(); an IFunction F(t, U, U') = 0 (TSSetIFunction()) is not supported: functional "
             "iteration evaluates f and has no Jacobian or mass matrix to solve F with");
  PetscCall(TSGetRHSFunction(ts, NULL, &rhs, NULL));
  PetscCheck(rhs, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS am needs the right-hand side: call TSSetRHSFunction()");
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptCandidatesClear(ts->adapt));
  PetscCall(TSReset_AM(ts));
  for (int b = 0; b < 2; b++) PetscCall(VecDuplicateVecs(ts->vec_sol, kMaxOrder + 1, &am->zb[b]));
  for (Vec *v : {&am->delta, &am->work, &am->diff, &am->y, &am->fval, &am->ewt, &am->scratch, &am->prev_delta}) PetscCall(VecDuplicate(ts->vec_sol, v));
  PetscCall(VecGetSize(ts->vec_sol, &am->N));
  am->cur = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetFromOptions_AM(TS ts, PetscOptionItems *PetscOptionsObject)
{
  AM       *am = (AM *)ts->data;
  PetscBool flg;

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Adams-Moulton with functional iteration (am) options");
  PetscCall(PetscOptionsInt("-ts_am_max_order", "Highest order used (1..12)", "TSAM", am->max_order, &am->max_order, NULL));
  PetscCall(PetscOptionsBool("-ts_am_fixed_order", "Raise the order to -ts_am_max_order as the start-up allows, then keep it (no order selection)", "TSAM",
                             am->fixed_order, &am->fixed_order, NULL));
  PetscCall(PetscOptionsInt("-ts_am_max_iterations", "Fixed-point iterations (f evaluations) per step attempt (CVODE's maxcor)", "TSAM", am->max_it,
                            &am->max_it, NULL));
  PetscCall(PetscOptionsReal("-ts_am_convergence_coefficient",
                             "The fixed point has converged when the error it leaves in the local error estimate is below this fraction of the tolerance "
                             "(CVODE's nlscoef)",
                             "TSAM", am->conv_coef, &am->conv_coef, NULL));
  PetscCall(PetscOptionsReal("-ts_am_conv_fail_factor", "Step size factor after a fixed-point failure (CVODE's eta_cf)", "TSAM", am->conv_fail_factor,
                             &am->conv_fail_factor, NULL));
  PetscCall(PetscOptionsInt("-ts_am_max_conv_fails", "Fixed-point failures in one step before the solve stops with DIVERGED_NONLINEAR_SOLVE (CVODE's maxncf)",
                            "TSAM", am->max_conv_fails, &am->max_conv_fails, NULL));
  PetscCall(
    PetscOptionsBool("-ts_am_initial_step_auto",
                     "Choose the first step automatically (Hairer's estimate); default: when the time step is PETSc's default 0.1 and -ts_dt is not given",
                     "TSAM", am->auto_h0, &am->auto_h0, &flg));
  if (flg) am->auto_h0_set = PETSC_TRUE;
  PetscOptionsHeadEnd();
  PetscCall(PetscOptionsHasName(((PetscObject)ts)->options, ((PetscObject)ts)->prefix, "-ts_dt", &am->dt_option));
  PetscCheck(am->max_order >= 1 && am->max_order <= kMaxOrder, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_am_max_order = %" PetscInt_FMT ": must be in 1..%" PetscInt_FMT, am->max_order, kMaxOrder);
  PetscCheck(am->max_it >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_am_max_iterations = %" PetscInt_FMT ": must be >= 1",
             am->max_it);
  PetscCheck(am->conv_coef > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_am_convergence_coefficient = %g: must be > 0",
             (double)am->conv_coef);
  PetscCheck(am->conv_fail_factor > 0 && am->conv_fail_factor < 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_am_conv_fail_factor = %g: must be in (0, 1)", (double)am->conv_fail_factor);
  PetscCheck(am->max_conv_fails >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_am_max_conv_fails = %" PetscInt_FMT ": must be >= 1", am->max_conv_fails);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSView_AM(TS ts, PetscViewer viewer)
{
  AM       *am = (AM *)ts->data;
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Adams-Moulton predictor-corrector (Nordsieck array, variable coefficients), orders 1..%" PetscInt_FMT "%s\n",
                                   am->max_order, am->fixed_order ? " (order fixed at the maximum after start-up)" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "  functional iteration: at most %" PetscInt_FMT
                                   " iterations, convergence coefficient %g; a failure cuts h by %g, %" PetscInt_FMT " in one step stop the solve\n",
                                   am->max_it, (double)am->conv_coef, (double)am->conv_fail_factor, am->max_conv_fails));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "  f evaluations %" PetscInt_FMT ", fixed-point iterations %" PetscInt_FMT ", order raised %" PetscInt_FMT
                                   " times, lowered %" PetscInt_FMT " times, next order %" PetscInt_FMT "\n",
                                   am->n_rhs, am->n_fp_its, am->n_up, am->n_down, am->started ? am->acc.q_next : 1));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "  rejected attempts: fixed point not converging %" PetscInt_FMT ", domain errors %" PetscInt_FMT
                                   ", error test %" PetscInt_FMT "\n",
                                   am->n_fp_fail, am->n_domain, am->n_err_fail));
  PetscCall(PetscViewerASCIIPrintf(viewer, "  accepted steps per order:"));
  for (PetscInt k = 1; k <= am->max_order; k++) PetscCall(PetscViewerASCIIPrintf(viewer, " %" PetscInt_FMT ":%" PetscInt_FMT, k, am->steps_at[k]));
  PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* registered by TurgorTSRegisterAll() (ts_register.cpp) */
PetscErrorCode TSCreate_AM(TS ts)
{
  AM *am = new AM();

  PetscFunctionBeginUser;
  ts->data                = am;
  ts->ops->setup          = TSSetUp_AM;
  ts->ops->step           = TSStep_AM;
  ts->ops->interpolate    = TSInterpolate_AM;
  ts->ops->evaluatewlte   = TSEvaluateWLTE_AM;
  ts->ops->rollback       = TSRollBack_AM;
  ts->ops->setfromoptions = TSSetFromOptions_AM;
  ts->ops->view           = TSView_AM;
  ts->ops->reset          = TSReset_AM;
  ts->ops->destroy        = TSDestroy_AM;
  ts->usessnes            = PETSC_FALSE; /* functional iteration: no nonlinear solver */
  ts->default_adapt_type  = TSADAPTBASIC;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMGetCounters_C", TSAMGetCounters_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMSetMaxOrder_C", TSAMSetMaxOrder_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMGetMaxOrder_C", TSAMGetMaxOrder_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMSetFixedOrder_C", TSAMSetFixedOrder_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMGetFixedOrder_C", TSAMGetFixedOrder_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMSetMaxIterations_C", TSAMSetMaxIterations_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMGetMaxIterations_C", TSAMGetMaxIterations_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMSetMaxConvergenceFailures_C", TSAMSetMaxConvergenceFailures_AM));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSAMGetMaxConvergenceFailures_C", TSAMGetMaxConvergenceFailures_AM));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetCounters(TS ts, PetscInt *fixed_point_its, PetscInt *fixed_point_failures, PetscInt *current_order)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSAMGetCounters_C", (TS, PetscInt *, PetscInt *, PetscInt *), (ts, fixed_point_its, fixed_point_failures, current_order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PetscTryMethod: a no-op on a TS of another type, so callers may set it before knowing the type */
PetscErrorCode TSAMSetMaxOrder(TS ts, PetscInt max_order)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveInt(ts, max_order, 2);
  PetscTryMethod(ts, "TSAMSetMaxOrder_C", (TS, PetscInt), (ts, max_order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxOrder(TS ts, PetscInt *max_order)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidIntPointer(max_order, 2);
  PetscUseMethod(ts, "TSAMGetMaxOrder_C", (TS, PetscInt *), (ts, max_order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetFixedOrder(TS ts, PetscBool fixed)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveBool(ts, fixed, 2);
  PetscTryMethod(ts, "TSAMSetFixedOrder_C", (TS, PetscBool), (ts, fixed));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetFixedOrder(TS ts, PetscBool *fixed)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidBoolPointer(fixed, 2);
  PetscUseMethod(ts, "TSAMGetFixedOrder_C", (TS, PetscBool *), (ts, fixed));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetMaxIterations(TS ts, PetscInt max_it)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveInt(ts, max_it, 2);
  PetscTryMethod(ts, "TSAMSetMaxIterations_C", (TS, PetscInt), (ts, max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxIterations(TS ts, PetscInt *max_it)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidIntPointer(max_it, 2);
  PetscUseMethod(ts, "TSAMGetMaxIterations_C", (TS, PetscInt *), (ts, max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMSetMaxConvergenceFailures(TS ts, PetscInt max_fails)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveInt(ts, max_fails, 2);
  PetscTryMethod(ts, "TSAMSetMaxConvergenceFailures_C", (TS, PetscInt), (ts, max_fails));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAMGetMaxConvergenceFailures(TS ts, PetscInt *max_fails)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidIntPointer(max_fails, 2);
  PetscUseMethod(ts, "TSAMGetMaxConvergenceFailures_C", (TS, PetscInt *), (ts, max_fails));
  PetscFunctionReturn(PETSC_SUCCESS);
}
