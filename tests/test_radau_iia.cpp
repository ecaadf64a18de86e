static const char help[] = "The radauiia TS type (Radau IIA, order 5): (a) its constants against independent derivations;\n"
                           "(b) the order measured with fixed steps on a linear system with a non-trivial mass matrix,\n"
                           "and the order of the error estimate; (c) adaptive runs on a stiff nonlinear problem\n"
                           "(IFunction and RHS forms) against the exact solution; (d) TSInterpolate inside steps;\n"
                           "(e) domain errors (NaN, TSSetFunctionDomainError, SNESSetFunctionDomainError) force\n"
                           "rejections and the solve completes; (f) a distributed heat equation with a finite-element mass\n"
                           "matrix (also run on 2 ranks, where only (f) runs) against its semi-discrete exact solution;\n"
                           "(g) the type is registered as radauiia, and -ts_type radau5 selects it where PETSc has no RADAU5;\n"
                           "(h) defaults set with TSRadauIIASet*() before TSSetFromOptions() are used, options override them,\n"
                           "and the setters are a no-op on another TS type.\n";
#include "test_util.h"
#include "ode_util.h"
#include <turgor/ts/radau_iia.h>
#include <complex>

namespace {

enum class Kind {
  oscillator,
  stiff
};
enum class Domain {
  none,
  nan_values,
  callback,
  snes_flag
};

/* oscillator: M U' = L U with M = [[2,1],[1,3]], L = M B, B = [[-1/2, 2], [-2, -1/2]],
   U = exp(-t/2) [[cos 2t, sin 2t], [-sin 2t, cos 2t]] U(0), U(0) = (1, 0.5).
   stiff: u1' = lambda (u1 - sin t) + cos t, 2 u2' = -2 u2^2 (M = diag(1, 2); M = I in the RHS
   form), u(0) = (1, 1): u1 = sin t + exp(lambda t), u2 = 1/(1 + t). */
struct Problem {
  Kind      kind   = Kind::oscillator;
  Domain    domain = Domain::none;
  PetscReal lambda = -1e5;
  PetscReal hlim   = 0; /* domain error for stage times beyond t_n + hlim */
  PetscInt  nf = 0, nj = 0;
  /* dense-output sampling inside steps */
  PetscBool sample     = PETSC_FALSE;
  PetscReal interp_err = 0;
  Vec       X          = NULL;

  PetscReal M[2][2] = {
    {2, 1},
    {1, 3}
  };
  PetscReal L[2][2];
  Problem()
  {
    const PetscReal B[2][2] = {
      {-0.5, 2   },
      {-2,   -0.5}
    };
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) L[i][j] = M[i][0] * B[0][j] + M[i][1] * B[1][j];
  }
  void Exact(PetscReal t, PetscReal u[2]) const
  {
    if (kind == Kind::oscillator) {
      const PetscReal e = std::exp(-0.5 * t), c = std::cos(2 * t), s = std::sin(2 * t);
      u[0] = e * (c * 1 + s * 0.5);
      u[1] = e * (-s * 1 + c * 0.5);
    } else {
      u[0] = std::sin(t) + std::exp(lambda * t);
      u[1] = 1 / (1 + t);
    }
  }
  void Initial(PetscReal u[2]) const { Exact(0, u); }
};

