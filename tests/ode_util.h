#pragma once
/* Small ODE pieces shared by the time-integrator tests: Van der Pol's equation, a state vector
   from its values, and a dense Jacobian set into a PETSc matrix. */
#include <petscmat.h>
#include <vector>

namespace turgor_test {

/* Van der Pol in the scaled form y1' = y2, y2' = ((1 - y1^2) y2 - y1) / eps, y(0) = (2, 0):
   eps = 1 is mu = 1; eps = 1/mu^2, with time scaled by 1/mu and y2 by mu, is the stiff mu
   (Hairer & Wanner, Solving ODEs II, eq IV.1.5'). */
inline void VanDerPol(PetscReal eps, const PetscScalar y[2], PetscScalar f[2])
{
  f[0] = y[1];
  f[1] = ((1 - y[0] * y[0]) * y[1] - y[0]) / eps;
}

/* its Jacobian df/dy, row-major */
inline void VanDerPolJacobian(PetscReal eps, const PetscScalar y[2], PetscScalar J[4])
{
  J[0] = 0;
  J[1] = 1;
  J[2] = (-2 * y[0] * y[1] - 1) / eps;
  J[3] = (1 - y[0] * y[0]) / eps;
}

/* A sequential vector holding values[0 .. n-1]. */
inline PetscErrorCode CreateSeqVec(PetscInt n, const PetscReal values[], Vec *V)
{
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, V));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(*V, i, values[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(*V));
  PetscCall(VecAssemblyEnd(*V));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The dense n x n matrix v (row-major) as the entries of rows and columns 0 .. n-1 of B, assembled. */
inline PetscErrorCode SetDenseMatrix(Mat B, PetscInt n, const PetscScalar v[])
{
  std::vector<PetscInt> idx(n);
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) idx[i] = i;
  PetscCall(MatSetValues(B, n, idx.data(), n, idx.data(), v, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor_test
