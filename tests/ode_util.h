#pragma once
/* Small ODE pieces shared by the time-integrator tests: Van der Pol's equation, Kepler's problem
   and a forced linear system with their exact solutions, a state vector from its values, and a
   dense Jacobian set into a PETSc matrix. */
#include <petscts.h>
#include <cmath>
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

/* Kepler's problem q'' = -q/|q|^3, y = (q, p = q'), q(0) = (1 - e, 0), p(0) = (0, sqrt((1 + e)/(1 - e))):
   with the eccentric anomaly E - e sin E = t (Newton), q = (cos E - e, sqrt(1 - e^2) sin E),
   p = (-sin E, sqrt(1 - e^2) cos E) / (1 - e cos E). */
inline void KeplerExact(PetscReal e, PetscReal t, PetscReal y[4])
{
  PetscReal E = t;
  for (int it = 0; it < 50; it++) {
    const PetscReal dE = (E - e * std::sin(E) - t) / (1 - e * std::cos(E));
    E -= dE;
    if (std::fabs(dE) < 1e-16) break;
  }
  const PetscReal s = std::sqrt(1 - e * e), d = 1 - e * std::cos(E);
  y[0] = std::cos(E) - e;
  y[1] = s * std::sin(E);
  y[2] = -std::sin(E) / d;
  y[3] = s * std::cos(E) / d;
}

inline void KeplerRHS(const PetscScalar y[4], PetscScalar f[4])
{
  const PetscScalar r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * PetscSqrtScalar(r2);
  f[0] = y[2];
  f[1] = y[3];
  f[2] = -y[0] / r3;
  f[3] = -y[1] / r3;
}

/* y' = A (y - g(t)) + g'(t), A = [[-1, 1], [-1, -1]], g = (sin t, cos 2t): with y(0) = g(0) the
   solution is g, and errors decay like exp(-t). */
inline void ForcedExact(PetscReal t, PetscReal y[2])
{
  y[0] = std::sin(t);
  y[1] = std::cos(2 * t);
}

inline void ForcedRHS(PetscReal t, const PetscScalar y[2], PetscScalar f[2])
{
  const PetscReal   g[2] = {std::sin(t), std::cos(2 * t)}, dg[2] = {std::cos(t), -2 * std::sin(2 * t)};
  const PetscScalar e0 = y[0] - g[0], e1 = y[1] - g[1];
  f[0] = -e0 + e1 + dg[0];
  f[1] = -e0 - e1 + dg[1];
}

/* F(t, U, U') = U': U' = 0 in implicit form (TSSetIFunction), for checks of how a TS type takes it. */
inline PetscErrorCode ZeroRateIFunction(TS, PetscReal, Vec, Vec Udot, Vec F, void *)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(Udot, F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TSSetFunctionDomainError callback refusing any state more than P::hlim (> 0; 0: none) past the
   step's start, P the TS's application context: a stage that far is rejected, so no step longer
   than about hlim survives. */
template <class P>
PetscErrorCode RejectBeyondStepLimit(TS ts, PetscReal t, Vec, PetscBool *accept)
{
  P        *p;
  PetscReal tn;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &p));
  PetscCall(TSGetTime(ts, &tn));
  *accept = (PetscBool) !(p->hlim > 0 && t - tn > p->hlim * (1 + 1e-12));
  PetscFunctionReturn(PETSC_SUCCESS);
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
