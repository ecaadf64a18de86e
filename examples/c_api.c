static const char help[] = "turgor from C (C99): its C API, <turgor/turgor.h>, in a C program.\n"
                           "1. Robertson's chemical kinetics, the classic stiff test, solved by the radauiia TS type through\n"
                           "   PETSc's C TS API (options prefix rober_):\n"
                           "     y1' = -0.04 y1 + 1e4 y2 y3,  y2' = 0.04 y1 - 1e4 y2 y3 - 3e7 y2^2,  y3' = 3e7 y2^2,\n"
                           "     y(0) = (1, 0, 0),  t in [0, 1e11],\n"
                           "   the Test Set for IVP Solvers problem ROBER (Mazzia & Magherini, Univ. Bari), whose reference\n"
                           "   solution is hard-coded: y(1e11) = (2.083340149701255e-8, 8.333360770334713e-14, 0.9999999791665050).\n"
                           "   Fails when max_i |y_i - ref_i| / (atol_i + rtol |ref_i|) exceeds 10, or when y1 + y2 + y3 = 1\n"
                           "   (kept by any Runge-Kutta method) is off by more than 1e-12.\n"
                           "2. One of turgor's modes with TurgorRunMode(), as the turgor executable runs it: -mode (default\n"
                           "   here rve) and every other option come from the command line.\n"
                           "Prints \"c_api: OK\" when both succeeded.\n\n"
                           "  make -C examples c_api && ./examples/c_api -path_steps 4 -path_tangents 0 -output_dir out/c_api\n";

#include <turgor/turgor.h> /* the only include: turgor's C API, PETSc's TS */

typedef struct {
  PetscInt nf, nj; /* right-hand side and Jacobian evaluations */
} Rober;

