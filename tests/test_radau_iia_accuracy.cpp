static const char help[] = "Accuracy of the radauiia TS type against SciPy's Radau, and its round-off floor.\n"
                           "(a) HIRES (Test Set for IVP Solvers) and Van der Pol (mu = 1e3, scaled) at rtol = atol = 1e-4 .. 1e-8. The error\n"
                           "measured is the largest error of the dense output (TSInterpolate) at 50 sample times against the references in\n"
                           "tests/data; per tolerance tol its geometric mean over the runs at 0.8, 0.9, 1, 1.1, 1.25 x tol must be within 3x\n"
                           "that of SciPy's Radau (scipy.integrate.solve_ivp), measured by bench/radau_vs_scipy.py and stored here. The error at\n"
                           "t_end against the Test Set's reference is printed too: for HIRES it jumps by up to 100x between neighbouring\n"
                           "tolerances, for SciPy as for radauiia, and is not checked.\n"
                           "(b) tolerances below the round-off floor of the solution (rtol = atol = 1e-20; rtol = 0, atol = 1e-14; a Newton\n"
                           "tolerance of 1e-12) end quickly with an error that names the tolerances and the floor, instead of up to hundreds of\n"
                           "thousands of rejected steps; with -ts_error_if_step_fails false as a failed TS instead.\n"
                           "Options: -acc_problem hires|vdp -acc_rtol r [-acc_atol a]: one run, printed, nothing checked (any -ts_ option applies);\n"
                           "-acc_check false: the tables of (a) without the checks; -acc_trace: t and U after every step.\n";
#include "test_util.h"
#include "ode_util.h"
#include <turgor/ts/radau_iia.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

char      data_dir[PETSC_MAX_PATH_LEN] = TURGOR_TEST_DATA_DIR; /* -acc_data DIR */
PetscBool check                        = PETSC_TRUE;           /* -acc_check false: print the tables, check nothing */
PetscBool trace                        = PETSC_FALSE;          /* -acc_trace: print t and the solution after every step */

PetscErrorCode Trace(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  const PetscScalar *u;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(U, &n));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "trace %.17g", (double)t));
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscPrintf(PETSC_COMM_SELF, " %.17g", (double)PetscRealPart(u[i])));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n"));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* SciPy 1.10.1 (NumPy 1.24.2, Python 3.11.2; Debian 12's python3-scipy), measured by
   `/usr/bin/python3 bench/radau_vs_scipy.py --cxx`. Per rtol = atol = tol: the error at t_end against the
   Test Set's reference; the largest error of the dense output at the 50 sample times against
   tests/data/radau_iia_<problem>.txt (both absolute, max norm); the geometric mean of the latter over
   the runs at 0.8, 0.9, 1, 1.1, 1.25 x tol (the band); f-evals (nfev) of the run at tol. */
struct ScipyFigure {
  PetscReal tol, err_end, err_sampled, band;
  PetscInt  nfev;
};
const ScipyFigure kScipy_hires[] = {
  {1e-04, 1.952e-05, 1.952e-05, 2.062e-05, 386 },
  {1e-05, 3.889e-07, 1.387e-06, 1.996e-06, 621 },
  {1e-06, 5.490e-08, 4.994e-07, 4.395e-07, 839 },
  {1e-07, 1.853e-10, 8.911e-08, 8.277e-08, 1247},
  {1e-08, 3.012e-10, 3.170e-09, 5.575e-09, 2019},
};
const ScipyFigure kScipy_vdp[] = {
  {1e-04, 1.965e-06, 2.390e-04, 2.140e-04, 2846 },
  {1e-05, 1.654e-07, 2.944e-05, 2.077e-05, 4509 },
  {1e-06, 6.653e-09, 2.548e-06, 1.901e-06, 7342 },
  {1e-07, 4.445e-10, 1.409e-07, 1.659e-07, 12616},
  {1e-08, 2.631e-11, 1.223e-08, 1.295e-08, 21953},
};
const PetscReal kBand[5] = {0.8, 0.9, 1.0, 1.1, 1.25};

