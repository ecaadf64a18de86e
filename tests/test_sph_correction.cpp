static const char help[] = "Bonet-Lok correction of the SPH velocity gradient (TW 562 eqs 13-15):\n"
                           "1. on a disordered patch the corrected gradient of v = A x equals A to round-off;\n"
                           "2. a rigid rotation then produces no viscous force at all;\n"
                           "3. a closed cell spinning rigidly keeps its angular momentum over one revolution\n"
                           "   (velocity Verlet) with the correction, and loses it without (>= 100x more drift).\n";
#include "test_util.h"
#include "fine_run_util.h"
#include <turgor/physics/sph_fluid.h>

using namespace turgor;

/* 8 x 8 fluid particles of one cell, spacing 4 µm, each moved at random by up to 1.2 µm. */
static Tissue DisorderedPatch()
{
  Tissue              T;
  turgor_test::Random rnd(5);
  for (int j = 0; j < 8; j++)
    for (int i = 0; i < 8; i++) T.AddParticle(4.0 * i + 1.2 * rnd(), 4.0 * j + 1.2 * rnd(), 0.16, KIND_FLUID, 0);
  T.Finalize();
  return T;
}

static PetscErrorCode LinearField(PetscBool correction, PetscReal *err_grad, PetscReal *max_force)
{
  Tissue                 T    = DisorderedPatch();
  const PetscInt         n    = T.particles.n;
  const PetscReal        A[4] = {0.3, -0.7, 0.45, -0.1}, W[4] = {0, -0.8, 0.8, 0}; /* general and rigid rotation */
  std::vector<PetscReal> v(2 * n), f(2 * n), rho, gradv;
  PhysicsSpec            physics;
  ForceModel             model;
  auto                   own = std::make_unique<SPHFluid>();
  PetscFunctionBeginUser;
  own->correction  = correction;
  own->sound_speed = 0; /* viscous stress only */
  own->viscosity   = 5.0;
  physics.Add(std::move(own));
  PetscCall(model.SetUp(physics, T.particles));
  auto *sph = dynamic_cast<SPHFluid *>(model.Term("sph")); /* the model's own, set-up copy */
  for (PetscInt i = 0; i < n; i++) {
    v[2 * i]     = A[0] * T.X[2 * i] + A[1] * T.X[2 * i + 1];
    v[2 * i + 1] = A[2] * T.X[2 * i] + A[3] * T.X[2 * i + 1];
  }
  PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL)); /* builds the neighbour lists */
  const ForceInput in = {&T.particles, T.X.data(), v.data(), &model.Neighbours(), &model.Images()};
  PetscCall(sph->DensityAndVelocityGradient(in, rho, gradv));
  *err_grad = 0;
  for (PetscInt i = 0; i < n; i++)
    for (int c = 0; c < 4; c++) *err_grad = PetscMax(*err_grad, std::fabs(gradv[4 * i + c] - A[c]));
  /* rigid rotation: the viscous forces */
  for (PetscInt i = 0; i < n; i++) {
    v[2 * i]     = W[1] * T.X[2 * i + 1];
    v[2 * i + 1] = W[2] * T.X[2 * i];
  }
  PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
  *max_force = 0;
  for (PetscReal fk : f) *max_force = PetscMax(*max_force, std::fabs(fk));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One closed cell (8 wall particles, 16 fluid particles moved at random) spinning rigidly with
   period 10 µs, integrated over one revolution by velocity Verlet (dt = 1e-3 µs), no clamps;
   returns |L(T) - L(0)| / |L(0)|. */
static PetscErrorCode SpinningCell(PetscBool correction, PetscReal *drift)
{
  Tissue  T;
  FineRun run(PETSC_COMM_SELF);
  auto    sph = std::make_unique<SPHFluid>();
  PetscFunctionBeginUser;
  PetscCall(turgor_test::SquareGridTissue(1, &T));
  turgor_test::Random rnd(9);
  const PetscReal     omega = 2 * PETSC_PI / 10.0, c = 12.5;
  T.V.resize(T.X.size());
  for (PetscInt i = 0; i < T.particles.n; i++) {
    if (T.particles.kind[i] == KIND_FLUID) {
      T.X[2 * i] += 1.5 * rnd();
      T.X[2 * i + 1] += 1.5 * rnd();
    }
    T.V[2 * i]     = -omega * (T.X[2 * i + 1] - c);
    T.V[2 * i + 1] = omega * (T.X[2 * i] - c);
  }
  /* springs and repulsion with their defaults; the fluid viscous (mu = 5) */
  sph->viscosity      = 5;
  sph->correction     = correction;
  run.Physics().names = {"springs", "repulsion"};
  run.Physics().Add(std::move(sph));
  run.Spec().clamp = {"none"};
  run.Spec().dt    = 1e-3;
  turgor_test::QuietOutput(run, "test_sph_correction_out");
  PetscCall(run.SetFromOptions());
  run.SetTissue(T);
  PetscCall(TSSetType(run.GetTS(), TSBASICSYMPLECTIC));
  PetscCall(TSSetMaxTime(run.GetTS(), 10));
  PetscCall(run.SetUp());
  auto L = [&](Vec U) {
    const PetscScalar *u;
    const PetscInt     n = T.particles.n;
    PetscReal          l = 0;
    VecGetArrayRead(U, &u);
    for (PetscInt i = 0; i < n; i++) l += T.particles.mass[i] * ((u[2 * i] - c) * u[2 * n + 2 * i + 1] - (u[2 * i + 1] - c) * u[2 * n + 2 * i]);
    VecRestoreArrayRead(U, &u);
    return l;
  };
  const PetscReal L0 = L(run.GetState());
  PetscCall(run.Solve());
  *drift = std::fabs(L(run.GetState()) - L0) / std::fabs(L0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal err_on, err_off, f_on, f_off, drift_on, drift_off;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(LinearField(PETSC_TRUE, &err_on, &f_on));
  PetscCall(LinearField(PETSC_FALSE, &err_off, &f_off));
  PetscCall(
    PetscPrintf(PETSC_COMM_SELF, "grad(A x) error on a disordered patch: corrected %.2e, uncorrected %.2e (|A| ~ 0.7)\n", (double)err_on, (double)err_off));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "largest viscous force under rigid rotation: corrected %.2e µN, uncorrected %.2e µN\n", (double)f_on, (double)f_off));
  TG_CHECK(err_on < 1e-12, "corrected gradient of a linear field is not exact: %.3e", (double)err_on);
  TG_CHECK(err_off > 1e-2, "the uncorrected gradient should be visibly wrong on a disordered patch (%.3e)", (double)err_off);
  TG_CHECK(f_on < 1e-12 * f_off, "rigid rotation must not produce viscous forces with the correction (%.3e vs %.3e)", (double)f_on, (double)f_off);

  PetscCall(SpinningCell(PETSC_TRUE, &drift_on));
  PetscCall(SpinningCell(PETSC_FALSE, &drift_off));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "spinning cell, one revolution: |dL|/|L| corrected %.2e, uncorrected %.2e (ratio %.2e)\n", (double)drift_on,
                        (double)drift_off, (double)(drift_off / drift_on)));
  TG_CHECK(drift_on * 100 <= drift_off, "the correction must reduce the angular momentum drift at least 100x");
  TG_CHECK(drift_on < 1e-10, "corrected angular momentum drift %.3e is not round-off", (double)drift_on);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_sph_correction: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
