/* Radau IIA, 3 stages, order 5, as the PETSc TS type "radauiia" (docs/radau_iia.md).

   Problem: F(t, U, U') = 0 from TSSetIFunction/TSSetIJacobian (or U' = G(t, U) from the RHS
   interface), assumed linearly implicit, F = M U' - f(t, U), with a constant nonsingular M.
   The stage residuals use F itself (collocation: U' at a stage is the derivative of the
   collocation polynomial), so only the Newton matrices and the error filter depend on M, which
   is recovered once from two IJacobian calls with different shifts.

   Step: stage increments Z_i = Y_i - U_n solve F(t_n + c_i h, U_n + Z_i, (1/h) sum_j Ainv_ij Z_j) = 0
   by simplified Newton with one Jacobian J at (t_n, U_n), decoupled by the eigen-decomposition
   Tinv Ainv T = Lambda into a real N x N system (gamma/h M - J) and a complex one, solved as the
   real 2N x 2N system [[alpha/h M - J, beta/h M], [-beta/h M, alpha/h M - J]] (interleaved rows).
   Error estimate, Jacobian reuse and Newton control follow Hairer & Wanner's RADAU5; the step
   size is chosen by TSAdapt through ops->evaluatewlte. */
#include <turgor/ts/radau_iia.h>
#include "ts_types_internal.h"
#include <petsc/private/tsimpl.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace {

using Mat3 = PetscReal[3][3];

void Invert3(const Mat3 a, Mat3 inv)
{
  const PetscReal c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1], c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2], c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const PetscReal det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  inv[0][0]           = c00 / det;
  inv[1][0]           = c01 / det;
  inv[2][0]           = c02 / det;
  inv[0][1]           = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
  inv[1][1]           = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  inv[2][1]           = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
  inv[0][2]           = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
  inv[1][2]           = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
  inv[2][2]           = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
}

/* The method's constants, derived numerically from A so that no transcribed digits are trusted:
   the unit test checks them against independent derivations. */
void ComputeTableau(TSRadauIIATableau *t)
{
  const PetscReal s6      = std::sqrt(6.0);
  const PetscReal A[3][3] = {
    {(88 - 7 * s6) / 360,     (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225},
    {(296 + 169 * s6) / 1800, (88 + 7 * s6) / 360,     (-2 - 3 * s6) / 225},
    {(16 - s6) / 36,          (16 + s6) / 36,          1.0 / 9            }
  };
  t->c[0] = (4 - s6) / 10;
  t->c[1] = (4 + s6) / 10;
  t->c[2] = 1;
  for (int i = 0; i < 3; i++) {
    t->b[i] = A[2][i]; /* stiffly accurate */
    for (int j = 0; j < 3; j++) t->A[i][j] = A[i][j];
  }
  Invert3(t->A, t->Ainv);
  const Mat3 &B = t->Ainv;

  /* eigenvalues of Ainv: the characteristic polynomial z^3 - tr z^2 + m2 z - det has one real
     root (Newton converges: the polynomial is monotone here) and a complex pair */
  const PetscReal tr  = B[0][0] + B[1][1] + B[2][2];
  const PetscReal m2  = B[0][0] * B[1][1] - B[0][1] * B[1][0] + B[0][0] * B[2][2] - B[0][2] * B[2][0] + B[1][1] * B[2][2] - B[1][2] * B[2][1];
  const PetscReal det = B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) - B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
                        B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0]);
  PetscReal z = tr / 3;
  for (int it = 0; it < 100; it++) {
    const PetscReal p = ((z - tr) * z + m2) * z - det, dp = (3 * z - 2 * tr) * z + m2, dz = p / dp;
    z -= dz;
    if (std::fabs(dz) <= 1e-16 * std::fabs(z)) break;
  }
  t->gamma  = z;
  t->alpha  = (tr - z) / 2;
  t->beta   = std::sqrt(det / z - t->alpha * t->alpha);
  t->gamma0 = 1 / z;

  /* eigenvectors as the cross product of two rows of (Ainv - lambda I), scaled to a last entry 1 */
  using C          = std::complex<PetscReal>;
  auto null_vector = [&](C lambda, C v[3]) {
    C r0[3], r1[3];
    for (int j = 0; j < 3; j++) {
      r0[j] = B[0][j] - (j == 0 ? lambda : C(0));
      r1[j] = B[1][j] - (j == 1 ? lambda : C(0));
    }
    v[0]      = r0[1] * r1[2] - r0[2] * r1[1];
    v[1]      = r0[2] * r1[0] - r0[0] * r1[2];
    v[2]      = r0[0] * r1[1] - r0[1] * r1[0];
    const C s = v[2];
    for (int j = 0; j < 3; j++) v[j] /= s;
  };
  C vr[3], vc[3];
  null_vector(C(t->gamma, 0), vr);
  null_vector(C(t->alpha, t->beta), vc);
  for (int i = 0; i < 3; i++) {
    t->T[i][0] = vr[i].real();
    t->T[i][1] = vc[i].real();
    t->T[i][2] = vc[i].imag();
  }
  Invert3(t->T, t->Tinv);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      PetscReal s = 0;
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) s += t->Tinv[i][k] * B[k][l] * t->T[l][j];
      t->Lambda[i][j] = s;
    }

  /* embedded quadrature with nodes (0, c1, c2, c3) and weight gamma0 at 0, exact for degree <= 2;
     e = (bhat - b)^T Ainv turns its difference to b into a combination of the Z_i */
  Mat3 V, Vinv;
  for (int k = 0; k < 3; k++)
    for (int i = 0; i < 3; i++) V[k][i] = std::pow(t->c[i], k);
  Invert3(V, Vinv);
  const PetscReal rhs[3] = {1 - t->gamma0, 0.5, 1.0 / 3};
  PetscReal       bhat[3];
  for (int i = 0; i < 3; i++) bhat[i] = Vinv[i][0] * rhs[0] + Vinv[i][1] * rhs[1] + Vinv[i][2] * rhs[2];
  for (int j = 0; j < 3; j++) {
    t->e[j] = 0;
    for (int i = 0; i < 3; i++) t->e[j] += (bhat[i] - t->b[i]) * B[i][j];
  }
}

struct RadauIIA {
  TSRadauIIATableau tab;

  /* options */
  PetscInt  max_it       = 7;             /* Newton iterations per attempt */
  PetscInt  min_it       = 2;             /* Newton iterations before convergence is accepted (RADAU5: 1, SciPy: 2) */
  PetscBool predictive   = PETSC_TRUE;    /* with TSAdaptBasic: RADAU5's predictive controller and Newton-dependent safety */
  PetscReal newton_tol   = PETSC_DEFAULT; /* kappa set by option or setter, or PETSC_DEFAULT: RADAU5's rule (RadauIIANewtonTolerance) */
  PetscReal reuse_theta  = 1e-3;          /* keep J for the next step while the contraction rate stays below */
  PetscReal keep_step[2] = {1.0, 1.2};
  PetscBool extrapolate  = PETSC_TRUE;

  /* linear algebra: P = shiftP M - J from the last Jacobian evaluation, the mass matrix M, the
     real (Ar) and complex (Ac) Newton matrices for the step size h_fact */
  KSP              kspr = NULL, kspc = NULL;
  Mat              P = NULL, M = NULL, Ar = NULL, Ac = NULL;
  PetscReal        shiftP = 0, h_fact = 0;
  PetscObjectState P_nzstate     = 0;
  PetscBool        pattern_dirty = PETSC_TRUE;

  /* vectors */
  Vec U0 = NULL, U1 = NULL, Udot = NULL, Udot0 = NULL, Udot1 = NULL, scal = NULL, work = NULL, rhs = NULL, err = NULL, Xc = NULL, Yc = NULL;
  Vec Z[3] = {NULL, NULL, NULL}, Y[3] = {NULL, NULL, NULL}, R[3] = {NULL, NULL, NULL}, dW[3] = {NULL, NULL, NULL}, D[3] = {NULL, NULL, NULL};