/* y' = f(t, y), given to the TS as F = y' - f(y) with IJacobian shift I - df/dy. */
struct Ode {
  const char            *name;
  PetscInt               n;
  PetscReal              tf, h0;
  std::vector<PetscReal> y0, ref;
  const ScipyFigure     *scipy;
  void (*f)(const PetscScalar *y, PetscScalar *f);
  void (*jac)(const PetscScalar *y, PetscScalar *J); /* dense, row-major */
  PetscInt nf = 0, nj = 0;
  /* reference at the sample times (tests/data/radau_iia_<name>.txt; ys row-major) and the sampling of a run */
  std::vector<PetscReal> ts, ys;
  PetscReal              sample_err  = 0;
  PetscInt               next_sample = 0;
  Vec                    X           = NULL;
};

/* HIRES (Test Set for IVP Solvers, Mazzia & Magherini, release 2.4): 8 equations, t in [0, 321.8122] */
void HiresF(const PetscScalar *y, PetscScalar *f)
{
  f[0] = -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
  f[1] = 1.71 * y[0] - 8.75 * y[1];
  f[2] = -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
  f[3] = 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
  f[4] = -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
  f[5] = -280 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
  f[6] = 280 * y[5] * y[7] - 1.81 * y[6];
  f[7] = -280 * y[5] * y[7] + 1.81 * y[6];
}

void HiresJac(const PetscScalar *y, PetscScalar *J)
{
  for (int i = 0; i < 64; i++) J[i] = 0;
  auto a = [&](int i, int j, PetscScalar v) { J[8 * i + j] = v; };
  a(0, 0, -1.71), a(0, 1, 0.43), a(0, 2, 8.32);
  a(1, 0, 1.71), a(1, 1, -8.75);
  a(2, 2, -10.03), a(2, 3, 0.43), a(2, 4, 0.035);
  a(3, 1, 8.32), a(3, 2, 1.71), a(3, 3, -1.12);
  a(4, 4, -1.745), a(4, 5, 0.43), a(4, 6, 0.43);
  a(5, 3, 0.69), a(5, 4, 1.71), a(5, 5, -0.43 - 280 * y[7]), a(5, 6, 0.69), a(5, 7, -280 * y[5]);
  a(6, 5, 280 * y[7]), a(6, 6, -1.81), a(6, 7, 280 * y[5]);
  a(7, 5, -280 * y[7]), a(7, 6, 1.81), a(7, 7, -280 * y[5]);
}

/* Van der Pol, mu = 1e3, scaled as in examples/van_der_pol.cpp (eps = 1/mu^2) */
const PetscReal kEps = 1e-6;
void            VdpF(const PetscScalar *y, PetscScalar *f)
{
  turgor_test::VanDerPol(kEps, y, f);
}

void VdpJac(const PetscScalar *y, PetscScalar *J)
{
  turgor_test::VanDerPolJacobian(kEps, y, J);
}

Ode Hires()
{
  Ode p;
  p.name  = "hires";
  p.n     = 8;
  p.tf    = 321.8122;
  p.h0    = 1e-6;
  p.y0    = {1, 0, 0, 0, 0, 0, 0, 0.0057};
  p.ref   = {0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4, 0.1175651343283149e-2,
             0.2386356198831331e-2, 0.6238968252742796e-2, 0.2849998395185769e-2, 0.2850001604814231e-2};
  p.scipy = kScipy_hires;
  p.f     = HiresF;
  p.jac   = HiresJac;
  return p;
}

/* the Test Set's VDPOL (mu = 1e3 on [0, 2000]) rescaled to [0, 2] */
Ode Vdp()
{
  Ode p;
  p.name  = "vdp";
  p.n     = 2;
  p.tf    = 2;
  p.h0    = 1e-6;
  p.y0    = {2, 0};
  p.ref   = {1.706167732170469, -0.8928097010248125};
  p.scipy = kScipy_vdp;
  p.f     = VdpF;
  p.jac   = VdpJac;
  return p;
}