PetscErrorCode StageTooFar(TS ts, Problem *p, PetscReal t, PetscBool *far)
{
  PetscReal tn;
  PetscFunctionBeginUser;
  PetscCall(TSGetTime(ts, &tn));
  *far = (PetscBool)(p->hlim > 0 && t - tn > p->hlim * (1 + 1e-12));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *u, *ud;
  PetscScalar       *f;
  PetscBool          far = PETSC_FALSE;

  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArrayRead(Udot, &ud));
  PetscCall(VecGetArray(F, &f));
  if (p->kind == Kind::oscillator) {
    for (int i = 0; i < 2; i++) f[i] = p->M[i][0] * ud[0] + p->M[i][1] * ud[1] - (p->L[i][0] * u[0] + p->L[i][1] * u[1]);
  } else {
    f[0] = ud[0] - (p->lambda * (u[0] - std::sin(t)) + std::cos(t));
    f[1] = 2 * ud[1] + 2 * u[1] * u[1];
  }
  PetscCall(StageTooFar(ts, p, t, &far));
  if (far && p->domain == Domain::nan_values) f[0] = f[1] = NAN;
  if (far && p->domain == Domain::snes_flag) {
    SNES snes;
    PetscCall(TSGetSNES(ts, &snes));
    PetscCall(SNESSetFunctionDomainError(snes));
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Udot, &ud));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *u;
  PetscScalar        v[2][2];

  PetscFunctionBeginUser;
  p->nj++;
  PetscCall(VecGetArrayRead(U, &u));
  if (p->kind == Kind::oscillator) {
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) v[i][j] = shift * p->M[i][j] - p->L[i][j];
  } else {
    v[0][0] = shift - p->lambda;
    v[0][1] = 0;
    v[1][0] = 0;
    v[1][1] = 2 * shift + 4 * u[1];
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(turgor_test::SetDenseMatrix(B, 2, &v[0][0]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the stiff problem as U' = G(t, U) */
PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec G, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *u;
  PetscScalar       *g;

  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(G, &g));
  g[0] = p->lambda * (u[0] - std::sin(t)) + std::cos(t);
  g[1] = -u[1] * u[1];
  PetscCall(VecRestoreArray(G, &g));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec U, Mat A, Mat B, void *ctx)
{
  Problem           *p = (Problem *)ctx;
  const PetscScalar *u;
  PetscScalar        v[4];

  PetscFunctionBeginUser;
  p->nj++;
  PetscCall(VecGetArrayRead(U, &u));
  v[0] = p->lambda;
  v[1] = 0;
  v[2] = 0;
  v[3] = -2 * u[1];
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(turgor_test::SetDenseMatrix(B, 2, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DomainCheck(TS ts, PetscReal t, Vec Y, PetscBool *accept)
{
  Problem  *p;
  PetscBool far = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &p));
  PetscCall(StageTooFar(ts, p, t, &far));
  *accept = (PetscBool)!far;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* after each step: the collocation polynomial at interior points against the exact solution */
PetscErrorCode SampleInterior(TS ts)
{
  Problem           *p;
  PetscReal          t0, t1;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &p));
  if (!p->sample) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSGetPrevTime(ts, &t0));
  PetscCall(TSGetTime(ts, &t1));
  for (PetscReal s : {0.2, 0.5, 0.8}) {
    const PetscReal t = t0 + s * (t1 - t0);
    PetscReal       ue[2];
    PetscCall(TSInterpolate(ts, t, p->X));
    p->Exact(t, ue);
    PetscCall(VecGetArrayRead(p->X, &x));
    for (int i = 0; i < 2; i++) p->interp_err = PetscMax(p->interp_err, std::fabs(PetscRealPart(x[i]) - ue[i]));
    PetscCall(VecRestoreArrayRead(p->X, &x));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct Result {
  PetscReal t, u[2], err_max, err_scaled, wlte;
  PetscInt  steps, rejects, jac, newton, solves, nf, nj;
};

struct RunSpec {
  const char *adapt    = TSADAPTBASIC;
  PetscReal   dt       = 1e-3;
  PetscReal   tf       = 1;
  PetscReal   tol      = 1e-6;
  PetscInt    max_step = 1000000;
  PetscBool   rhs_form = PETSC_FALSE;
  PetscReal   reuse    = -1; /* >= 0: TSRadauIIASetJacobianReuse() before TSSetFromOptions() */
};

PetscErrorCode Run(Problem &p, const RunSpec &spec, Result *res)
{
  TS                 ts;
  Vec                U;
  Mat                J;
  TSConvergedReason  reason;
  const PetscScalar *u;
  PetscReal          u0[2];

  PetscFunctionBeginUser;
  p.nf = p.nj  = 0;
  p.interp_err = 0;
  p.Initial(u0);
  PetscCall(turgor_test::CreateSeqVec(2, u0, &U));
  PetscCall(VecDuplicate(U, &p.X));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, NULL, &J));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetApplicationContext(ts, &p));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  if (spec.rhs_form) {
    PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &p));
    PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &p));
  } else {
    PetscCall(TSSetIFunction(ts, NULL, IFunction, &p));
    PetscCall(TSSetIJacobian(ts, J, J, IJacobian, &p));
  }
  if (p.domain == Domain::callback) PetscCall(TSSetFunctionDomainError(ts, DomainCheck));
  PetscCall(TSSetTime(ts, 0));
  PetscCall(TSSetTimeStep(ts, spec.dt));
  PetscCall(TSSetMaxTime(ts, spec.tf));
  PetscCall(TSSetMaxSteps(ts, spec.max_step));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, spec.tol, NULL, spec.tol, NULL));
  PetscCall(TSSetPostStep(ts, SampleInterior));
  if (spec.reuse >= 0) PetscCall(TSRadauIIASetJacobianReuse(ts, spec.reuse));
  {
    /* command-line options may change the adaptive runs, but fixed steps stay fixed */
    TSAdapt   adapt;
    PetscBool fixed;
    PetscCall(TSGetAdapt(ts, &adapt));
    PetscCall(TSAdaptSetType(adapt, spec.adapt));
    PetscCall(TSSetFromOptions(ts));
    PetscCall(PetscStrcmp(spec.adapt, TSADAPTNONE, &fixed));
    if (fixed) PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  }
  PetscCall(TSSolve(ts, U));
  PetscCall(TSGetConvergedReason(ts, &reason));
  TG_CHECK(reason > 0, "TSSolve did not converge: %s", TSConvergedReasons[reason]);
  PetscCall(TSGetTime(ts, &res->t));
  PetscCall(TSGetStepNumber(ts, &res->steps));
  PetscCall(TSGetStepRejections(ts, &res->rejects));
  PetscCall(TSRadauIIAGetCounters(ts, &res->jac, &res->newton, &res->solves));
  res->wlte = -1;
  if (spec.max_step == 1) {
    PetscInt order;
    PetscCall(TSEvaluateWLTE(ts, NORM_2, &order, &res->wlte));
    TG_CHECK(order == 4, "the error estimate must report order 4 (local error O(h^4)), got %" PetscInt_FMT, order);
  }
  res->nf = p.nf;
  res->nj = p.nj;
  {
    PetscReal ue[2];
    p.Exact(res->t, ue);
    PetscCall(VecGetArrayRead(U, &u));
    res->err_max = res->err_scaled = 0;
    for (int i = 0; i < 2; i++) {
      res->u[i]       = PetscRealPart(u[i]);
      res->err_max    = PetscMax(res->err_max, std::fabs(res->u[i] - ue[i]));
      res->err_scaled = PetscMax(res->err_scaled, std::fabs(res->u[i] - ue[i]) / (spec.tol + spec.tol * std::fabs(ue[i])));
    }
    PetscCall(VecRestoreArrayRead(U, &u));
  }
  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&p.X));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PrintRun(const char *what, const Result &r)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "%s: t = %g, steps %" PetscInt_FMT ", rejected %" PetscInt_FMT ", Jacobian evals %" PetscInt_FMT " (callback %" PetscInt_FMT
                        "), Newton its %" PetscInt_FMT ", linear solves %" PetscInt_FMT ", F evals %" PetscInt_FMT ", error %.3e (%.3g x tol)\n",
                        what, (double)r.t, r.steps, r.rejects, r.jac, r.nj, r.newton, r.solves, r.nf, (double)r.err_max, (double)r.err_scaled));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (a) */
