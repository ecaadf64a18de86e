static const char help[] = "Undamped chain of wall springs with clamped ends:\n"
                           "1. the first longitudinal mode oscillates at omega_1 = 2 sqrt(k/m) sin(pi / (2 (N+1))) (within 1%),\n"
                           "   with DOPRI (rk 5dp) and both velocity Verlets (PETSc's basicsymplectic, turgor's verlet);\n"
                           "2. both Verlets keep the energy error bounded over 10^4 steps (within the modified-energy\n"
                           "   bound, and no drift); this caught PETSc defaulting basicsymplectic to symplectic Euler;\n"
                           "3. turgor's verlet: second order against the exact first mode (error ratio 4 +- 0.2 when dt halves),\n"
                           "   one force evaluation per step (the last one reused), its Hermite interpolation second order,\n"
                           "   and at a step's start the previous step's state to round-off.\n";
#include <turgor/ts/velocity_verlet.h>
#include "test_util.h"
#include "fine_run_util.h"
#include <turgor/physics/wall_springs.h>

using namespace turgor;

static const PetscInt  N = 10; /* free particles */
static const PetscReal k = 4000.0, m = 0.5, l0 = 12.5;

struct ChainRecord {
  std::vector<PetscReal> t, u, E;
};

static PetscErrorCode Record(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx)
{
  ChainRecord       *rec = (ChainRecord *)ctx;
  const PetscScalar *u;
  const PetscInt     n = N + 2;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscReal E = 0;
  for (PetscInt i = 0; i < n; i++) E += 0.5 * m * (u[2 * n + 2 * i] * u[2 * n + 2 * i] + u[2 * n + 2 * i + 1] * u[2 * n + 2 * i + 1]);
  for (PetscInt i = 0; i + 1 < n; i++) {
    const PetscReal r = std::hypot(u[2 * i + 2] - u[2 * i], u[2 * i + 3] - u[2 * i + 1]);
    E += 0.5 * k * (r - l0) * (r - l0);
  }
  rec->t.push_back(t);
  rec->u.push_back(u[2 * (N / 2)] - (N / 2) * l0); /* displacement of a middle particle */
  rec->E.push_back(E);
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Clamped chain of N+2 undamped springs; initial displacement: the first mode or random; run
   `ts_type` for `steps` fixed steps of dt. */
static PetscErrorCode RunChain(TSType ts_type, PetscReal dt, PetscInt steps, bool first_mode, ChainRecord *rec, FineRun **keep = nullptr)
{
  Tissue   T;
  FineRun *own = new FineRun(PETSC_COMM_SELF), &run = *own; /* *keep takes it (the caller inspects the TS), else deleted */
  auto     springs = std::make_unique<WallSprings>();
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < N + 2; i++) T.AddParticle(i * l0, 0, m, KIND_WALL);
  for (PetscInt i = 0; i + 1 < N + 2; i++) T.AddSpring(i, i + 1);
  T.Finalize();
  turgor_test::Random rnd(1);
  for (PetscInt i = 1; i <= N; i++) T.X[2 * i] += first_mode ? 0.01 * std::sin(PETSC_PI * i / (N + 1)) : 0.5 * rnd();
  springs->stiffness     = k;
  springs->damping_ratio = 0;
  run.Physics().names    = {}; /* no listed terms: the springs below only */
  run.Physics().Add(std::move(springs));
  run.Spec().clamp = {"left", "right"};
  run.Spec().dt    = dt;
  turgor_test::QuietOutput(run, "test_spring_chain_out");
  PetscCall(run.SetFromOptions());
  run.SetTissue(T);
  PetscCall(TSSetType(run.GetTS(), ts_type));
  PetscCall(turgor_test::FixedSteps(run.GetTS(), steps));
  PetscCall(run.SetUp());
  PetscCall(TSMonitorSet(run.GetTS(), Record, rec, NULL));
  PetscCall(run.Solve());
  if (keep) *keep = own;
  else delete own;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Mean period from the upward zero crossings (linear interpolation). */
static PetscReal MeasuredPeriod(const ChainRecord &rec)
{
  std::vector<PetscReal> up;
  for (size_t s = 1; s < rec.u.size(); s++)
    if (rec.u[s - 1] < 0 && rec.u[s] >= 0) up.push_back(rec.t[s - 1] + (rec.t[s] - rec.t[s - 1]) * (-rec.u[s - 1]) / (rec.u[s] - rec.u[s - 1]));
  return up.size() >= 2 ? (up.back() - up.front()) / (up.size() - 1) : -1;
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  const PetscReal omega1 = 2 * std::sqrt(k / m) * std::sin(PETSC_PI / (2 * (N + 1))), T1 = 2 * PETSC_PI / omega1;
  const PetscReal omega_max = 2 * std::sqrt(k / m);
  for (TSType type : {TSRK, TSBASICSYMPLECTIC, TSVERLET}) {
    ChainRecord rec;
    PetscCall(RunChain(type, T1 / 400, 4000, true, &rec)); /* ten periods */
    const PetscReal T = MeasuredPeriod(rec);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s first-mode period %.6f µs, analytic %.6f µs (relative error %.2e)\n", type, (double)T, (double)T1,
                          (double)std::fabs(T - T1) / T1));
    TG_CHECK_CLOSE(T, T1, 1e-2, 0, "first-mode period");
  }
  for (TSType type : {TSBASICSYMPLECTIC, TSVERLET}) {
    /* all modes excited, dt at half the Verlet stability limit 2/omega_max */
    ChainRecord rec;
    PetscCall(RunChain(type, 1.0 / omega_max, 10000, false, &rec));
    const PetscReal E0   = rec.E[0];
    PetscReal       emax = 0, mean_first = 0, mean_last = 0;
    const size_t    ns = rec.E.size(), w = 1000;
    for (size_t s = 0; s < ns; s++) emax = PetscMax(emax, std::fabs(rec.E[s] - E0) / E0);
    for (size_t s = 1; s <= w; s++) mean_first += rec.E[s] / w;
    for (size_t s = ns - w; s < ns; s++) mean_last += rec.E[s] / w;
    const PetscReal drift = std::fabs(mean_last - mean_first) / E0;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s %zu steps at dt = 1/omega_max: max |E - E0|/E0 = %.3e, drift of the mean energy = %.3e\n", type, ns - 1,
                          (double)emax, (double)drift));
    TG_CHECK(ns == 10001, "steps");
    /* Verlet conserves a modified energy; per mode the true energy then oscillates within a factor
       1 / (1 - (omega h / 2)^2), i.e. by at most 1/3 at omega h = 1, and does not drift. */
    TG_CHECK(emax <= 1.0 / 3.0 + 1e-9, "energy error above the Verlet bound 1/3: %.3e", (double)emax);
    TG_CHECK(drift < 1e-2 * emax, "energy drifts: %.3e (oscillation %.3e)", (double)drift, (double)emax);
  }
  {
    /* turgor's verlet on the first mode u(t) = A sin(pi i/(N+1)) cos(omega_1 t): error at t = 2.25 T1
       (steps of T1/100 and T1/200; Verlet's error is a phase error, largest where the cosine is
       steepest), and the interpolation half a step before the end */
    PetscReal err[2], ierr[2], start_err = 0, start_energy_err = 0;
    for (int r = 0; r < 2; r++) {
      ChainRecord     rec;
      const PetscInt  steps = 225 << r;
      const PetscReal dt = 2.25 * T1 / steps, A = 0.01 * std::sin(PETSC_PI * (N / 2) / (N + 1));
      FineRun        *run = nullptr;
      PetscCall(RunChain(TSVERLET, dt, steps, true, &rec, &run));
      err[r] = std::fabs(rec.u.back() - A * std::cos(omega1 * rec.t.back())) / A;
      PetscInt evals, reused;
      PetscCall(TSVerletGetCounters(run->GetTS(), &evals, &reused));
      TG_CHECK(evals == steps + 1 && reused == steps - 1, "verlet: %" PetscInt_FMT " evaluations (%" PetscInt_FMT " reused) in %" PetscInt_FMT " steps", evals,
               reused, steps);
      Vec                X;
      PetscReal          tm = rec.t.back() - 0.5 * dt;
      const PetscScalar *x;
      PetscCall(VecDuplicate(run->GetState(), &X));
      PetscCall(TSInterpolate(run->GetTS(), tm, X));
      PetscCall(VecGetArrayRead(X, &x));
      ierr[r] = std::fabs(x[2 * (N / 2)] - (N / 2) * l0 - A * std::cos(omega1 * tm)) / A;
      PetscCall(VecRestoreArrayRead(X, &x));
      /* at the last step's start: the previous step's state, recovered from the end (verlet keeps
         no copy of the state), to round-off of the positions (about 60 µm here) */
      PetscCall(TSInterpolate(run->GetTS(), rec.t[rec.t.size() - 2], X));
      PetscCall(VecGetArrayRead(X, &x));
      start_err = std::max(start_err, std::fabs(x[2 * (N / 2)] - (N / 2) * l0 - rec.u[rec.u.size() - 2]));
      PetscCall(VecRestoreArrayRead(X, &x));
      ChainRecord start; /* and its energy (the velocities: v_n = v+ - h/2 a_n) */
      PetscCall(Record(run->GetTS(), 0, 0, X, &start));
      start_energy_err = std::max(start_energy_err, std::fabs(start.E[0] / rec.E[rec.E.size() - 2] - 1));
      PetscCall(VecDestroy(&X));
      delete run;
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "verlet, first mode at t = 2.25 T1: error %.3e (dt T1/100), %.3e (T1/200), ratio %.3f; interpolated mid-step %.3e, %.3e\n",
                          (double)err[0], (double)err[1], (double)(err[0] / err[1]), (double)ierr[0], (double)ierr[1]));
    TG_CHECK(std::fabs(err[0] / err[1] - 4) < 0.2, "verlet is not second order: ratio %.3f", (double)(err[0] / err[1]));
    TG_CHECK(ierr[0] < 2 * err[0] && ierr[1] < 2 * err[1], "the interpolation is less accurate than the steps");
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "verlet, interpolated at the last step's start: %.3e µm from the previous step's state, energy %.3e relative\n",
                          (double)start_err, (double)start_energy_err));
    TG_CHECK(start_err < 1e-12 && start_energy_err < 1e-10, "the step's start is not recovered to round-off: %.3e µm, energy %.3e", (double)start_err,
             (double)start_energy_err);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_spring_chain: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
