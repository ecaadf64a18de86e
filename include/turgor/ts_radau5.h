#pragma once
/* Radau IIA (3 stages, order 5) registered as the PETSc TS type "radau5": the method of Hairer &
   Wanner's RADAU5 (Solving ODEs II, §IV.8) with step control through TSAdapt. Problems are given
   with TSSetIFunction/TSSetIJacobian (or TSSetRHSFunction/TSSetRHSJacobian) and must be linearly
   implicit, F(t, U, U') = M U' - f(t, U) with a constant nonsingular M. See docs/radau5.md. */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

#include <turgor/ts_register.h> /* TurgorRegisterAll() */

#define TSRADAU5 "radau5"

/* Work done by a radau5 TS since the first step of its current TSSolve(): IJacobian (or
   RHSJacobian) calls, simplified Newton iterations, KSPSolve() calls. NULL pointers are skipped;
   errors if ts is not of type radau5. */
PetscErrorCode TSRadau5GetCounters(TS ts, PetscInt *jacobian_evals, PetscInt *newton_its, PetscInt *linear_solves);

/* The constants the implementation uses, for tests and documentation. Lambda = Tinv Ainv T is
   block diagonal: gamma (the real eigenvalue of Ainv) and the 2x2 block [[alpha, beta], [-beta, alpha]]
   of the complex pair alpha +- i beta. The embedded error estimate is
   (M - h gamma0 J)^-1 [gamma0 h f(t_n, U_n) + M (e_1 Z_1 + e_2 Z_2 + e_3 Z_3)], gamma0 = 1/gamma. */
typedef struct {
  PetscReal c[3], b[3], A[3][3], Ainv[3][3];
  PetscReal T[3][3], Tinv[3][3], Lambda[3][3];
  PetscReal gamma, alpha, beta, gamma0;
  PetscReal e[3];
} TSRadau5Tableau;

PetscErrorCode TSRadau5GetTableau(TSRadau5Tableau *tableau);