PetscErrorCode CheckTableau()
{
  TSRadauIIATableau t;
  const PetscReal   s6 = std::sqrt(6.0);

  PetscFunctionBeginUser;
  PetscCall(TSRadauIIAGetTableau(&t));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(a) c = (%.16f, %.16f, %g); gamma = %.15f, alpha = %.15f, beta = %.15f, gamma0 = %.15f\n", (double)t.c[0],
                        (double)t.c[1], (double)t.c[2], (double)t.gamma, (double)t.alpha, (double)t.beta, (double)t.gamma0));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    e = (%.15f, %.15f, %.15f)\n", (double)t.e[0], (double)t.e[1], (double)t.e[2]));
  /* Radau right points: zeros of d^2/dx^2 [x^2 (x-1)^3] = 20x^3 - 36x^2 + 18x - 2 */
  for (int i = 0; i < 3; i++) {
    const PetscReal c = t.c[i];
    TG_CHECK(std::fabs(((20 * c - 36) * c + 18) * c - 2) < 1e-13, "c[%d] = %g is not a Radau point", i, (double)c);
  }
  /* A by collocation: a_ij = integral over [0, c_i] of the Lagrange polynomial l_j */
  PetscReal maxdA = 0;
  for (int j = 0; j < 3; j++) {
    const int       m = (j + 1) % 3, n = (j + 2) % 3;
    const PetscReal d = (t.c[j] - t.c[m]) * (t.c[j] - t.c[n]);
    for (int i = 0; i < 3; i++) {
      const PetscReal x = t.c[i], integral = (x * x * x / 3 - (t.c[m] + t.c[n]) * x * x / 2 + t.c[m] * t.c[n] * x) / d;
      maxdA = PetscMax(maxdA, std::fabs(integral - t.A[i][j]));
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    A against collocation integrals: max difference %.2e\n", (double)maxdA));
  TG_CHECK(maxdA < 1e-14, "A differs from the collocation integrals by %g", (double)maxdA);
  /* B(5) and C(3) */
  PetscReal maxB = 0, maxC = 0;
  for (int k = 1; k <= 5; k++) {
    PetscReal s = 0;
    for (int i = 0; i < 3; i++) s += t.b[i] * std::pow(t.c[i], k - 1);
    maxB = PetscMax(maxB, std::fabs(s - 1.0 / k));
  }
  for (int k = 1; k <= 3; k++)
    for (int i = 0; i < 3; i++) {
      PetscReal s = 0;
      for (int j = 0; j < 3; j++) s += t.A[i][j] * std::pow(t.c[j], k - 1);
      maxC = PetscMax(maxC, std::fabs(s - std::pow(t.c[i], k) / k));
    }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    order conditions: B(5) residual %.2e, C(3) residual %.2e\n", (double)maxB, (double)maxC));
  TG_CHECK(maxB < 1e-14 && maxC < 1e-14, "B(5) or C(3) fails");
  /* Ainv A = I, T Tinv = I, Ainv T = T Lambda with Lambda = [[gamma,0,0],[0,alpha,beta],[0,-beta,alpha]] */
  const PetscReal Lam[3][3] = {
    {t.gamma, 0,       0      },
    {0,       t.alpha, t.beta },
    {0,       -t.beta, t.alpha}
  };
  PetscReal dI = 0, dT = 0, dL = 0, dLam = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      PetscReal s1 = 0, s2 = 0, s3 = 0, s4 = 0;
      for (int k = 0; k < 3; k++) {
        s1 += t.Ainv[i][k] * t.A[k][j];
        s2 += t.T[i][k] * t.Tinv[k][j];
        s3 += t.Ainv[i][k] * t.T[k][j];
        s4 += t.T[i][k] * Lam[k][j];
      }
      dI   = PetscMax(dI, std::fabs(s1 - (i == j)));
      dT   = PetscMax(dT, std::fabs(s2 - (i == j)));
      dL   = PetscMax(dL, std::fabs(s3 - s4));
      dLam = PetscMax(dLam, std::fabs(t.Lambda[i][j] - Lam[i][j]));
    }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    |Ainv A - I| %.2e, |T Tinv - I| %.2e, |Ainv T - T Lambda| %.2e, |Lambda - block form| %.2e\n", (double)dI,
                        (double)dT, (double)dL, (double)dLam));
  TG_CHECK(dI < 1e-12 && dT < 1e-12 && dL < 1e-12 && dLam < 1e-12, "the eigen-decomposition of Ainv is wrong");
  /* eigenvalues of Ainv are the zeros of the Pade(2,3) denominator 1 - 3z/5 + 3z^2/20 - z^3/60 */
  for (std::complex<PetscReal> z : {std::complex<PetscReal>(t.gamma, 0), std::complex<PetscReal>(t.alpha, t.beta)}) {
    const std::complex<PetscReal> q = 1.0 - 3.0 * z / 5.0 + 3.0 * z * z / 20.0 - z * z * z / 60.0;
    TG_CHECK(std::abs(q) < 1e-13, "eigenvalue (%g, %g) is not a pole of the stability function (|Q| = %g)", (double)z.real(), (double)z.imag(),
             (double)std::abs(q));
  }
  TG_CHECK_CLOSE(t.gamma0 * t.gamma, 1, 1e-15, 1, "gamma0 = 1/gamma");
  /* the error constants in closed form, and the embedded quadrature they imply */
  const PetscReal eref[3] = {t.gamma0 * (-13 - 7 * s6) / 3, t.gamma0 * (-13 + 7 * s6) / 3, -t.gamma0 / 3};
  for (int i = 0; i < 3; i++) TG_CHECK_CLOSE(t.e[i], eref[i], 1e-13, 1e-3, "error constant e_i");
  PetscReal bhat[3], cond[4] = {t.gamma0, 0, 0, 0};
  for (int j = 0; j < 3; j++) {
    bhat[j] = t.b[j];
    for (int i = 0; i < 3; i++) bhat[j] += t.e[i] * t.A[i][j];
  }
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) cond[k] += bhat[i] * std::pow(t.c[i], k);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "    embedded quadrature (weight gamma0 at 0): moments %.15f %.15f %.15f %.15f (exact 1, 1/2, 1/3; 1/4 must fail)\n",
                        (double)cond[0], (double)cond[1], (double)cond[2], (double)cond[3]));
  TG_CHECK(std::fabs(cond[0] - 1) < 1e-14 && std::fabs(cond[1] - 0.5) < 1e-14 && std::fabs(cond[2] - 1.0 / 3) < 1e-14, "the embedded method is not of order 3");
  TG_CHECK(std::fabs(cond[3] - 0.25) > 1e-3, "the embedded method is of order 4: the estimate would vanish");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TSRollBack (as TSEvent uses it): the state returns exactly, and the step is retried without a new Jacobian */
