static const char help[] = "Van der Pol's equation with mu = 1e3, the classic stiff test, solved by the radauiia TS type.\n"
                           "Scaled form (Hairer & Wanner, Solving ODEs II, eq IV.1.5'), eps = 1/mu^2 = 1e-6:\n"
                           "  y1' = y2,  eps y2' = (1 - y1^2) y2 - y1,  y(0) = (2, 0),  t in [0, 2],\n"
                           "the Test Set for IVP Solvers problem VDPOL (Mazzia & Magherini, Univ. Bari; mu = 1e3 on [0, 2000])\n"
                           "with time scaled by 1/mu and y2 by mu. The final state is compared with the Test Set's reference\n"
                           "solution (hard-coded, rescaled): y(2) = (1.706167732170469, -0.8928097010248125).\n"
                           "Written as F(t, y, y') = M y' - f(y) with an analytic IJacobian; M = I by default, M = diag(1, eps)\n"
                           "with -vdp_mass (then f2 = (1 - y1^2) y2 - y1). Any -ts_type works; radauiia is the default.\n"
                           "Fails when max_i |y_i - ref_i| / (atol + rtol |ref_i|) exceeds 10.\n\n"
                           "  make -C examples van_der_pol && ./examples/van_der_pol -ts_rtol 1e-8 -ts_atol 1e-8\n";

#include <turgor/ts/radau_iia.h>

struct VdP {
  PetscReal eps  = 1e-6;
  PetscBool mass = PETSC_FALSE; /* eps on the left (M = diag(1, eps)) instead of dividing f2 by it */
  PetscInt  nf = 0, nj = 0;
};

static PetscErrorCode IFunction(TS ts, PetscReal t, Vec Y, Vec Ydot, Vec F, void *ctx)
{
  VdP               *p = (VdP *)ctx;
  const PetscScalar *y, *yd;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  p->nf++;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArrayRead(Ydot, &yd));
  PetscCall(VecGetArray(F, &f));
  const PetscScalar g = (1 - y[0] * y[0]) * y[1] - y[0];
  f[0]                = yd[0] - y[1];
  f[1]                = p->mass ? p->eps * yd[1] - g : yd[1] - g / p->eps;
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Ydot, &yd));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* shift M - df/dy */
static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec Y, Vec Ydot, PetscReal shift, Mat A, Mat B, void *ctx)
{
  VdP               *p = (VdP *)ctx;
  const PetscScalar *y;
  const PetscInt     idx[2] = {0, 1};
  PetscScalar        v[2][2];

  PetscFunctionBeginUser;
  p->nj++;
  PetscCall(VecGetArrayRead(Y, &y));
  const PetscReal s = p->mass ? 1 : 1 / p->eps;
  v[0][0]           = shift;
  v[0][1]           = -1;
  v[1][0]           = s * (2 * y[0] * y[1] + 1);
  v[1][1]           = (p->mass ? p->eps : 1) * shift - s * (1 - y[0] * y[0]);
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(MatSetValues(B, 2, idx, 2, idx, &v[0][0], INSERT_VALUES));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const PetscReal   ref[2] = {1.706167732170469, -0.8928097010248125};
  VdP               p;
  TS                ts;
  Vec               Y;
  Mat               J;
  TSType            type;
  TSConvergedReason reason;
  PetscReal         t, rtol, atol, err = 0;
  PetscInt          steps, rejects;
  void (*radau_counters)(void);
  const PetscScalar *y;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorTSRegisterAll());
  PetscOptionsBegin(PETSC_COMM_WORLD, "vdp_", "Van der Pol options", "van_der_pol");
  PetscCall(PetscOptionsBool("-mass", "Write eps y2' = ... (M = diag(1, eps)) instead of y2' = .../eps", "van_der_pol", p.mass, &p.mass, NULL));
  PetscOptionsEnd();

  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2, &Y));
  PetscCall(VecSetValue(Y, 0, 2.0, INSERT_VALUES));
  PetscCall(VecSetValue(Y, 1, 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(Y));
  PetscCall(VecAssemblyEnd(Y));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, NULL, &J));

  PetscCall(TSCreate(PETSC_COMM_SELF, &ts));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  PetscCall(TSSetIFunction(ts, NULL, IFunction, &p));
  PetscCall(TSSetIJacobian(ts, J, J, IJacobian, &p));
  PetscCall(TSSetMaxTime(ts, 2.0));
  PetscCall(TSSetTimeStep(ts, 1e-6));
  PetscCall(TSSetMaxSteps(ts, 1000000));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetTolerances(ts, 1e-6, NULL, 1e-6, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSolve(ts, Y));

  PetscCall(TSGetConvergedReason(ts, &reason));
  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetStepRejections(ts, &rejects));
  PetscCall(TSGetTolerances(ts, &atol, NULL, &rtol, NULL));
  PetscCall(VecGetArrayRead(Y, &y));
  for (int i = 0; i < 2; i++) err = PetscMax(err, PetscAbsScalar(y[i] - ref[i]) / (atol + rtol * PetscAbsReal(ref[i])));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "van_der_pol: ts_type %s, rtol %g, atol %g, %s form: %s at t = %g\n", type, (double)rtol, (double)atol,
                        p.mass ? "M = diag(1, eps)" : "M = I", TSConvergedReasons[reason], (double)t));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  y(2) = (%.12f, %.12f), reference (%.12f, %.12f)\n", (double)PetscRealPart(y[0]), (double)PetscRealPart(y[1]),
                        (double)ref[0], (double)ref[1]));
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "  steps %" PetscInt_FMT ", rejected %" PetscInt_FMT ", IFunction evaluations %" PetscInt_FMT ", IJacobian evaluations %" PetscInt_FMT
                        "\n",
                        steps, rejects, p.nf, p.nj));
  /* by method, not by name: -ts_type radau5 may be the alias of radauiia */
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, "TSRadauIIAGetCounters_C", &radau_counters));
  if (radau_counters) {
    PetscInt jac, newton, solves;
    PetscCall(TSRadauIIAGetCounters(ts, &jac, &newton, &solves));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "  radauiia: Jacobian evaluations %" PetscInt_FMT ", Newton iterations %" PetscInt_FMT ", linear solves %" PetscInt_FMT "\n", jac,
                          newton, solves));
  } else {
    PetscInt snes_its, ksp_its;
    PetscCall(TSGetSNESIterations(ts, &snes_its));
    PetscCall(TSGetKSPIterations(ts, &ksp_its));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  nonlinear iterations %" PetscInt_FMT ", linear iterations %" PetscInt_FMT "\n", snes_its, ksp_its));
  }
  PetscCheck(reason > 0 && PetscAbsReal(t - 2) < 1e-10, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "van_der_pol: the solve stopped at t = %g (%s)", (double)t,
             TSConvergedReasons[reason]);
  PetscCheck(err <= 10, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "van_der_pol: error %.3g x (atol + rtol |ref|) exceeds 10", (double)err);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "van_der_pol: error within tolerance scale: %.3g x (atol + rtol |ref|) <= 10\n", (double)err));

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&Y));
  PetscCall(PetscFinalize());
  return 0;
}