  /* state of the integration */
  PetscReal t0 = 0, h = 0; /* the attempt in progress */
  PetscReal eval_t    = 0; /* the residual evaluation in progress (its SNES view: SNESFormFunction_RadauIIA) */
  Vec       eval_Udot = NULL;
  PetscReal cont_t0 = 0, cont_h = 0; /* the last accepted step, whose polynomial D describes */
  PetscBool have_cont = PETSC_FALSE, started = PETSC_FALSE;
  PetscBool need_jac = PETSC_TRUE, jac_fresh = PETSC_FALSE, jac_fresh_prev = PETSC_FALSE;
  PetscBool first = PETSC_TRUE, last_rejected = PETSC_FALSE;
  PetscReal faccon = 1, theta = 0;
  PetscReal kappa = 0.03;         /* the Newton tolerance of the current step, in units of the error weights */
  PetscInt  newt  = 0;            /* Newton iterations of the attempt that converged last */
  PetscReal hacc = 0, erracc = 0; /* RADAU5's HACC, ERRACC: h and error norm of the last accepted step */
  PetscBool have_acc        = PETSC_FALSE;
  PetscReal rho             = 0;           /* round-off level of U0 in the error norm (RadauIIAWeights) */
  PetscInt  n_floor         = 0;           /* consecutive Newton failures of this step with increments at the round-off level */
  PetscBool newton_roundoff = PETSC_FALSE; /* the last Newton increment was at the round-off level */
  char      floor_msg[1024];
  PetscBool wlte_valid = PETSC_FALSE;
  NormType  wlte_type  = NORM_2;
  PetscReal wlte       = -1;

  /* counters */
  PetscInt n_jac = 0, n_newton = 0, n_solve = 0, n_decomp = 0, n_ifunc = 0, n_newton_fail = 0, n_domain = 0;
};

enum class NewtonOutcome {
  converged,
  diverged,
  slow,
  too_many,
  domain,
  linear_solve
};

const char *const NewtonOutcomeNames[] =
  {"converged", "diverged (rate >= 0.99)", "predicted not to converge", "too many iterations", "domain error or non-finite residual", "linear solve failed"};