PetscErrorCode CheckRollBack()
{
  Problem   p;
  TS        ts;
  Vec       U, U2, U3;
  Mat       J;
  PetscReal t, u0[2], d2, d3;
  PetscInt  jac_before, jac_after;
  PetscFunctionBeginUser;
  p.Initial(u0);
  PetscCall(turgor_test::CreateSeqVec(2, u0, &U));
  PetscCall(VecDuplicate(U, &U2));
  PetscCall(VecDuplicate(U, &U3));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, NULL, &J));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  PetscCall(TSSetIFunction(ts, NULL, IFunction, &p));
  PetscCall(TSSetIJacobian(ts, J, J, IJacobian, &p));
  PetscCall(TSSetTimeStep(ts, 0.1));
  PetscCall(TSSetMaxTime(ts, 10));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, 1e-10, NULL, 1e-10, NULL));
  {
    TSAdapt adapt;
    PetscCall(TSGetAdapt(ts, &adapt));
    PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  }
  PetscCall(TSSetSolution(ts, U));
  PetscCall(TSSetUp(ts));
  PetscCall(TSStep(ts));
  PetscCall(TSStep(ts));
  PetscCall(VecCopy(U, U2));
  PetscCall(TSStep(ts));
  PetscCall(VecCopy(U, U3));
  PetscCall(TSRadauIIAGetCounters(ts, &jac_before, NULL, NULL));
  PetscCall(TSRollBack(ts));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(VecAXPY(U2, -1.0, U));
  PetscCall(VecNorm(U2, NORM_INFINITY, &d2));
  TG_CHECK(std::fabs(t - 0.2) < 1e-14 && d2 == 0, "TSRollBack: t = %g, |U - U(0.2)| = %g", (double)t, (double)d2);
  PetscCall(TSStep(ts));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSRadauIIAGetCounters(ts, &jac_after, NULL, NULL));
  PetscCall(VecAXPY(U3, -1.0, U));
  PetscCall(VecNorm(U3, NORM_INFINITY, &d3));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "    TSRollBack: back to t = 0.2 exactly; the retried step differs by %.2e; Jacobian evaluations %" PetscInt_FMT " -> %" PetscInt_FMT
                        "\n",
                        (double)d3, jac_before, jac_after));
  TG_CHECK(std::fabs(t - 0.3) < 1e-14 && d3 < 1e-13, "the retried step: t = %g, difference %g", (double)t, (double)d3);
  TG_CHECK(jac_after == jac_before, "a rolled-back step must not need a new Jacobian");
  PetscCall(TSInterpolate(ts, 0.25, U2));
  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&U2));
  PetscCall(VecDestroy(&U3));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (f) u_t = u_xx on (0, 1), u = 0 at both ends, linear elements on n interior nodes: M u' = -K u with
   M = (h/6) tridiag(1, 4, 1), K = (1/h) tridiag(-1, 2, -1). sin(k pi x_j) are generalised eigenvectors
   with eigenvalues 6 (1 - cos(k pi h)) / (h^2 (2 + cos(k pi h))), so the semi-discrete solution from
   sin(pi x) + 0.5 sin(20 pi x) is known exactly. */