PetscErrorCode IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx)
{
  Ode               *p = (Ode *)ctx;
  const PetscScalar *u, *ud;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArrayRead(Udot, &ud));
  PetscCall(VecGetArray(F, &f));
  p->f(u, f);
  for (PetscInt i = 0; i < p->n; i++) f[i] = ud[i] - f[i];
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Udot, &ud));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  Ode                     *p = (Ode *)ctx;
  const PetscScalar       *u;
  std::vector<PetscScalar> J(p->n * p->n);

  PetscFunctionBeginUser;
  p->nj++;
  PetscCall(VecGetArrayRead(U, &u));
  p->jac(u, J.data());
  PetscCall(VecRestoreArrayRead(U, &u));
  for (PetscInt i = 0; i < p->n; i++)
    for (PetscInt j = 0; j < p->n; j++) J[i * p->n + j] = (i == j ? shift : 0) - J[i * p->n + j];
  PetscCall(turgor_test::SetDenseMatrix(B, p->n, J.data()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* t y_1 .. y_n per line, '#' lines skipped */
PetscErrorCode LoadReference(Ode &p)
{
  char  path[PETSC_MAX_PATH_LEN], line[4096];
  FILE *f;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/radau_iia_%s.txt", data_dir, p.name));
  f = std::fopen(path, "r");
  TG_CHECK(f, "cannot open the reference %s (-acc_data DIR)", path);
  while (std::fgets(line, sizeof(line), f)) {
    char *c = line, *end;
    if (line[0] == '#') continue;
    for (PetscInt i = 0; i <= p.n; i++, c = end) {
      const double v = std::strtod(c, &end);
      TG_CHECK(end != c, "%s: a line with fewer than %" PetscInt_FMT " numbers", path, p.n + 1);
      if (i == 0) p.ts.push_back(v);
      else p.ys.push_back(v);
    }
  }
  std::fclose(f);
  TG_CHECK(!p.ts.empty() && std::fabs(p.ts.back() - p.tf) < 1e-12 * p.tf, "%s: the last sample must be at t = %g", path, (double)p.tf);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* after every step: the dense output (TSInterpolate) at the sample times inside it, against the reference */
PetscErrorCode Sample(TS ts)
{
  Ode               *p;
  PetscReal          t1;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &p));
  PetscCall(TSGetTime(ts, &t1));
  for (; p->next_sample < (PetscInt)p->ts.size() && p->ts[p->next_sample] <= t1 * (1 + 1e-14); p->next_sample++) {
    PetscCall(TSInterpolate(ts, PetscMin(p->ts[p->next_sample], t1), p->X));
    PetscCall(VecGetArrayRead(p->X, &x));
    for (PetscInt i = 0; i < p->n; i++) p->sample_err = PetscMax(p->sample_err, PetscAbsScalar(x[i] - p->ys[p->next_sample * p->n + i]));
    PetscCall(VecRestoreArrayRead(p->X, &x));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct Result {
  PetscErrorCode    ierr = 0;
  TSConvergedReason reason;
  PetscReal         t = 0, err = 0, sampled = 0, wall = 0; /* err: at t_end; sampled: the largest at the sample times */
  PetscInt          steps = 0, rejects = 0, newton_fail = 0, jac = 0, nf = 0;
  char              message[1024] = "";
};

/* One run at (rtol, atol). Errors raised inside TSSolve are returned in res->ierr (with their
   message) instead of aborting, so that (b) can check them. */
struct RunOptions {
  PetscBool error_if_fails = PETSC_TRUE;    /* TSSetErrorIfStepFails() */
  PetscReal newton_tol     = PETSC_DEFAULT; /* TSRadauIIASetNewtonTolerance() */
};

PetscErrorCode Run(Ode &p, PetscReal rtol, PetscReal atol, Result *res, const RunOptions &opt = RunOptions())
{
  TS                 ts;
  Vec                U;
  Mat                J;
  const PetscScalar *u;
  PetscLogDouble     t0, t1;

  PetscFunctionBeginUser;
  p.nf = p.nj   = 0;
  p.sample_err  = 0;
  p.next_sample = 0;
  PetscCall(turgor_test::CreateSeqVec(p.n, p.y0.data(), &U));
  PetscCall(VecDuplicate(U, &p.X));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, p.n, p.n, p.n, NULL, &J));
  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  PetscCall(TSSetApplicationContext(ts, &p));
  PetscCall(TSSetIFunction(ts, NULL, IFunction, &p));
  PetscCall(TSSetIJacobian(ts, J, J, IJacobian, &p));
  PetscCall(TSSetTime(ts, 0));
  PetscCall(TSSetTimeStep(ts, p.h0));
  PetscCall(TSSetMaxTime(ts, p.tf));
  PetscCall(TSSetMaxSteps(ts, 10000000));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, atol, NULL, rtol, NULL));
  PetscCall(TSSetPostStep(ts, Sample));
  PetscCall(TSSetErrorIfStepFails(ts, opt.error_if_fails));
  if (opt.newton_tol != PETSC_DEFAULT) PetscCall(TSRadauIIASetNewtonTolerance(ts, opt.newton_tol));
  if (trace) PetscCall(TSMonitorSet(ts, Trace, NULL, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(PetscTime(&t0));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  res->ierr = TSSolve(ts, U);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscTime(&t1));
  res->wall = t1 - t0;
  if (res->ierr) {
    const char *text;
    char       *specific;
    PetscCall(PetscErrorMessage(res->ierr, &text, &specific));
    PetscCall(PetscStrncpy(res->message, specific ? specific : text, sizeof(res->message)));
  }
  PetscCall(TSGetConvergedReason(ts, &res->reason));
  PetscCall(TSGetTime(ts, &res->t));
  PetscCall(TSGetStepNumber(ts, &res->steps));
  PetscCall(TSGetStepRejections(ts, &res->rejects));
  PetscCall(TSGetSNESFailures(ts, &res->newton_fail));
  res->jac     = p.nj;
  res->nf      = p.nf;
  res->sampled = p.next_sample == (PetscInt)p.ts.size() ? p.sample_err : PETSC_INFINITY;
  PetscCall(VecGetArrayRead(U, &u));
  res->err = 0;
  for (PetscInt i = 0; i < p.n; i++) res->err = PetscMax(res->err, PetscAbsScalar(u[i] - p.ref[i]));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&p.X));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PrintRun(const Ode &p, PetscReal rtol, PetscReal atol, const Result &r)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "%s rtol %g atol %g: %s at t = %g, steps %" PetscInt_FMT ", rejected %" PetscInt_FMT " (Newton %" PetscInt_FMT
                        "), f-evals %" PetscInt_FMT ", Jacobians %" PetscInt_FMT ", error at the end %.3e, sampled %.3e, %.3f s\n",
                        p.name, (double)rtol, (double)atol, r.ierr ? "error" : TSConvergedReasons[r.reason], (double)r.t, r.steps, r.rejects, r.newton_fail,
                        r.nf, r.jac, (double)r.err, (double)(r.sampled < PETSC_INFINITY ? r.sampled : NAN), r.wall));
  if (r.ierr) PetscCall(PetscPrintf(PETSC_COMM_SELF, "  error %d: %s\n", (int)r.ierr, r.message));
  else if (r.sampled == PETSC_INFINITY) PetscCall(PetscPrintf(PETSC_COMM_SELF, "  (stopped before the last sample time: no sampled error)\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal GeometricMean(const PetscReal *v, int n)
{
  PetscReal s = 0;
  for (int i = 0; i < n; i++) s += std::log(v[i]);
  return std::exp(s / n);
}

/* (a) */
PetscErrorCode CheckAgainstScipy(Ode &p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "(a) %s, rtol = atol = tol: errors (max norm) at t = %g and of the dense output at %d times, their band mean, f-evals; radauiia vs "
                        "SciPy 1.10.1 Radau\n",
                        p.name, (double)p.tf, (int)p.ts.size()));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "     tol |   at t_end: radauiia     SciPy |    sampled: radauiia     SciPy |  band: radauiia     SciPy  ratio | "
                                         "f-evals (SciPy) | steps rejected Jacobians\n"));
  for (int k = 0; k < 5; k++) {
    const ScipyFigure &s = p.scipy[k];
    Result             r, rb;
    PetscReal          sampled[5];
    for (int b = 0; b < 5; b++) {
      PetscCall(Run(p, s.tol * kBand[b], s.tol * kBand[b], &rb));
      TG_CHECK(!rb.ierr && rb.reason > 0, "%s at tol %g: %s", p.name, (double)(s.tol * kBand[b]), rb.ierr ? rb.message : TSConvergedReasons[rb.reason]);
      sampled[b] = rb.sampled;
      if (kBand[b] == 1.0) r = rb;
    }
    const PetscReal band = GeometricMean(sampled, 5);
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "   %5.0e |           %9.3e %9.3e |           %9.3e %9.3e |       %9.3e %9.3e %6.2f | %7" PetscInt_FMT " (%5" PetscInt_FMT
                          ") | %5" PetscInt_FMT " %8" PetscInt_FMT " %9" PetscInt_FMT "\n",
                          (double)s.tol, (double)r.err, (double)s.err_end, (double)r.sampled, (double)s.err_sampled, (double)band, (double)s.band,
                          (double)(band / s.band), r.nf, s.nfev, r.steps, r.rejects, r.jac));
    if (check)
      TG_CHECK(band <= 3 * s.band, "%s at rtol = atol = %g: the band mean of the sampled error, %.3e, is more than 3x SciPy's %.3e", p.name, (double)s.tol,
               (double)band, (double)s.band);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (b) one case below the round-off floor: it must end with the floor error, after little work */
