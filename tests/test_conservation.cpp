static const char help[] = "Momentum conservation of the fine model, term by term and all together, without clamps or\n"
                           "body force: linear momentum over 1000 steps of DOPRI (rk 5dp, which keeps linear invariants),\n"
                           "angular momentum over 1000 steps of velocity Verlet (basicsymplectic and verlet, which keep\n"
                           "sum x cross m v exactly when every force is torque-free).\n";
#include "test_util.h"
#include "fine_run_util.h"
#include <turgor/ts/velocity_verlet.h>
#include <algorithm>

using namespace turgor;

struct Momenta {
  PetscReal P[2], L, Pscale, Lscale;
};

static Momenta Measure(const ParticleSet &Pset, Vec U)
{
  const PetscScalar *u;
  const PetscInt     n = Pset.n;
  Momenta            m = {
               {0, 0},
               0, 0, 0
  };
  VecGetArrayRead(U, &u);
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal x = u[2 * i], y = u[2 * i + 1], vx = u[2 * n + 2 * i], vy = u[2 * n + 2 * i + 1], mi = Pset.mass[i];
    m.P[0] += mi * vx;
    m.P[1] += mi * vy;
    m.L += mi * (x * vy - y * vx);
    m.Pscale += mi * std::hypot(vx, vy);
    m.Lscale += mi * std::hypot(x, y) * std::hypot(vx, vy);
  }
  VecRestoreArrayRead(U, &u);
  return m;
}

/* The names in a comma-separated list. */
static std::vector<std::string> Split(const std::string &list)
{
  std::vector<std::string> names;
  for (size_t begin = 0, end; begin <= list.size(); begin = end + 1) {
    end = std::min(list.find(',', begin), list.size());
    names.push_back(list.substr(begin, end - begin));
  }
  return names;
}

/* Run 1000 steps of `ts_type` (fixed steps of 5e-4 µs) with only `physics`; report the relative drifts. */
static PetscErrorCode RunCase(const char *physics, TSType ts_type, const Tissue &T, PetscReal *dP, PetscReal *dL)
{
  FineRun run(PETSC_COMM_SELF);
  PetscFunctionBeginUser;
  run.Spec().clamp    = {"none"};
  run.Spec().dt       = 5e-4;
  run.Physics().names = Split(physics);
  turgor_test::QuietOutput(run, "test_conservation_out");
  PetscCall(run.SetFromOptions());
  run.SetTissue(T);
  PetscCall(TSSetType(run.GetTS(), ts_type));
  PetscCall(turgor_test::FixedSteps(run.GetTS(), 1000));
  PetscCall(run.SetUp());
  const Momenta a = Measure(T.particles, run.GetState());
  PetscCall(run.Solve());
  PetscInt steps;
  PetscCall(TSGetStepNumber(run.GetTS(), &steps));
  TG_CHECK(steps == 1000, "expected 1000 steps, took %" PetscInt_FMT, steps);
  const Momenta b = Measure(T.particles, run.GetState());
  *dP             = std::hypot(b.P[0] - a.P[0], b.P[1] - a.P[1]) / a.Pscale;
  *dL             = std::fabs(b.L - a.L) / a.Lscale;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-26s %-16s |dP|/sum m|v| = %.2e   |dL|/sum m|x||v| = %.2e   (%" PetscInt_FMT " RHS evaluations)\n", physics, ts_type,
                        (double)*dP, (double)*dL, run.RHSEvaluations()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  /* 3 x 3 cells, perturbed positions and random velocities: every term is active */
  Tissue T;
  PetscCall(turgor_test::SquareGridTissue(3, &T));
  turgor_test::Random rnd(3);
  for (PetscReal &x : T.X) x += 0.3 * rnd();
  T.V.resize(T.X.size());
  for (PetscReal &v : T.V) v = rnd();

  PetscReal dP, dL;
  for (const char *physics : {"springs", "repulsion", "sph", "springs,repulsion,sph"}) {
    PetscCall(RunCase(physics, TSRK, T, &dP, &dL));
    TG_CHECK(dP < 1e-13, "%s: linear momentum drift %.3e under rk", physics, (double)dP);
  }
  for (TSType verlet : {TSBASICSYMPLECTIC, TSVERLET})
    for (const char *physics : {"springs", "repulsion", "sph", "springs,repulsion,sph"}) {
      PetscCall(RunCase(physics, verlet, T, &dP, &dL));
      TG_CHECK(dP < 1e-13, "%s: linear momentum drift %.3e under %s", physics, (double)dP, verlet);
      TG_CHECK(dL < 1e-12, "%s: angular momentum drift %.3e under %s", physics, (double)dL, verlet);
    }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_conservation: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