PetscErrorCode RadauIIAEnsureKSPs(TS ts, RadauIIA *r)
{
  const char *prefix;
  PetscMPIInt size;

  PetscFunctionBeginUser;
  if (r->kspr) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)ts), &size));
  for (KSP *k : {&r->kspr, &r->kspc}) {
    PC pc;
    PetscCall(KSPCreate(PetscObjectComm((PetscObject)ts), k));
    PetscCall(PetscObjectIncrementTabLevel((PetscObject)*k, (PetscObject)ts, 1));
    PetscCall(KSPSetOptionsPrefix(*k, prefix));
    PetscCall(KSPAppendOptionsPrefix(*k, "ts_radauiia_"));
    PetscCall(KSPSetType(*k, KSPPREONLY));
    PetscCall(KSPGetPC(*k, &pc));
    /* on more than one rank, every rank factors the whole matrix (PCREDUNDANT, PETSc's LU): the
       result is then the same run to run, which MUMPS's dynamic scheduling does not give */
    PetscCall(PCSetType(pc, size > 1 ? PCREDUNDANT : PCLU));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The residual of RadauIIAResidual's evaluation in progress as the TS's SNES sees it
   (ts->ops->snesfunction, which SNESTSFormFunction calls): F at that evaluation's t and U'. */
PetscErrorCode SNESFormFunction_RadauIIA(SNES snes, Vec U, Vec F, TS ts)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCall(TSComputeIFunction(ts, r->eval_t, U, r->eval_Udot, F, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* F(t, U, Udot) into Fv; *bad when the application flagged a domain error or F is not finite. An
   application flags one with SNESSetFunctionDomainError() on the TS's SNES (TSGetSNES); where it
   has that SNES, F is evaluated through it (SNESComputeFunction), which clears the flag before the
   evaluation, so the flag read after it is this evaluation's. */
PetscErrorCode RadauIIAResidual(TS ts, RadauIIA *r, PetscReal t, Vec U, Vec Udot, Vec Fv, PetscBool *bad)
{
  PetscBool domain = PETSC_FALSE;
  PetscReal nrm;
  SNES      snes;

  PetscFunctionBeginUser;
  PetscCall(TSGetSNES(ts, &snes));
  r->eval_t    = t;
  r->eval_Udot = Udot;
  PetscCall(SNESComputeFunction(snes, U, Fv));
  r->eval_Udot = NULL;
  r->n_ifunc++;
  PetscCall(SNESGetFunctionDomainError(snes, &domain));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &domain, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)ts)));
  PetscCall(VecNorm(Fv, NORM_INFINITY, &nrm));
  *bad = (PetscBool)(domain || PetscIsInfOrNanReal(nrm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RadauIIASolve(RadauIIA *r, KSP ksp, Vec b, Vec x, PetscBool *ok, TS ts)
{
  KSPConvergedReason reason;
  PetscInt           its;

  PetscFunctionBeginUser;
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  r->n_solve++;
  ts->ksp_its += its;
  *ok = (PetscBool)(reason >= 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Copy the application's Jacobian into r->P, re-creating it when its nonzero pattern changed. */
PetscErrorCode RadauIIACopyJacobian(RadauIIA *r, Mat B)
{
  PetscObjectState nz;

  PetscFunctionBeginUser;
  PetscCall(MatGetNonzeroState(B, &nz));
  if (!r->P || nz != r->P_nzstate) {
    PetscCall(MatDestroy(&r->P));
    PetscCall(MatDuplicate(B, MAT_COPY_VALUES, &r->P));
    r->P_nzstate     = nz;
    r->pattern_dirty = PETSC_TRUE;
  } else PetscCall(MatCopy(B, r->P, SAME_NONZERO_PATTERN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* J at (t0, U0). With an IFunction, P = (gamma/h) M - J comes from one IJacobian call; the very
   first evaluation makes a second call at the same state with shift alpha/h to recover the
   constant M. Without one (U' = G), M = I and P = -dG/dU. */
PetscErrorCode RadauIIAEvaluateJacobian(TS ts, RadauIIA *r)
{
  TSIFunction ifunction;
  Mat         A, B;

  PetscFunctionBeginUser;
  PetscCall(TSGetIFunction(ts, NULL, &ifunction, NULL));
  if (ifunction) {
    const PetscReal s1 = r->tab.gamma / r->h, s2 = r->tab.alpha / r->h;
    PetscCall(TSGetIJacobian(ts, &A, &B, NULL, NULL));
    if (!B) B = A;
    PetscCheck(B, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE,
               "TS radauiia needs a Jacobian: call TSSetIJacobian() (or TSSetRHSJacobian() for U' = G(t, U))");
    PetscCall(TSComputeIJacobian(ts, r->t0, r->U0, r->Udot0, s1, A, B, PETSC_FALSE));
    r->n_jac++;
    PetscCall(RadauIIACopyJacobian(r, B));
    r->shiftP = s1;
    if (!r->M) {
      PetscCall(TSComputeIJacobian(ts, r->t0, r->U0, r->Udot0, s2, A, B, PETSC_FALSE));
      r->n_jac++;
      PetscCall(MatDuplicate(r->P, MAT_COPY_VALUES, &r->M));
      PetscCall(MatAXPY(r->M, -1.0, B, UNKNOWN_NONZERO_PATTERN));
      PetscCall(MatScale(r->M, 1 / (s1 - s2)));
      r->pattern_dirty = PETSC_TRUE;
    }
  } else {
    PetscCall(TSGetRHSJacobian(ts, &A, &B, NULL, NULL));
    if (!B) B = A;
    PetscCheck(B, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS radauiia needs a Jacobian: call TSSetRHSJacobian() (or TSSetIJacobian())");
    PetscCall(TSComputeRHSJacobian(ts, r->t0, r->U0, A, B));
    r->n_jac++;
    PetscCall(RadauIIACopyJacobian(r, B));
    PetscCall(MatScale(r->P, -1.0));
    r->shiftP = 0;
    if (!r->M) {
      PetscInt n, N, rs, re;
      PetscCall(MatGetLocalSize(r->P, &n, NULL));
      PetscCall(MatGetSize(r->P, &N, NULL));
      PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)ts), n, n, N, N, 1, NULL, 0, NULL, &r->M));
      PetscCall(MatGetOwnershipRange(r->M, &rs, &re));
      for (PetscInt i = rs; i < re; i++) PetscCall(MatSetValue(r->M, i, i, 1.0, INSERT_VALUES));
      PetscCall(MatAssemblyBegin(r->M, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(r->M, MAT_FINAL_ASSEMBLY));
      r->pattern_dirty = PETSC_TRUE;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (Re)create Ar (N x N) and Ac (2N x 2N, rows 2i and 2i+1 for the real and imaginary parts of
   unknown i) preallocated for the union of the patterns of P and M. */
PetscErrorCode RadauIIACreateMatrices(TS ts, RadauIIA *r)
{
  PetscInt              n, rs, re, cs, ce;
  std::vector<PetscInt> dr, orr, dc, oc, cols;

  PetscFunctionBeginUser;
  PetscCall(MatGetLocalSize(r->P, &n, NULL));
  PetscCall(MatGetOwnershipRange(r->P, &rs, &re));
  PetscCall(MatGetOwnershipRangeColumn(r->P, &cs, &ce));
  dr.assign(n, 0);
  orr.assign(n, 0);
  dc.assign(2 * n, 0);
  oc.assign(2 * n, 0);
  for (PetscInt i = rs; i < re; i++) {
    const PetscInt *c;
    PetscInt        nc;
    cols.clear();
    for (Mat X : {r->P, r->M}) {
      PetscCall(MatGetRow(X, i, &nc, &c, NULL));
      cols.insert(cols.end(), c, c + nc);
      PetscCall(MatRestoreRow(X, i, &nc, &c, NULL));
    }
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    for (PetscInt j : cols) {
      if (j >= cs && j < ce) dr[i - rs]++;
      else orr[i - rs]++;
    }
    dc[2 * (i - rs)] = dc[2 * (i - rs) + 1] = 2 * dr[i - rs];
    oc[2 * (i - rs)] = oc[2 * (i - rs) + 1] = 2 * orr[i - rs];
  }
  PetscCall(MatDestroy(&r->Ar));
  PetscCall(MatDestroy(&r->Ac));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)ts), &r->Ar));
  PetscCall(MatSetSizes(r->Ar, n, n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(r->Ar, MATAIJ));
  PetscCall(MatXAIJSetPreallocation(r->Ar, 1, dr.data(), orr.data(), NULL, NULL));
  PetscCall(MatCreate(PetscObjectComm((PetscObject)ts), &r->Ac));
  PetscCall(MatSetSizes(r->Ac, 2 * n, 2 * n, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(r->Ac, MATAIJ));
  PetscCall(MatXAIJSetPreallocation(r->Ac, 1, dc.data(), oc.data(), NULL, NULL));
  PetscCall(KSPSetOperators(r->kspr, r->Ar, r->Ar));
  PetscCall(KSPSetOperators(r->kspc, r->Ac, r->Ac));
  r->pattern_dirty = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Ar = (gamma/h) M - J and Ac for step size h; the KSPs factor them at their next solve. */
PetscErrorCode RadauIIAAssembleMatrices(TS ts, RadauIIA *r)
{
  const PetscReal        h  = r->h;
  const PetscReal        ar = r->tab.gamma / h - r->shiftP, a11 = r->tab.Lambda[1][1] / h - r->shiftP, a22 = r->tab.Lambda[2][2] / h - r->shiftP;
  const PetscReal        l12 = r->tab.Lambda[1][2] / h, l21 = r->tab.Lambda[2][1] / h;
  PetscInt               rs, re;
  std::vector<PetscInt>  c2;
  std::vector<PetscReal> v1, v2;

  PetscFunctionBeginUser;
  if (r->pattern_dirty || !r->Ar) PetscCall(RadauIIACreateMatrices(ts, r));
  PetscCall(MatZeroEntries(r->Ar));
  PetscCall(MatZeroEntries(r->Ac));
  PetscCall(MatGetOwnershipRange(r->P, &rs, &re));
  for (PetscInt i = rs; i < re; i++) {
    const PetscInt    *c;
    const PetscScalar *v;
    PetscInt           nc;
    const PetscInt     row0 = 2 * i, row1 = 2 * i + 1;

    /* -J = P - shiftP M: the P part goes on the diagonal blocks */
    PetscCall(MatGetRow(r->P, i, &nc, &c, &v));
    PetscCall(MatSetValues(r->Ar, 1, &i, nc, c, v, ADD_VALUES));
    c2.resize(nc);
    for (PetscInt k = 0; k < nc; k++) c2[k] = 2 * c[k];
    PetscCall(MatSetValues(r->Ac, 1, &row0, nc, c2.data(), v, ADD_VALUES));
    for (PetscInt k = 0; k < nc; k++) c2[k] = 2 * c[k] + 1;
    PetscCall(MatSetValues(r->Ac, 1, &row1, nc, c2.data(), v, ADD_VALUES));
    PetscCall(MatRestoreRow(r->P, i, &nc, &c, &v));

    /* the M part, scaled by the entries of Lambda / h */
    PetscCall(MatGetRow(r->M, i, &nc, &c, &v));
    c2.resize(nc);
    v1.resize(nc);
    v2.resize(nc);
    for (PetscInt k = 0; k < nc; k++) v1[k] = ar * PetscRealPart(v[k]);
    PetscCall(MatSetValues(r->Ar, 1, &i, nc, c, v1.data(), ADD_VALUES));
    for (PetscInt k = 0; k < nc; k++) {
      c2[k] = 2 * c[k];
      v1[k] = a11 * PetscRealPart(v[k]);
      v2[k] = l21 * PetscRealPart(v[k]);
    }
    PetscCall(MatSetValues(r->Ac, 1, &row0, nc, c2.data(), v1.data(), ADD_VALUES));
    PetscCall(MatSetValues(r->Ac, 1, &row1, nc, c2.data(), v2.data(), ADD_VALUES));
    for (PetscInt k = 0; k < nc; k++) {
      c2[k] = 2 * c[k] + 1;
      v1[k] = l12 * PetscRealPart(v[k]);
      v2[k] = a22 * PetscRealPart(v[k]);
    }
    PetscCall(MatSetValues(r->Ac, 1, &row0, nc, c2.data(), v1.data(), ADD_VALUES));
    PetscCall(MatSetValues(r->Ac, 1, &row1, nc, c2.data(), v2.data(), ADD_VALUES));
    PetscCall(MatRestoreRow(r->M, i, &nc, &c, &v));
  }
  PetscCall(MatAssemblyBegin(r->Ar, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(r->Ac, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(r->Ar, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(r->Ac, MAT_FINAL_ASSEMBLY));
  r->h_fact = h;
  r->n_decomp++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* RADAU5's Newton tolerance (radau5.f, "FNEWT"; docs/radau_iia.md, "... the rules and their sources"): with
   RADAU5's transformed tolerance rtol' = 0.1 rtol^(2/3), kappa = max(10 u / rtol, min(0.03, rtol'^(1/2))).
   kappa is relative to the error test's weights atol + rtol |U|, which are not transformed here; the
   round-off term is therefore 10 u / rtol, which keeps the absolute Newton tolerance at or above
   10 u |U| as RADAU5's 10 u / rtol' does relative to its transformed weights. The smallest rtol of a
   vector tolerance is used (RADAU5 takes RTOL(1)); with rtol = 0, the smallest atol takes its place
   in the rule and there is no round-off term. */
PetscErrorCode RadauIIANewtonTolerance(TS ts, PetscReal *kappa)
{
  PetscReal atol, rtol, tol;
  Vec       vatol, vrtol;

  PetscFunctionBeginUser;
  PetscCall(TSGetTolerances(ts, &atol, &vatol, &rtol, &vrtol));
  if (vrtol) PetscCall(VecMin(vrtol, NULL, &rtol));
  if (vatol) PetscCall(VecMin(vatol, NULL, &atol));
  tol    = rtol > 0 ? rtol : atol;
  *kappa = PetscMin(0.03, PetscSqrtReal(0.1 * PetscPowReal(PetscMax(tol, 0), 2.0 / 3)));
  if (rtol > 0) *kappa = PetscMax(*kappa, 10 * PETSC_MACHINE_EPSILON / rtol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The error weights W = atol + rtol |U0| of the Newton increments, and the round-off floor of the
   tolerances: rho = || 10 u |U0| / W || in the norm of the error test (TSAdapt's, RMS by default) is
   the round-off of the solution measured as the error test measures errors. With rho >= 1 the
   tolerances ask for less than round-off can deliver: no error estimate, and no Newton increment,
   can be certified below them, and the step size would shrink and grow without end. That is
   reported instead (RadauIIAFloorFailure). RADAU5 has the same floor as an input check: it refuses
   rtol <= 10 u. */
PetscErrorCode RadauIIAWeights(TS ts, RadauIIA *r, PetscBool *below_floor)
{
  PetscReal atol, rtol, wmin, umax, worst;
  Vec       vatol, vrtol;
  PetscInt  N, iworst;
  NormType  type = ts->adapt ? ts->adapt->wnormtype : NORM_2;

  PetscFunctionBeginUser;
  *below_floor = PETSC_FALSE;
  PetscCall(TSGetTolerances(ts, &atol, &vatol, &rtol, &vrtol));
  PetscCall(VecCopy(r->U0, r->scal));
  PetscCall(VecAbs(r->scal));
  if (vrtol) PetscCall(VecPointwiseMult(r->scal, r->scal, vrtol));
  else PetscCall(VecScale(r->scal, rtol));
  if (vatol) PetscCall(VecAXPY(r->scal, 1.0, vatol));
  else PetscCall(VecShift(r->scal, atol));
  PetscCall(VecMin(r->scal, NULL, &wmin));
  PetscCheck(wmin > 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TS radauiia: the error weights atol + rtol |U| must be positive (a component is 0 with atol = 0; set -ts_atol > 0)");

  PetscCall(VecGetSize(r->U0, &N));
  PetscCall(VecCopy(r->U0, r->work));
  PetscCall(VecAbs(r->work));
  PetscCall(VecPointwiseDivide(r->work, r->work, r->scal));
  PetscCall(VecMax(r->work, &iworst, &worst));
  if (type == NORM_INFINITY) r->rho = worst;
  else {
    PetscCall(VecNorm(r->work, NORM_2, &r->rho));
    r->rho /= PetscSqrtReal((PetscReal)N);
  }
  r->rho *= 10 * PETSC_MACHINE_EPSILON;
  if (r->rho >= 1) {
    PetscCall(VecNorm(r->U0, NORM_INFINITY, &umax));
    PetscCall(PetscSNPrintf(r->floor_msg, sizeof(r->floor_msg),
                            "TS radauiia: at t = %g the tolerances -ts_rtol %g and -ts_atol %g are below the round-off floor of the solution: its round-off "
                            "10 u |U| is %.3g x (atol + rtol |U|) in the error norm (%.3g x at component %" PetscInt_FMT
                            "), so no error estimate can pass them reliably. Raise -ts_atol to at least %.2g (100 u max |U|) or -ts_rtol to at least %.2g "
                            "(100 u)",
                            (double)r->t0, (double)rtol, (double)atol, (double)r->rho, (double)(10 * PETSC_MACHINE_EPSILON * worst), iworst,
                            (double)(100 * PETSC_MACHINE_EPSILON * umax), (double)(100 * PETSC_MACHINE_EPSILON)));
    *below_floor = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A failure at the round-off floor, with the message in r->floor_msg: an error (PETSc's default
   -ts_error_if_step_fails), else a failed TS (TS_DIVERGED_STEP_REJECTED) and the message in -info. */
PetscErrorCode RadauIIAFloorFailure(TS ts, RadauIIA *r)
{
  PetscFunctionBeginUser;
  PetscCheck(!ts->errorifstepfailed, PetscObjectComm((PetscObject)ts), PETSC_ERR_NOT_CONVERGED, "%s", r->floor_msg);
  PetscCall(PetscInfo(ts, "%s\n", r->floor_msg));
  ts->reason = TS_DIVERGED_STEP_REJECTED;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Coefficients of the collocation polynomial of the step [cont_t0, cont_t0 + cont_h] in Newton
   form on the nodes s = 1, c2, c1, 0 (s = (t - cont_t0)/cont_h), so that
   U(s) = U_end + (s-1) [D1 + (s-c2) (D2 + (s-c1) D3)]. */
PetscErrorCode RadauIIABuildPolynomial(RadauIIA *r)
{
  const PetscReal *c = r->tab.c;

  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(r->D[0], -1.0, r->Z[1], r->Z[2]));
  PetscCall(VecScale(r->D[0], 1 / (1 - c[1])));
  PetscCall(VecWAXPY(r->work, -1.0, r->Z[0], r->Z[1])); /* [c2, c1] */
  PetscCall(VecScale(r->work, 1 / (c[1] - c[0])));
  PetscCall(VecWAXPY(r->D[1], -1.0, r->work, r->D[0]));
  PetscCall(VecScale(r->D[1], 1 / (1 - c[0])));
  PetscCall(VecAXPY(r->work, -1 / c[0], r->Z[0])); /* [c2, c1, 0] */
  PetscCall(VecScale(r->work, 1 / c[1]));
  PetscCall(VecWAXPY(r->D[2], -1.0, r->work, r->D[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* X = sum of the polynomial's terms at s, without U_end (X = U(s) - U_end). */
PetscErrorCode RadauIIAPolynomialIncrement(RadauIIA *r, PetscReal s, Vec X)
{
  const PetscReal  *c  = r->tab.c;
  const PetscReal   w0 = s - 1, w1 = w0 * (s - c[1]), w2 = w1 * (s - c[0]);
  const PetscScalar a[3] = {w0, w1, w2};

  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(X));
  PetscCall(VecMAXPY(X, 3, a, r->D));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Simplified Newton on the stage system for the attempt (t0, h), in the transformed variables.
   Stopping and failure as in RADAU5 (radau5.f, RADCOR, "LOOP FOR THE SIMPLIFIED NEWTON ITERATION"),
   with NEWT = k + 1 the number of iterations done and NIT = max_it: the rate theta is measured from
   the second iteration on, but not at the last allowed one; eta = theta / (1 - theta) (at the first
   iteration the previous step's, raised to the power 0.8); converged when eta ||dW|| <= kappa. */
PetscErrorCode RadauIIANewton(TS ts, RadauIIA *r, NewtonOutcome *outcome, PetscReal *hfac)
{
  const TSRadauIIATableau &tab = r->tab;
  PetscInt                 N;
  PetscReal                dynold = 1, thqold = 1;
  PetscBool                at_roundoff = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(VecGetSize(r->U0, &N));
  r->faccon = PetscPowReal(PetscMax(r->faccon, PETSC_MACHINE_EPSILON), 0.8);
  r->theta  = r->reuse_theta;
  *hfac     = 0.5;
  for (PetscInt k = 0;; k++) {
    PetscBool bad = PETSC_FALSE, ok;
    PetscReal dyno, sum = 0;

    if (k >= r->max_it) {
      *outcome = NewtonOutcome::too_many;
      break;
    }
    for (int i = 0; i < 3 && !bad; i++) {
      PetscScalar a[3];
      for (int j = 0; j < 3; j++) a[j] = tab.Ainv[i][j] / r->h;
      PetscCall(VecWAXPY(r->Y[i], 1.0, r->U0, r->Z[i]));
      PetscCall(VecZeroEntries(r->Udot));
      PetscCall(VecMAXPY(r->Udot, 3, a, r->Z));
      PetscCall(RadauIIAResidual(ts, r, r->t0 + tab.c[i] * r->h, r->Y[i], r->Udot, r->R[i], &bad));
    }
    if (bad) {
      *outcome = NewtonOutcome::domain;
      break;
    }
    /* right-hand sides -Tinv R: the real one in rhs, the complex pair interleaved in Xc */
    for (int p = 0; p < 3; p++) {
      PetscScalar a[3];
      Vec         out = p == 0 ? r->rhs : r->dW[p];
      for (int i = 0; i < 3; i++) a[i] = -tab.Tinv[p][i];
      PetscCall(VecZeroEntries(out));
      PetscCall(VecMAXPY(out, 3, a, r->R));
    }
    PetscCall(VecStrideScatter(r->dW[1], 0, r->Xc, INSERT_VALUES));
    PetscCall(VecStrideScatter(r->dW[2], 1, r->Xc, INSERT_VALUES));
    PetscCall(RadauIIASolve(r, r->kspr, r->rhs, r->dW[0], &ok, ts));
    if (ok) PetscCall(RadauIIASolve(r, r->kspc, r->Xc, r->Yc, &ok, ts));
    r->n_newton++;
    ts->snes_its++;
    if (!ok) {
      *outcome = NewtonOutcome::linear_solve;
      break;
    }
    PetscCall(VecStrideGather(r->Yc, 0, r->dW[1], INSERT_VALUES));
    PetscCall(VecStrideGather(r->Yc, 1, r->dW[2], INSERT_VALUES));

    for (int p = 0; p < 3; p++) {
      PetscReal nrm;
      PetscCall(VecPointwiseDivide(r->work, r->dW[p], r->scal));
      PetscCall(VecNorm(r->work, NORM_2, &nrm));
      sum += nrm * nrm;
    }
    dyno = PetscSqrtReal(sum / (3 * N));
    if (PetscIsInfOrNanReal(dyno)) {
      *outcome = NewtonOutcome::linear_solve;
      break;
    }
    /* an increment at the round-off level of the solution: the iterate cannot be improved, and the
       ratio of such increments is noise, not a contraction rate */
    at_roundoff = (PetscBool)(dyno <= 10 * r->rho);
    if (k >= 1 && k + 1 < r->max_it && !at_roundoff) {
      /* contraction rate; averaged over the last two iterations once available */
      const PetscReal thq = dyno / dynold;
      r->theta            = k == 1 ? thq : PetscSqrtReal(thq * thqold);
      thqold              = thq;
      if (r->theta >= 0.99) {
        *outcome = NewtonOutcome::diverged;
        break;
      }
      r->faccon = r->theta / (1 - r->theta);
      {
        /* RADAU5's prediction of the error after the iterations still allowed, if the rate holds
           (its exponent NIT - 1 - NEWT is one less than the iterations left: a safety margin) */
        const PetscInt  margin    = r->max_it - 2 - k;
        const PetscReal predicted = r->faccon * dyno * PetscPowReal(r->theta, (PetscReal)margin) / r->kappa;
        if (predicted >= 1) {
          const PetscReal q = PetscMax(1e-4, PetscMin(20.0, predicted));
          *hfac             = 0.8 * PetscPowReal(q, -1.0 / (4 + margin));
          *outcome          = NewtonOutcome::slow;
          break;
        }
      }
    }
    dynold = PetscMax(dyno, PETSC_MACHINE_EPSILON);
    for (int i = 0; i < 3; i++) {
      const PetscScalar a[3] = {tab.T[i][0], tab.T[i][1], tab.T[i][2]};
      PetscCall(VecMAXPY(r->Z[i], 3, a, r->dW));
    }
    if ((r->faccon * dyno <= r->kappa || (at_roundoff && dyno <= r->kappa)) && k + 1 >= r->min_it) {
      r->newt  = k + 1;
      *outcome = NewtonOutcome::converged;
      break;
    }
  }
  r->newton_roundoff = at_roundoff;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With TSAdaptBasic (and -ts_radauiia_predictive, the default), RADAU5's step-size rules on top of
   TSAdapt's proposal next_h (radau5.f, RADCOR, "COMPUTATION OF HNEW" and "PREDICTIVE CONTROLLER OF
   GUSTAFSSON"; Hairer & Wanner II, §IV.8):
   - the safety factor falls with the Newton iterations NEWT the step took: RADAU5's
     FAC = min(SAFE, SAFE (1 + 2 NIT) / (NEWT + 2 NIT)), i.e. next_h is scaled by FAC / SAFE;
   - after an accepted step, Gustafsson's predictive controller: the step may not exceed
     h SAFE / FACGUS with FACGUS = (h_acc / h) (err^2 / err_acc)^(1/4), clipped to [1/8, 5], where
     h_acc and err_acc = max(0.01, err) are those of the previous accepted step.
   Other adapters (dsp, none, ...) are left as they are. */
PetscErrorCode RadauIIAStepControl(TS ts, RadauIIA *r, PetscBool accept, PetscReal *next_h)
{
  PetscBool basic;
  PetscReal safety, reject_safety;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts->adapt, TSADAPTBASIC, &basic));
  if (!r->predictive || !basic || !r->wlte_valid || r->wlte < 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSAdaptGetSafety(ts->adapt, &safety, &reject_safety));
  *next_h *= PetscMin(1.0, (1.0 + 2 * r->max_it) / (PetscReal)(r->newt + 2 * r->max_it));
  if (accept) {
    if (r->have_acc) {
      const PetscReal facgus = (r->hacc / r->h) * PetscPowReal(r->wlte * r->wlte / r->erracc, 0.25) / safety;
      *next_h                = PetscMin(*next_h, r->h / PetscMax(0.125, PetscMin(5.0, facgus)));
    }
    r->hacc     = r->h;
    r->erracc   = PetscMax(0.01, r->wlte);
    r->have_acc = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSStep_RadauIIA(TS ts)
{
  RadauIIA *r          = (RadauIIA *)ts->data;
  PetscInt  rejections = 0;
  PetscBool accept     = PETSC_TRUE;
  PetscReal next_h     = ts->time_step;

  PetscFunctionBeginUser;
  if (!r->started || (ts->steprestart && !ts->steprollback)) {
    /* a new trajectory: no history, a fresh Jacobian */
    r->have_cont = PETSC_FALSE;
    r->need_jac  = PETSC_TRUE;
    r->first     = PETSC_TRUE;
    r->have_acc  = PETSC_FALSE;
    r->faccon    = 1;
    r->h_fact    = 0;
    PetscCall(VecZeroEntries(r->Udot0));
    PetscCall(VecZeroEntries(r->Udot1));
    if (ts->steps == 0) r->n_jac = r->n_newton = r->n_solve = r->n_decomp = r->n_ifunc = r->n_newton_fail = r->n_domain = 0;
    r->started = PETSC_TRUE;
  } else if (!ts->steprollback) PetscCall(VecCopy(r->Udot1, r->Udot0)); /* U' at the new step's start */
  r->t0 = ts->ptime;
  PetscCall(VecCopy(ts->vec_sol, r->U0));
  {
    PetscBool below_floor;
    PetscCall(RadauIIAWeights(ts, r, &below_floor));
    if (below_floor) {
      PetscCall(RadauIIAFloorFailure(ts, r));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  /* RADAU5's rule; its round-off term (absent with rtol = 0) is never below rho */
  if (r->newton_tol > 0) r->kappa = r->newton_tol;
  else {
    PetscCall(RadauIIANewtonTolerance(ts, &r->kappa));
    r->kappa = PetscMax(r->kappa, r->rho);
  }
  r->n_floor = 0;

  while (!ts->reason) {
    NewtonOutcome outcome  = NewtonOutcome::too_many;
    PetscReal     hfac     = 0.5;
    PetscBool     stage_ok = PETSC_TRUE;

    r->h          = ts->time_step;
    r->wlte_valid = PETSC_FALSE;
    if (r->need_jac) {
      PetscCall(RadauIIAEvaluateJacobian(ts, r));
      r->need_jac  = PETSC_FALSE;
      r->jac_fresh = PETSC_TRUE;
      r->h_fact    = 0;
    }
    if (r->h != r->h_fact || r->pattern_dirty) PetscCall(RadauIIAAssembleMatrices(ts, r));

    /* starting values: the previous step's collocation polynomial continued, or zero */
    for (int i = 0; i < 3; i++) {
      if (r->have_cont && r->extrapolate) PetscCall(RadauIIAPolynomialIncrement(r, 1 + r->tab.c[i] * r->h / r->cont_h, r->Z[i]));
      else PetscCall(VecZeroEntries(r->Z[i]));
      PetscCall(TSPreStage(ts, r->t0 + r->tab.c[i] * r->h));
    }
    PetscCall(RadauIIANewton(ts, r, &outcome, &hfac));
    if (outcome != NewtonOutcome::converged) {
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT " t=%g h=%g: Newton %s, retrying with h=%g\n", ts->steps, (double)r->t0, (double)r->h,
                          NewtonOutcomeNames[(int)outcome], (double)(r->h * hfac)));
      if (outcome == NewtonOutcome::domain) r->n_domain++;
      else {
        r->n_newton_fail++;
        ts->num_snes_failures++; /* reported by TSGetSNESFailures(); no limit: h is reduced instead */
      }
      ts->time_step = r->h * hfac;
      /* a stale J may be why Newton failed to converge; a domain error or a singular matrix is not
         cured by a new J (the new h gives new factors anyway) */
      if (!r->jac_fresh && (outcome == NewtonOutcome::diverged || outcome == NewtonOutcome::slow || outcome == NewtonOutcome::too_many))
        r->need_jac = PETSC_TRUE;
      /* Newton's floor: its increments are at the round-off level of the solution and still above its
         tolerance; a smaller h does not lower round-off, so a second such failure ends the solve */
      if (outcome == NewtonOutcome::too_many && r->newton_roundoff && ++r->n_floor >= 2) {
        if (r->newton_tol > 0)
          PetscCall(PetscSNPrintf(r->floor_msg, sizeof(r->floor_msg),
                                  "TS radauiia: at t = %g Newton cannot reduce its increments below its tolerance because of round-off: they stay at the "
                                  "round-off level of the solution, 10 u |U| = %.3g x (atol + rtol |U|), above -ts_radauiia_newton_tol %g. That Newton "
                                  "tolerance is below the round-off floor: raise it above %.2g, or leave it to RADAU5's rule",
                                  (double)r->t0, (double)r->rho, (double)r->kappa, (double)(10 * r->rho)));
        else {
          PetscReal atol, rtol;
          PetscCall(TSGetTolerances(ts, &atol, NULL, &rtol, NULL));
          PetscCall(
            PetscSNPrintf(r->floor_msg, sizeof(r->floor_msg),
                          "TS radauiia: at t = %g Newton cannot reduce its increments below its tolerance %.3g x (atol + rtol |U|) because of "
                          "round-off: they stay at the round-off level of the solution, 10 u |U| = %.3g x (atol + rtol |U|). The tolerances -ts_rtol %g "
                          "and -ts_atol %g are below the round-off floor: raise them",
                          (double)r->t0, (double)r->kappa, (double)r->rho, (double)rtol, (double)atol));
        }
        PetscCall(RadauIIAFloorFailure(ts, r));
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      goto reject_step;
    }
    for (int i = 0; i < 3; i++) PetscCall(VecWAXPY(r->Y[i], 1.0, r->U0, r->Z[i]));
    for (int i = 0; i < 3; i++) PetscCall(TSPostStage(ts, r->t0 + r->tab.c[i] * r->h, i, r->Y));
    for (int i = 0; i < 3 && stage_ok; i++) PetscCall(TSAdaptCheckStage(ts->adapt, ts, r->t0 + r->tab.c[i] * r->h, r->Y[i], &stage_ok));
    if (!stage_ok) { /* TSAdaptCheckStage has reduced ts->time_step */
      r->n_domain++;
      goto reject_step;
    }

    PetscCall(VecWAXPY(r->U1, 1.0, r->U0, r->Z[2]));
    PetscCall(TSAdaptCandidatesClear(ts->adapt));
    PetscCall(TSAdaptCandidateAdd(ts->adapt, "radauiia", 5, 3, 1.0, 1.0, PETSC_TRUE));
    PetscCall(TSAdaptChoose(ts->adapt, ts, r->h, NULL, &next_h, &accept));
    PetscCall(RadauIIAStepControl(ts, r, accept, &next_h));
    if (!accept) {
      /* a first step that fails the error test is usually far too large (e.g. across an initial
         layer, where the error grows as h shrinks towards the fast time scale): RADAU5 cuts it by 10 */
      ts->time_step = r->first ? PetscMin(next_h, 0.1 * r->h) : next_h;
      if (!r->jac_fresh) r->need_jac = PETSC_TRUE;
      goto reject_step;
    }

    /* accepted */
    PetscCall(VecCopy(r->U1, ts->vec_sol));
    ts->ptime += r->h;
    PetscCall(RadauIIABuildPolynomial(r));
    r->cont_t0   = r->t0;
    r->cont_h    = r->h;
    r->have_cont = PETSC_TRUE;
    {
      PetscScalar a[3];
      for (int j = 0; j < 3; j++) a[j] = r->tab.Ainv[2][j] / r->h;
      PetscCall(VecZeroEntries(r->Udot1));
      PetscCall(VecMAXPY(r->Udot1, 3, a, r->Z));
    }
    /* RADAU5's reuse: a fast Newton keeps J, and a step-size change too small to pay for new
       factors keeps h; neither is done close to the final time, where TSAdapt fits the last step */
    r->jac_fresh_prev = r->jac_fresh;
    r->jac_fresh      = PETSC_FALSE;
    r->need_jac       = (PetscBool)(r->theta > r->reuse_theta);
    if (ts->ptime + 2 * next_h < ts->max_time) {
      if (rejections && next_h > r->h) next_h = r->h;
      if (!r->need_jac && next_h >= r->keep_step[0] * r->h && next_h <= r->keep_step[1] * r->h) next_h = r->h;
    }
    ts->time_step    = next_h;
    r->first         = PETSC_FALSE;
    r->last_rejected = PETSC_FALSE;
    break;

  reject_step:
    ts->reject++;
    accept           = PETSC_FALSE;
    r->last_rejected = PETSC_TRUE;
    if (!ts->reason && ++rejections > ts->max_reject && ts->max_reject >= 0) {
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT ": %" PetscInt_FMT " rejections, more than -ts_max_reject allows\n", ts->steps, rejections));
      ts->reason = TS_DIVERGED_STEP_REJECTED;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* RADAU5's estimate err = (gamma/h M - J)^-1 [f(t0, U0) + (1/(gamma0 h)) M sum_i e_i Z_i], written
   with F: the bracket is -F(t0, U0, V) with V = -sum_i e_i Z_i / (gamma0 h). On the first step and
   after a rejection a large estimate is filtered once more, with f evaluated at U0 + err. */
PetscErrorCode TSEvaluateWLTE_RadauIIA(TS ts, NormType wnormtype, PetscInt *order, PetscReal *wlte)
{
  RadauIIA *r = (RadauIIA *)ts->data;
  PetscReal wa, wr;
  PetscBool bad, ok;

  PetscFunctionBeginUser;
  if (order) *order = 4; /* the estimate is O(h^4): TSAdaptBasic scales h by wlte^(-1/4) */
  if (r->wlte_valid && r->wlte_type == wnormtype) {
    *wlte = r->wlte;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(r->h > 0 && r->h == r->h_fact, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS radauiia: no step to estimate the error of");
  {
    PetscScalar a[3];
    for (int i = 0; i < 3; i++) a[i] = -r->tab.e[i] / (r->tab.gamma0 * r->h);
    PetscCall(VecZeroEntries(r->Udot));
    PetscCall(VecMAXPY(r->Udot, 3, a, r->Z));
  }
  *wlte = PETSC_INFINITY;
  PetscCall(RadauIIAResidual(ts, r, r->t0, r->U0, r->Udot, r->rhs, &bad));
  if (!bad) {
    PetscCall(VecScale(r->rhs, -1.0));
    PetscCall(RadauIIASolve(r, r->kspr, r->rhs, r->err, &ok, ts));
    if (ok) {
      PetscCall(VecWAXPY(r->work, 1.0, r->U1, r->err));
      PetscCall(TSErrorWeightedNorm(ts, r->U1, r->work, wnormtype, wlte, &wa, &wr));
      if (PetscIsInfOrNanReal(*wlte)) *wlte = PETSC_INFINITY;
    }
  }
  if (*wlte >= 1 && *wlte < PETSC_INFINITY && (r->first || r->last_rejected)) {
    PetscCall(VecWAXPY(r->work, 1.0, r->U0, r->err));
    PetscCall(RadauIIAResidual(ts, r, r->t0, r->work, r->Udot, r->rhs, &bad));
    if (!bad) {
      PetscCall(VecScale(r->rhs, -1.0));
      PetscCall(RadauIIASolve(r, r->kspr, r->rhs, r->err, &ok, ts));
      if (ok) {
        PetscReal w2;
        PetscCall(VecWAXPY(r->work, 1.0, r->U1, r->err));
        PetscCall(TSErrorWeightedNorm(ts, r->U1, r->work, wnormtype, &w2, &wa, &wr));
        if (!PetscIsInfOrNanReal(w2)) *wlte = w2;
      }
    }
  }
  r->wlte       = *wlte;
  r->wlte_type  = wnormtype;
  r->wlte_valid = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSInterpolate_RadauIIA(TS ts, PetscReal t, Vec X)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCheck(r->have_cont, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_WRONGSTATE, "TS radauiia: no completed step to interpolate in");
  PetscCall(RadauIIAPolynomialIncrement(r, (t - r->cont_t0) / r->cont_h, X));
  PetscCall(VecAXPY(X, 1.0, r->U1));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRollBack_RadauIIA(TS ts)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCall(VecCopy(r->U0, ts->vec_sol));
  /* J is only evaluated at the start of a step, so the one in memory is the one the undone step
     used: keep it. The polynomial of the step before that is gone: Newton starts from zero. */
  r->have_cont = PETSC_FALSE;
  r->jac_fresh = r->jac_fresh_prev;
  r->need_jac  = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSReset_RadauIIA(TS ts)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  for (Vec *v : {&r->U0, &r->U1, &r->Udot, &r->Udot0, &r->Udot1, &r->scal, &r->work, &r->rhs, &r->err, &r->Xc, &r->Yc}) PetscCall(VecDestroy(v));
  for (int i = 0; i < 3; i++)
    for (Vec *v : {&r->Z[i], &r->Y[i], &r->R[i], &r->dW[i], &r->D[i]}) PetscCall(VecDestroy(v));
  for (Mat *m : {&r->P, &r->M, &r->Ar, &r->Ac}) PetscCall(MatDestroy(m));
  PetscCall(KSPDestroy(&r->kspr));
  PetscCall(KSPDestroy(&r->kspc));
  r->pattern_dirty = PETSC_TRUE;
  r->h_fact        = 0;
  r->have_cont     = PETSC_FALSE;
  r->started       = PETSC_FALSE;
  r->wlte_valid    = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetCounters_RadauIIA(TS ts, PetscInt *jac, PetscInt *newton, PetscInt *solves)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  if (jac) *jac = r->n_jac;
  if (newton) *newton = r->n_newton;
  if (solves) *solves = r->n_solve;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The setters check what TSSetFromOptions_RadauIIA() checks for the options of the same values. */
PetscErrorCode TSRadauIIASetJacobianReuse_RadauIIA(TS ts, PetscReal theta)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCheck(theta >= 0 && theta < 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "TSRadauIIASetJacobianReuse(): theta = %g must be in [0, 1)",
             (double)theta);
  r->reuse_theta = theta;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetJacobianReuse_RadauIIA(TS ts, PetscReal *theta)
{
  PetscFunctionBeginUser;
  *theta = ((RadauIIA *)ts->data)->reuse_theta;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIASetNewtonTolerance_RadauIIA(TS ts, PetscReal kappa)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCheck(kappa == PETSC_DEFAULT || (kappa > 0 && kappa < 1), PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TSRadauIIASetNewtonTolerance(): kappa = %g must be in (0, 1), or PETSC_DEFAULT for RADAU5's rule", (double)kappa);
  r->newton_tol = kappa;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetNewtonTolerance_RadauIIA(TS ts, PetscReal *kappa)
{
  PetscFunctionBeginUser;
  *kappa = ((RadauIIA *)ts->data)->newton_tol;
  if (*kappa == PETSC_DEFAULT) PetscCall(RadauIIANewtonTolerance(ts, kappa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIASetNewtonMaxIterations_RadauIIA(TS ts, PetscInt max_it)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscCheck(max_it >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "TSRadauIIASetNewtonMaxIterations(): max_it = %" PetscInt_FMT " must be >= 1", max_it);
  r->max_it = max_it;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetNewtonMaxIterations_RadauIIA(TS ts, PetscInt *max_it)
{
  PetscFunctionBeginUser;
  *max_it = ((RadauIIA *)ts->data)->max_it;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every function TSCreate_RadauIIA() composes (listed in radau_iia.h), removed again on destroy so
   that a TS changed to another type no longer answers to them */
const char *const kComposedNames[] = {"TSRadauIIAGetCounters_C",           "TSRadauIIASetJacobianReuse_C",   "TSRadauIIAGetJacobianReuse_C",
                                      "TSRadauIIASetNewtonTolerance_C",    "TSRadauIIAGetNewtonTolerance_C", "TSRadauIIASetNewtonMaxIterations_C",
                                      "TSRadauIIAGetNewtonMaxIterations_C"};

PetscErrorCode TSDestroy_RadauIIA(TS ts)
{
  PetscFunctionBeginUser;
  PetscCall(TSReset_RadauIIA(ts));
  delete (RadauIIA *)ts->data;
  ts->data = NULL;
  for (const char *name : kComposedNames) PetscCall(PetscObjectComposeFunction((PetscObject)ts, name, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetUp_RadauIIA(TS ts)
{
  RadauIIA *r = (RadauIIA *)ts->data;
  PetscInt  n;

  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptCandidatesClear(ts->adapt));
  PetscCall(RadauIIAEnsureKSPs(ts, r));
  /* sub-solver options are read here, as PETSc's block preconditioners do for their blocks */
  PetscCall(KSPSetFromOptions(r->kspr));
  PetscCall(KSPSetFromOptions(r->kspc));
  for (Vec *v : {&r->U0, &r->U1, &r->Udot, &r->Udot0, &r->Udot1, &r->scal, &r->work, &r->rhs, &r->err}) PetscCall(VecDuplicate(ts->vec_sol, v));
  for (int i = 0; i < 3; i++)
    for (Vec *v : {&r->Z[i], &r->Y[i], &r->R[i], &r->dW[i], &r->D[i]}) PetscCall(VecDuplicate(ts->vec_sol, v));
  PetscCall(VecGetLocalSize(ts->vec_sol, &n));
  PetscCall(VecCreate(PetscObjectComm((PetscObject)ts), &r->Xc));
  PetscCall(VecSetSizes(r->Xc, 2 * n, PETSC_DETERMINE));
  PetscCall(VecSetBlockSize(r->Xc, 2));
  PetscCall(VecSetType(r->Xc, VECSTANDARD));
  PetscCall(VecDuplicate(r->Xc, &r->Yc));
  r->started = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSSetFromOptions_RadauIIA(TS ts, PetscOptionItems *PetscOptionsObject)
{
  RadauIIA *r = (RadauIIA *)ts->data;

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Radau IIA order 5 (radauiia) options; linear solvers: -ts_radauiia_ksp_*, -ts_radauiia_pc_*");
  PetscCall(PetscOptionsInt("-ts_radauiia_newton_max_it", "Simplified Newton iterations per step attempt", "TSRADAUIIA", r->max_it, &r->max_it, NULL));
  PetscCall(PetscOptionsInt("-ts_radauiia_newton_min_it", "Newton iterations before convergence is accepted (1: RADAU5, 2: SciPy)", "TSRADAUIIA", r->min_it,
                            &r->min_it, NULL));
  PetscCall(PetscOptionsBool("-ts_radauiia_predictive", "With -ts_adapt_type basic: RADAU5's predictive controller and Newton-dependent safety factor",
                             "TSRADAUIIA", r->predictive, &r->predictive, NULL));
  {
    /* shown with the value in effect: RADAU5's rule for the TS's tolerances (read before this) unless set */
    PetscReal kappa = r->newton_tol;
    PetscBool set;
    if (kappa == PETSC_DEFAULT) PetscCall(RadauIIANewtonTolerance(ts, &kappa));
    PetscCall(PetscOptionsReal("-ts_radauiia_newton_tol",
                               "Newton stops when its estimated error is below this fraction of the error tolerance (default: RADAU5's rule "
                               "max(10 u/rtol, min(0.03, sqrt(0.1 rtol^(2/3)))); 'default' restores it)",
                               "TSRADAUIIA", kappa, &kappa, &set));
    if (set) r->newton_tol = kappa;
  }
  PetscCall(PetscOptionsReal("-ts_radauiia_jacobian_reuse", "Keep the Jacobian for the next step while the Newton contraction rate is below this", "TSRADAUIIA",
                             r->reuse_theta, &r->reuse_theta, NULL));
  PetscCall(PetscOptionsReal("-ts_radauiia_keep_step_min", "Keep h (and the factorisations) if TSAdapt proposes between min x h ...", "TSRADAUIIA",
                             r->keep_step[0], &r->keep_step[0], NULL));
  PetscCall(PetscOptionsReal("-ts_radauiia_keep_step_max", "... and max x h", "TSRADAUIIA", r->keep_step[1], &r->keep_step[1], NULL));
  PetscCall(PetscOptionsBool("-ts_radauiia_extrapolate", "Start Newton from the previous step's collocation polynomial (else from zero)", "TSRADAUIIA",
                             r->extrapolate, &r->extrapolate, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(r->max_it >= 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE, "Option -ts_radauiia_newton_max_it = %" PetscInt_FMT ": must be >= 1",
             r->max_it);
  PetscCheck(r->min_it >= 1 && r->min_it <= r->max_it, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_radauiia_newton_min_it = %" PetscInt_FMT ": must be in [1, -ts_radauiia_newton_max_it = %" PetscInt_FMT "]", r->min_it, r->max_it);
  PetscCheck(r->newton_tol == PETSC_DEFAULT || (r->newton_tol > 0 && r->newton_tol < 1), PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_radauiia_newton_tol = %g: must be in (0, 1), or 'default' for RADAU5's rule", (double)r->newton_tol);
  PetscCheck(r->reuse_theta >= 0 && r->reuse_theta < 1, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Option -ts_radauiia_jacobian_reuse = %g: must be in [0, 1)", (double)r->reuse_theta);
  PetscCheck(r->keep_step[0] <= r->keep_step[1], PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_OUTOFRANGE,
             "Options -ts_radauiia_keep_step_min = %g > -ts_radauiia_keep_step_max = %g", (double)r->keep_step[0], (double)r->keep_step[1]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSView_RadauIIA(TS ts, PetscViewer viewer)
{
  RadauIIA *r = (RadauIIA *)ts->data;
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  Radau IIA, 3 stages, order 5 (stage order 3); error estimate O(h^4) (order 3)\n"));
  {
    PetscReal kappa = r->newton_tol;
    if (kappa == PETSC_DEFAULT) PetscCall(RadauIIANewtonTolerance(ts, &kappa));
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "  simplified Newton: %" PetscInt_FMT " to %" PetscInt_FMT
                                     " iterations, tolerance %g (%s), Jacobian kept while rate <= %g, h kept for ratios in [%g, %g], start values %s\n",
                                     r->min_it, r->max_it, (double)kappa, r->newton_tol == PETSC_DEFAULT ? "RADAU5's rule" : "set", (double)r->reuse_theta,
                                     (double)r->keep_step[0], (double)r->keep_step[1], r->extrapolate ? "extrapolated" : "zero"));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "  step control: TSAdapt%s\n",
                                   r->predictive ? ", with TSAdaptBasic completed by RADAU5's predictive controller and Newton-dependent safety" : ""));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "  Jacobian evaluations %" PetscInt_FMT ", factorisations %" PetscInt_FMT ", Newton iterations %" PetscInt_FMT
                                   ", linear solves %" PetscInt_FMT ", IFunction evaluations %" PetscInt_FMT "\n",
                                   r->n_jac, r->n_decomp, r->n_newton, r->n_solve, r->n_ifunc));
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "  rejected attempts: Newton not converging %" PetscInt_FMT ", domain errors %" PetscInt_FMT ", error test %" PetscInt_FMT
                                   "\n",
                                   r->n_newton_fail, r->n_domain, ts->reject - r->n_newton_fail - r->n_domain));
  if (r->kspr) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  real system (gamma/h M - J):\n"));
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(KSPView(r->kspr, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  complex system as a real 2N x 2N system:\n"));
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(KSPView(r->kspc, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* registered by TurgorTSRegisterAll() (ts_register.cpp), also as "radau5" where PETSc has no RADAU5 */
PetscErrorCode TSCreate_RadauIIA(TS ts)
{
  RadauIIA *r = new RadauIIA();

  PetscFunctionBeginUser;
  ComputeTableau(&r->tab);
  ts->data                = r;
  ts->ops->setup          = TSSetUp_RadauIIA;
  ts->ops->step           = TSStep_RadauIIA;
  ts->ops->interpolate    = TSInterpolate_RadauIIA;
  ts->ops->evaluatewlte   = TSEvaluateWLTE_RadauIIA;
  ts->ops->rollback       = TSRollBack_RadauIIA;
  ts->ops->setfromoptions = TSSetFromOptions_RadauIIA;
  ts->ops->view           = TSView_RadauIIA;
  ts->ops->reset          = TSReset_RadauIIA;
  ts->ops->destroy        = TSDestroy_RadauIIA;
  ts->ops->snesfunction   = SNESFormFunction_RadauIIA;
  ts->usessnes            = PETSC_FALSE; /* Newton is done here, on the transformed stage system */
  ts->default_adapt_type  = TSADAPTBASIC;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIAGetCounters_C", TSRadauIIAGetCounters_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIASetJacobianReuse_C", TSRadauIIASetJacobianReuse_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIAGetJacobianReuse_C", TSRadauIIAGetJacobianReuse_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIASetNewtonTolerance_C", TSRadauIIASetNewtonTolerance_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIAGetNewtonTolerance_C", TSRadauIIAGetNewtonTolerance_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIASetNewtonMaxIterations_C", TSRadauIIASetNewtonMaxIterations_RadauIIA));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRadauIIAGetNewtonMaxIterations_C", TSRadauIIAGetNewtonMaxIterations_RadauIIA));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetCounters(TS ts, PetscInt *jacobian_evals, PetscInt *newton_its, PetscInt *linear_solves)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscUseMethod(ts, "TSRadauIIAGetCounters_C", (TS, PetscInt *, PetscInt *, PetscInt *), (ts, jacobian_evals, newton_its, linear_solves));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PetscTryMethod: a no-op on a TS of another type, so callers may set it before knowing the type */
PetscErrorCode TSRadauIIASetJacobianReuse(TS ts, PetscReal theta)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveReal(ts, theta, 2);
  PetscTryMethod(ts, "TSRadauIIASetJacobianReuse_C", (TS, PetscReal), (ts, theta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetJacobianReuse(TS ts, PetscReal *theta)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidRealPointer(theta, 2);
  PetscUseMethod(ts, "TSRadauIIAGetJacobianReuse_C", (TS, PetscReal *), (ts, theta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIASetNewtonTolerance(TS ts, PetscReal kappa)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveReal(ts, kappa, 2);
  PetscTryMethod(ts, "TSRadauIIASetNewtonTolerance_C", (TS, PetscReal), (ts, kappa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetNewtonTolerance(TS ts, PetscReal *kappa)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidRealPointer(kappa, 2);
  PetscUseMethod(ts, "TSRadauIIAGetNewtonTolerance_C", (TS, PetscReal *), (ts, kappa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIASetNewtonMaxIterations(TS ts, PetscInt max_it)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidLogicalCollectiveInt(ts, max_it, 2);
  PetscTryMethod(ts, "TSRadauIIASetNewtonMaxIterations_C", (TS, PetscInt), (ts, max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetNewtonMaxIterations(TS ts, PetscInt *max_it)
{
  PetscFunctionBeginUser;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidIntPointer(max_it, 2);
  PetscUseMethod(ts, "TSRadauIIAGetNewtonMaxIterations_C", (TS, PetscInt *), (ts, max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSRadauIIAGetTableau(TSRadauIIATableau *tableau)
{
  PetscFunctionBeginUser;
  PetscValidPointer(tableau, 1);
  ComputeTableau(tableau);
  PetscFunctionReturn(PETSC_SUCCESS);
}