PetscErrorCode CheckFloorCase(Ode &p, PetscReal rtol, PetscReal atol, PetscReal newton_tol, const char *must_name, PetscInt max_work)
{
  Result     r, rf;
  RunOptions opt;

  PetscFunctionBeginUser;
  opt.newton_tol = newton_tol;
  PetscCall(Run(p, rtol, atol, &r, opt));

  PetscCall(PrintRun(p, rtol, atol, r));
  TG_CHECK(r.ierr == PETSC_ERR_NOT_CONVERGED, "%s rtol %g atol %g: expected the round-off floor error (PETSC_ERR_NOT_CONVERGED), got %d (%s)", p.name,
           (double)rtol, (double)atol, (int)r.ierr, r.ierr ? r.message : TSConvergedReasons[r.reason]);
  TG_CHECK(std::strstr(r.message, "round-off") && std::strstr(r.message, must_name), "%s: the message must name the round-off floor and %s: %s", p.name,
           must_name, r.message);
  TG_CHECK(r.rejects <= max_work && r.jac <= max_work,
           "%s rtol %g atol %g: %" PetscInt_FMT " rejections and %" PetscInt_FMT " Jacobians before the floor error", p.name, (double)rtol, (double)atol,
           r.rejects, r.jac);
  /* -ts_error_if_step_fails false: the same stop as a failed TS */
  opt.error_if_fails = PETSC_FALSE;
  PetscCall(Run(p, rtol, atol, &rf, opt));
  TG_CHECK(!rf.ierr && rf.reason == TS_DIVERGED_STEP_REJECTED && rf.t == r.t, "%s with -ts_error_if_step_fails false: error %d, reason %s at t = %g", p.name,
           (int)rf.ierr, TSConvergedReasons[rf.reason], (double)rf.t);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckRoundOffFloor(Ode &hires, Ode &vdp)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "(b) tolerances below the round-off floor end with an error naming them (before: up to 10^5 rejected steps)\n"));
  PetscCall(CheckFloorCase(hires, 1e-20, 1e-20, PETSC_DEFAULT, "-ts_atol", 0));
  PetscCall(CheckFloorCase(vdp, 1e-20, 1e-20, PETSC_DEFAULT, "-ts_atol", 0));
  PetscCall(CheckFloorCase(vdp, 0, 1e-14, PETSC_DEFAULT, "-ts_atol", 100));
  PetscCall(CheckFloorCase(vdp, 1e-8, 1e-8, 1e-12, "-ts_radauiia_newton_tol", 10));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  char      name[16] = "hires";
  PetscReal rtol = -1, atol = -1;
  PetscBool one = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-acc_problem", name, sizeof(name), NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-acc_rtol", &rtol, &one));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-acc_atol", &atol, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-acc_check", &check, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-acc_trace", &trace, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-acc_data", data_dir, sizeof(data_dir), NULL));
  if (one) {
    Ode    p = std::strcmp(name, "vdp") ? Hires() : Vdp();
    Result r;
    PetscCall(LoadReference(p));
    PetscCall(Run(p, rtol, atol >= 0 ? atol : rtol, &r));
    PetscCall(PrintRun(p, rtol, atol >= 0 ? atol : rtol, r));
    PetscCall(PetscFinalize());
    return 0;
  }
  {
    Ode h = Hires(), v = Vdp();
    PetscCall(LoadReference(h));
    PetscCall(LoadReference(v));
    PetscCall(CheckAgainstScipy(h));
    PetscCall(CheckAgainstScipy(v));
    PetscCall(CheckRoundOffFloor(h, v));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_radau_iia_accuracy: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