static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec Y, Vec F, void *ctx)
{
  Rober             *rober = (Rober *)ctx;
  const PetscScalar *y;
  PetscScalar       *f;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
  f[2] = 3e7 * y[1] * y[1];
  f[1] = -f[0] - f[2];
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Y, &y));
  rober->nf++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RHSJacobian(TS ts, PetscReal t, Vec Y, Mat A, Mat B, void *ctx)
{
  Rober             *rober  = (Rober *)ctx;
  const PetscInt     idx[3] = {0, 1, 2};
  const PetscScalar *y;
  PetscScalar        J[3][3];

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(Y, &y));
  J[0][0] = -0.04;
  J[0][1] = 1e4 * y[2];
  J[0][2] = 1e4 * y[1];
  J[2][0] = 0;
  J[2][1] = 6e7 * y[1];
  J[2][2] = 0;
  for (PetscInt j = 0; j < 3; j++) J[1][j] = -J[0][j] - J[2][j];
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(MatSetValues(B, 3, idx, 3, idx, &J[0][0], INSERT_VALUES));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  if (A != B) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  rober->nj++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ROBER on [0, 1e11] with radauiia; errors when the final state is off the Test Set's reference. */
static PetscErrorCode SolveRobertson(void)
{
  const PetscReal    ref[3]  = {2.083340149701255e-8, 8.333360770334713e-14, 0.9999999791665050};
  const PetscReal    t_final = 1e11;
  PetscReal          rtol = 1e-6, atol[3] = {1e-12, 1e-18, 1e-12}, theta, t, err = 0, sum = 0;
  PetscInt           steps, rejected, jac, newton, solves;
  TSConvergedReason  reason;
  Rober              rober = {0, 0};
  TS                 ts;
  Vec                y, vatol;
  Mat                J;
  const PetscScalar *ya;
  MPI_Comm           comm = PETSC_COMM_SELF; /* a 3-unknown problem: every rank solves its own */

  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(comm, 3, &y));
  PetscCall(VecSet(y, 0.0));
  PetscCall(VecSetValue(y, 0, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(y));
  PetscCall(VecAssemblyEnd(y));
  PetscCall(MatCreateSeqDense(comm, 3, 3, NULL, &J));

  PetscCall(TSCreate(comm, &ts));
  PetscCall(TSSetOptionsPrefix(ts, "rober_"));
  PetscCall(TSSetProblemType(ts, TS_NONLINEAR));
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, &rober));
  PetscCall(TSSetRHSJacobian(ts, J, J, RHSJacobian, &rober));
  PetscCall(TSSetType(ts, TSRADAUIIA));
  /* defaults through turgor's C API before TSSetFromOptions(), which may override them */
  PetscCall(TSRadauIIASetJacobianReuse(ts, 0.1)); /* RADAU5's advice for expensive Jacobians */
  PetscCall(TSSetMaxTime(ts, t_final));
  PetscCall(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetMaxSteps(ts, 100000));
  PetscCall(TSSetTimeStep(ts, 1e-6));
  PetscCall(VecDuplicate(y, &vatol));
  for (PetscInt i = 0; i < 3; i++) PetscCall(VecSetValue(vatol, i, atol[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(vatol));
  PetscCall(VecAssemblyEnd(vatol));
  /* absolute tolerances far below the final y1 = 2e-8 and y2 = 8e-14 (y2 never exceeds 4e-5) */
  PetscCall(TSSetTolerances(ts, PETSC_DECIDE, vatol, rtol, NULL));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSGetTolerances(ts, NULL, NULL, &rtol, NULL)); /* the tolerances -rober_ts_rtol may have changed */
  PetscCall(TSRadauIIAGetJacobianReuse(ts, &theta));

  PetscCall(TSSolve(ts, y));
  PetscCall(TSGetConvergedReason(ts, &reason));
  PetscCheck(reason > 0, comm, PETSC_ERR_NOT_CONVERGED, "ROBER: TSSolve did not converge: %s", TSConvergedReasons[reason]);
  PetscCall(TSGetSolveTime(ts, &t));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetStepRejections(ts, &rejected));
  PetscCall(TSRadauIIAGetCounters(ts, &jac, &newton, &solves));

  PetscCall(VecGetArrayRead(y, &ya));
  for (PetscInt i = 0; i < 3; i++) {
    err = PetscMax(err, PetscAbsReal(PetscRealPart(ya[i]) - ref[i]) / (atol[i] + rtol * PetscAbsReal(ref[i])));
    sum += PetscRealPart(ya[i]);
  }
  PetscCall(PetscPrintf(comm, "ROBER with %s (rtol %g, Jacobian reuse %g): t = %g, y = (%.10e, %.10e, %.13f)\n", TSRADAUIIA, (double)rtol, (double)theta,
                        (double)t, (double)PetscRealPart(ya[0]), (double)PetscRealPart(ya[1]), (double)PetscRealPart(ya[2])));
  PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(PetscPrintf(comm,
                        "ROBER: %" PetscInt_FMT " steps (%" PetscInt_FMT " rejected), %" PetscInt_FMT " f evals, %" PetscInt_FMT
                        " Jacobians (radauiia counts %" PetscInt_FMT "), %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " linear solves\n",
                        steps, rejected, rober.nf, rober.nj, jac, newton, solves));
  PetscCall(PetscPrintf(comm, "ROBER: error %.3g of the tolerance, |y1 + y2 + y3 - 1| = %.2e\n", (double)err, (double)PetscAbsReal(sum - 1)));
  PetscCheck(PetscAbsReal(t - t_final) <= 1e-12 * t_final, comm, PETSC_ERR_PLIB, "ROBER: stopped at t = %g, not %g", (double)t, (double)t_final);
  PetscCheck(err <= 10, comm, PETSC_ERR_PLIB, "ROBER: error %g of the tolerance against the Test Set's reference: more than 10", (double)err);
  PetscCheck(PetscAbsReal(sum - 1) <= 1e-12, comm, PETSC_ERR_PLIB, "ROBER: y1 + y2 + y3 - 1 = %g: the linear invariant is lost", (double)(sum - 1));
  PetscCheck(jac == rober.nj, comm, PETSC_ERR_PLIB, "ROBER: TSRadauIIAGetCounters() counts %" PetscInt_FMT " Jacobians, the callback %" PetscInt_FMT, jac,
             rober.nj);

  PetscCall(TSDestroy(&ts));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&vatol));
  PetscCall(VecDestroy(&y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll()); /* the TS types radauiia and am; turgor's modes */
  PetscCall(SolveRobertson());
  PetscCall(TurgorRunMode(PETSC_COMM_WORLD, "rve"));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "c_api: OK (ROBER with radauiia within tolerance; TurgorRunMode done)\n"));
  PetscCall(PetscFinalize());
  return 0;
}