struct Heat {
  Mat      M, K;
  PetscInt nf = 0, nj = 0;
};

PetscErrorCode HeatIFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx)
{
  Heat *p = (Heat *)ctx;
  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(MatMult(p->K, U, F));
  PetscCall(MatMultAdd(p->M, Udot, F, F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HeatIJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  Heat *p = (Heat *)ctx;
  PetscFunctionBeginUser;
  p->nj++;
  PetscCall(MatCopy(p->K, B, SAME_NONZERO_PATTERN));
  PetscCall(MatAXPY(B, shift, p->M, SAME_NONZERO_PATTERN));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode HeatRun()
{
  const PetscInt    n = 200, modes[2] = {1, 20};
  const PetscReal   h = 1.0 / (n + 1), amp[2] = {1, 0.5}, tf = 0.05, tol = 1e-6;
  Heat              p;
  TS                ts;
  Vec               U, E;
  Mat               J;
  PetscInt          rs, re, steps, rejects, jac, newton, solves;
  PetscReal         err, nrm;
  PetscMPIInt       size;
  TSConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, NULL, 2, NULL, &p.M));
  PetscCall(MatGetOwnershipRange(p.M, &rs, &re));
  for (PetscInt i = rs; i < re; i++)
    for (PetscInt j = PetscMax(0, i - 1); j <= PetscMin(n - 1, i + 1); j++) PetscCall(MatSetValue(p.M, i, j, i == j ? 4 * h / 6 : h / 6, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(p.M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(p.M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatDuplicate(p.M, MAT_DO_NOT_COPY_VALUES, &p.K));
  for (PetscInt i = rs; i < re; i++)
    for (PetscInt j = PetscMax(0, i - 1); j <= PetscMin(n - 1, i + 1); j++) PetscCall(MatSetValue(p.K, i, j, i == j ? 2 / h : -1 / h, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(p.K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(p.K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatDuplicate(p.M, MAT_COPY_VALUES, &J));
  PetscCall(MatCreateVecs(p.M, &U, &E));
  for (PetscInt i = rs; i < re; i++) {
    PetscReal u0 = 0, ue = 0;
    for (int m = 0; m < 2; m++) {
      const PetscReal kph = modes[m] * PETSC_PI * h, lam = 6 * (1 - std::cos(kph)) / (h * h * (2 + std::cos(kph))),
                      phi = std::sin(modes[m] * PETSC_PI * (i + 1) * h);
      u0 += amp[m] * phi;
      ue += amp[m] * std::exp(-lam * tf) * phi;
    }
    PetscCall(VecSetValue(U, i, u0, INSERT_VALUES));
    PetscCall(VecSetValue(E, i, ue, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(VecAssemblyBegin(E));
  PetscCall(VecAssemblyEnd(E));
  PetscCall(TSCreate(PETSC_COMM_WORLD, &ts));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  PetscCall(TSSetIFunction(ts, NULL, HeatIFunction, &p));
  PetscCall(TSSetIJacobian(ts, J, J, HeatIJacobian, &p));
  PetscCall(TSSetMaxTime(ts, tf));
  PetscCall(TSSetTimeStep(ts, 1e-5));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, tol, NULL, tol, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, U));
  PetscCall(TSGetConvergedReason(ts, &reason));
  TG_CHECK(reason > 0, "heat: TSSolve did not converge: %s", TSConvergedReasons[reason]);
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetStepRejections(ts, &rejects));
  PetscCall(TSRadauIIAGetCounters(ts, &jac, &newton, &solves));
  PetscCall(VecNorm(E, NORM_INFINITY, &nrm));
  PetscCall(VecAXPY(E, -1.0, U));
  PetscCall(VecNorm(E, NORM_INFINITY, &err));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "(f) heat equation, %" PetscInt_FMT " nodes on %d rank(s), t = %g, rtol = atol = %g: steps %" PetscInt_FMT ", rejected %" PetscInt_FMT
                        ", Jacobian evals %" PetscInt_FMT ", Newton its %" PetscInt_FMT ", linear solves %" PetscInt_FMT ", max error %.3e (%.3g x tol)\n",
                        n, size, (double)tf, (double)tol, steps, rejects, jac, newton, solves, (double)err, (double)(err / (tol + tol * nrm))));
  TG_CHECK(err <= 10 * (tol + tol * nrm), "heat: error %g", (double)err);
  TG_CHECK(jac == 2, "heat: a linear problem needs 2 Jacobian evaluations, got %" PetscInt_FMT, jac);
  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(MatDestroy(&p.M));
  PetscCall(MatDestroy(&p.K));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&E));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A TS whose options come from a private database holding only "-ts_type <type>", so that neither
   the command line nor other checks can change what is tested. */
PetscErrorCode CreateTSFromTypeOption(const char *type, PetscOptions *opts, TS *ts)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsCreate(opts));
  PetscCall(PetscOptionsSetValue(*opts, "-ts_type", type));
  PetscCall(TSCreate(PETSC_COMM_SELF, ts));
  PetscCall(PetscObjectSetOptions((PetscObject)*ts, *opts));
  PetscCall(TSSetFromOptions(*ts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (g) */
PetscErrorCode CheckRegistration()
{
  TS           ts;
  PetscOptions opts;
  PetscBool    same;
  PetscInt     jac = -1;
  void (*counters)(void);

  PetscFunctionBeginUser;
  PetscCall(CreateTSFromTypeOption(TSRADAUIIA, &opts, &ts));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRADAUIIA, &same));
  TG_CHECK(same, "-ts_type " TSRADAUIIA " did not give a TS of that type");
  PetscCall(TSRadauIIAGetCounters(ts, &jac, NULL, NULL));
  TG_CHECK(jac == 0, "a new radauiia TS has %" PetscInt_FMT " Jacobian evaluations", jac);
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscOptionsDestroy(&opts));

  PetscCall(CreateTSFromTypeOption("radau5", &opts, &ts));
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, "TSRadauIIAGetCounters_C", &counters));
#if !defined(PETSC_HAVE_RADAU5)
  /* the alias: the same constructor under the former name */
  TG_CHECK(counters, "-ts_type radau5 must give turgor's Radau IIA where PETSc has no RADAU5");
  jac = -1;
  PetscCall(TSRadauIIAGetCounters(ts, &jac, NULL, NULL));
  TG_CHECK(jac == 0, "radau5 alias: %" PetscInt_FMT " Jacobian evaluations on a new TS", jac);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(g) -ts_type radauiia and -ts_type radau5 (alias: PETSc has no RADAU5) both give turgor's Radau IIA\n"));
#else
  /* PETSc's own TSRADAU5 must have been left in place */
  TG_CHECK(!counters, "-ts_type radau5 must stay PETSc's TSRADAU5 when PETSc has it");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(g) -ts_type radauiia gives turgor's Radau IIA; radau5 is PETSc's own TSRADAU5\n"));
#endif
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscOptionsDestroy(&opts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (h) */
PetscErrorCode CheckSetters()
{
  TS             ts;
  PetscOptions   opts;
  PetscReal      theta, kappa;
  PetscInt       max_it;
  PetscErrorCode ierr;
  void (*method)(void);

  PetscFunctionBeginUser;
  /* a private, empty options database: the command line must not change what is checked here */
  PetscCall(PetscOptionsCreate(&opts));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(PetscObjectSetOptions((PetscObject)ts, opts));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  PetscCall(TSRadauIIAGetJacobianReuse(ts, &theta));
  PetscCall(TSRadauIIAGetNewtonTolerance(ts, &kappa));
  PetscCall(TSRadauIIAGetNewtonMaxIterations(ts, &max_it));
  {
    /* the Newton tolerance defaults to RADAU5's rule for the TS's tolerances (PETSc's default rtol = 1e-4 here):
       max(10 u/rtol, min(0.03, sqrt(0.1 rtol^(2/3)))), and follows them */
    PetscReal atol, rtol, kappa8;
    PetscCall(TSGetTolerances(ts, &atol, NULL, &rtol, NULL));
    const PetscReal rule = PetscMax(10 * PETSC_MACHINE_EPSILON / rtol, PetscMin(0.03, PetscSqrtReal(0.1 * PetscPowReal(rtol, 2.0 / 3))));
    TG_CHECK(theta == 1e-3 && std::fabs(kappa - rule) <= 1e-15 * rule && max_it == 7,
             "defaults: Jacobian reuse %g, Newton tolerance %g, Newton iterations %" PetscInt_FMT " (expected 0.001, %g (RADAU5's rule at rtol %g), 7)",
             (double)theta, (double)kappa, max_it, (double)rule, (double)rtol);
    PetscCall(TSSetTolerances(ts, 1e-8, NULL, 1e-8, NULL));
    PetscCall(TSRadauIIAGetNewtonTolerance(ts, &kappa8));
    TG_CHECK(std::fabs(kappa8 - PetscSqrtReal(0.1 * PetscPowReal(1e-8, 2.0 / 3))) < 1e-15, "RADAU5's rule at rtol = 1e-8 gives %g", (double)kappa8);
    PetscCall(TSSetTolerances(ts, atol, NULL, rtol, NULL));
  }
  PetscCall(TSRadauIIASetJacobianReuse(ts, 0.1));
  PetscCall(TSRadauIIASetNewtonTolerance(ts, 0.05));
  PetscCall(TSRadauIIASetNewtonMaxIterations(ts, 10));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSRadauIIAGetJacobianReuse(ts, &theta));
  PetscCall(TSRadauIIAGetNewtonTolerance(ts, &kappa));
  PetscCall(TSRadauIIAGetNewtonMaxIterations(ts, &max_it));
  TG_CHECK(theta == 0.1 && kappa == 0.05 && max_it == 10,
           "set before TSSetFromOptions(): Jacobian reuse %g, Newton tolerance %g, Newton iterations %" PetscInt_FMT " (expected 0.1, 0.05, 10)", (double)theta,
           (double)kappa, max_it);
  /* PETSC_DEFAULT returns to the rule */
  PetscCall(TSRadauIIASetNewtonTolerance(ts, PETSC_DEFAULT));
  {
    PetscReal k2;
    PetscCall(TSRadauIIAGetNewtonTolerance(ts, &k2));
    TG_CHECK(k2 != 0.05 && k2 > 0 && k2 < 0.03 + 1e-16, "TSRadauIIASetNewtonTolerance(PETSC_DEFAULT) left %g", (double)k2);
    PetscCall(TSRadauIIASetNewtonTolerance(ts, 0.05));
  }
  /* an option given for the TS still wins over the value set in code */
  PetscCall(PetscOptionsSetValue(opts, "-ts_radauiia_jacobian_reuse", "0.2"));
  PetscCall(TSRadauIIASetJacobianReuse(ts, 0.1));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSRadauIIAGetJacobianReuse(ts, &theta));
  TG_CHECK(theta == 0.2, "-ts_radauiia_jacobian_reuse 0.2 must override TSRadauIIASetJacobianReuse(0.1), got %g", (double)theta);
  /* out of range is an error */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = TSRadauIIASetJacobianReuse(ts, 1.5);
  PetscCall(PetscPopErrorHandler());
  TG_CHECK(ierr == PETSC_ERR_ARG_OUTOFRANGE, "TSRadauIIASetJacobianReuse(1.5) returned %d, expected PETSC_ERR_ARG_OUTOFRANGE", (int)ierr);
  PetscCall(TSRadauIIAGetJacobianReuse(ts, &theta));
  TG_CHECK(theta == 0.2, "a rejected value changed the Jacobian reuse to %g", (double)theta);
  /* another type: a TS changed from radauiia, and one created as rk, ignore the setters */
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRadauIIASetJacobianReuse(ts, 0.5));
  PetscCall(TSRadauIIASetNewtonTolerance(ts, 0.5));
  PetscCall(TSRadauIIASetNewtonMaxIterations(ts, 3));
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, "TSRadauIIASetJacobianReuse_C", &method));
  TG_CHECK(!method, "a TS changed to rk still has TSRadauIIASetJacobianReuse_C");
  PetscCall(TSDestroy(&ts));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(PetscObjectSetOptions((PetscObject)ts, opts));
  PetscCall(TSSetType(ts, TSRK));
  PetscCall(TSRadauIIASetJacobianReuse(ts, 0.5));
  PetscCall(TSRadauIIASetJacobianReuse(ts, 1.5)); /* not even checked: the value means nothing to rk */
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, "TSRadauIIAGetJacobianReuse_C", &method));
  TG_CHECK(!method, "a TSRK has TSRadauIIAGetJacobianReuse_C");
  PetscCall(TSDestroy(&ts));
  PetscCall(PetscOptionsDestroy(&opts));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(h) TSRadauIIASetJacobianReuse/NewtonTolerance/NewtonMaxIterations before TSSetFromOptions(): the values are used "
                                         "(0.1, 0.05, 10); the Newton tolerance defaults to RADAU5's rule and PETSC_DEFAULT restores it; "
                                         "-ts_radauiia_jacobian_reuse 0.2 overrides 0.1; 1.5 is rejected; no-op on rk\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscMPIInt size;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  PetscCall(TurgorTSRegisterAll()); /* idempotent */
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(HeatRun());
  if (size > 1) { /* (a)-(e) are serial */
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_radau_iia: all checks passed\n"));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(CheckTableau());
  PetscCall(CheckRegistration());
  PetscCall(CheckSetters());

  /* (b) fixed steps on the oscillator with mass matrix M */
  {
    Problem   p;
    PetscReal e[5], ie[5];
    PetscInt  N[5] = {5, 10, 20, 40, 80};
    PetscCall(
      PetscPrintf(PETSC_COMM_SELF, "(b) fixed steps, M U' = L U, t in [0, 2], error at t = 2 (max norm); (d) TSInterpolate at 0.2, 0.5, 0.8 of every step\n"));
    for (int k = 0; k < 5; k++) {
      RunSpec s;
      Result  r;
      s.adapt  = TSADAPTNONE;
      s.dt     = 2.0 / N[k];
      s.tf     = 2;
      s.tol    = 1e-10;
      p.sample = PETSC_TRUE;
      PetscCall(Run(p, s, &r));
      e[k]  = r.err_max;
      ie[k] = p.interp_err;
      TG_CHECK(r.steps == N[k] && std::fabs(r.t - 2) < 1e-12, "fixed-step run: %" PetscInt_FMT " steps to t = %g", r.steps, (double)r.t);
      TG_CHECK(r.jac == 2 && r.nj == 2, "a linear problem needs exactly the 2 IJacobian calls that recover M, got %" PetscInt_FMT, r.jac);
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "    N = %3" PetscInt_FMT ", h = %.4f: error %.3e, interpolation error %.3e; Jacobian evals %" PetscInt_FMT
                            ", Newton its %" PetscInt_FMT "\n",
                            N[k], (double)s.dt, (double)e[k], (double)ie[k], r.jac, r.newton));
      if (k)
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "        observed order %.3f, dense output order %.3f\n", (double)std::log2(e[k - 1] / e[k]),
                              (double)std::log2(ie[k - 1] / ie[k])));
    }
    const PetscReal order = std::log2(e[3] / e[4]), order2 = std::log2(e[2] / e[3]), dense = std::log2(ie[3] / ie[4]);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "    measured order %.3f (N 40 -> 80), %.3f (N 20 -> 40); dense output %.3f\n", (double)order, (double)order2,
                          (double)dense));
    TG_CHECK(order >= 4.5 && order2 >= 4.5, "order %g / %g below 4.5", (double)order, (double)order2);
    TG_CHECK(order <= 6, "order %g suspiciously high", (double)order);
    TG_CHECK(dense >= 3.5, "dense output order %g below 3.5 (expected 4: the collocation polynomial is accurate to O(h^4))", (double)dense);

    /* the error estimate after one step of size h: O(h^4) */
    PetscReal w[4];
    for (int k = 0; k < 4; k++) {
      RunSpec s;
      Result  r;
      s.adapt    = TSADAPTNONE;
      s.dt       = 0.2 / (1 << k);
      s.tf       = 10;
      s.max_step = 1;
      s.tol      = 1e-10;
      p.sample   = PETSC_FALSE;
      PetscCall(Run(p, s, &r));
      w[k] = r.wlte;
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "    one step h = %.4f: weighted error estimate %.4e\n", (double)s.dt, (double)w[k]));
      if (k) PetscCall(PetscPrintf(PETSC_COMM_SELF, "        estimate order %.3f\n", (double)std::log2(w[k - 1] / w[k])));
    }
    const PetscReal eorder = std::log2(w[2] / w[3]);
    TG_CHECK(eorder > 3.5 && eorder < 4.5, "the error estimate scales as h^%g, expected h^4", (double)eorder);
    PetscCall(CheckRollBack());
  }

  /* (c) adaptive, stiff nonlinear problem, rtol = atol = 1e-6 */
  {
    Problem p;
    RunSpec s;
    Result  r, rr;
    p.kind = Kind::stiff;
    s.tf   = 3;
    s.dt   = 1e-6;
    s.tol  = 1e-6;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "(c) adaptive, u1' = -1e5 (u1 - sin t) + cos t, 2 u2' = -2 u2^2 on [0, 3], rtol = atol = 1e-6\n"));
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("    IFunction form", r));
    TG_CHECK(r.err_scaled <= 10, "error %g x tolerance", (double)r.err_scaled);
    TG_CHECK(r.jac < r.steps, "Jacobian reuse: %" PetscInt_FMT " Jacobian evaluations for %" PetscInt_FMT " steps", r.jac, r.steps);
    {
      /* (h) a reuse threshold set with TSRadauIIASetJacobianReuse() reaches the solver (unless the
         command line sets its own) */
      PetscBool given;
      Result    r1;
      RunSpec   s1 = s;
      s1.reuse     = 0.1;
      PetscCall(PetscOptionsHasName(NULL, NULL, "-ts_radauiia_jacobian_reuse", &given));
      PetscCall(Run(p, s1, &r1));
      PetscCall(PrintRun("    IFunction form, TSRadauIIASetJacobianReuse(ts, 0.1)", r1));
      TG_CHECK(r1.err_scaled <= 10, "error %g x tolerance", (double)r1.err_scaled);
      if (!given)
        TG_CHECK(r1.jac < r.jac,
                 "Jacobian reuse 0.1 set in code: %" PetscInt_FMT " Jacobian evaluations, not fewer than the %" PetscInt_FMT " of the default 0.001", r1.jac,
                 r.jac);
    }
    s.rhs_form = PETSC_TRUE;
    PetscCall(Run(p, s, &rr));
    PetscCall(PrintRun("    RHS form (M = I)", rr));
    TG_CHECK(rr.err_scaled <= 10, "error %g x tolerance", (double)rr.err_scaled);
    /* a large first step forces error-test rejections */
    s.rhs_form = PETSC_FALSE;
    s.dt       = 0.5;
    PetscCall(Run(p, s, &r));
    PetscCall(PrintRun("    IFunction form, first step 0.5", r));
    TG_CHECK(r.err_scaled <= 10, "error %g x tolerance", (double)r.err_scaled);
    TG_CHECK(r.rejects > 0, "a first step of 0.5 across a 1e-5 transient must be rejected");
  }

  /* (e) domain errors for stages beyond t_n + 0.05, starting with h = 1 */
  {
    const Domain      kinds[3] = {Domain::nan_values, Domain::callback, Domain::snes_flag};
    const char *const names[3] = {"IFunction returns NaN", "TSSetFunctionDomainError rejects", "SNESSetFunctionDomainError"};
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "(e) domain errors for stage times beyond t_n + 0.05 (oscillator, adaptive, first step 1, rtol = atol = 1e-6)\n"));
    for (int k = 0; k < 3; k++) {
      Problem p;
      RunSpec s;
      Result  r;
      char    what[128];
      p.domain = kinds[k];
      p.hlim   = 0.05;
      s.dt     = 1;
      s.tf     = 2;
      s.tol    = 1e-6;
      PetscCall(Run(p, s, &r));
      PetscCall(PetscSNPrintf(what, sizeof(what), "    %s", names[k]));
      PetscCall(PrintRun(what, r));
      TG_CHECK(std::fabs(r.t - 2) < 1e-12, "the solve stopped at t = %g", (double)r.t);
      TG_CHECK(r.rejects >= 3, "a first step of 1 must be rejected until h <= 0.05, got %" PetscInt_FMT " rejections", r.rejects);
      TG_CHECK(r.steps >= 40, "%" PetscInt_FMT " steps: steps beyond 0.05 were accepted", r.steps);
      TG_CHECK(r.err_scaled <= 10, "error %g x tolerance", (double)r.err_scaled);
      TG_CHECK(r.jac == 2, "domain errors must not trigger Jacobian evaluations on a linear problem: %" PetscInt_FMT, r.jac);
    }
  }

  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_radau_iia: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
