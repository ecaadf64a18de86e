#pragma once
/* Radau IIA (3 stages, order 5) registered as the PETSc TS type "radauiia": the method of Hairer &
   Wanner's RADAU5 (Solving ODEs II, §IV.8) with step control through TSAdapt. Problems are given
   with TSSetIFunction/TSSetIJacobian (or TSSetRHSFunction/TSSetRHSJacobian) and must be linearly
   implicit, F(t, U, U') = M U' - f(t, U) with a constant nonsingular M. See docs/radau_iia.md.

   The type is not called "radau5": that is PETSc's TSRADAU5 (the wrapper of Hairer's code).
   TurgorTSRegisterAll() registers "radau5" as an alias only where PETSc lacks its own; code should
   use TSRADAUIIA.

   A C header: the functions have C linkage (PETSC_EXTERN), callable from C and C++. */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

#include <turgor/ts/ts_register.h> /* TurgorTSRegisterAll() */

#define TSRADAUIIA "radauiia"

/* Work done by a radauiia TS since the first step of its current TSSolve(): IJacobian (or
   RHSJacobian) calls, simplified Newton iterations, KSPSolve() calls. NULL pointers are skipped;
   errors if ts is not of type radauiia. */
PETSC_EXTERN PetscErrorCode TSRadauIIAGetCounters(TS ts, PetscInt *jacobian_evals, PetscInt *newton_its, PetscInt *linear_solves);

/* Defaults set through the API, PETSc style: call them after TSSetType() and before
   TSSetFromOptions(), so that the command-line options (named beside each) still override them.
   The setters are a silent no-op on a TS of another type (PetscTryMethod); the getters error there
   (PetscUseMethod). Values out of range are errors naming the value.

   Jacobian reuse theta in [0, 1) (-ts_radauiia_jacobian_reuse, default 0.001): after an accepted
   step J is kept for the next one while the simplified Newton contraction rate stays <= theta.
   RADAU5 advises 0.1 when Jacobians are expensive. */
PETSC_EXTERN PetscErrorCode TSRadauIIASetJacobianReuse(TS ts, PetscReal theta);
PETSC_EXTERN PetscErrorCode TSRadauIIAGetJacobianReuse(TS ts, PetscReal *theta);

/* Newton tolerance kappa in (0, 1) (-ts_radauiia_newton_tol): Newton stops when its estimated error
   is below kappa times the error tolerance. Default (and PETSC_DEFAULT, or the option value
   "default"): RADAU5's rule for the TS's tolerances, evaluated at every step,
   kappa = max(10 u / rtol, min(0.03, sqrt(rtol'))) with rtol' = 0.1 rtol^(2/3) (docs/radau_iia.md);
   e.g. 0.0147 at rtol = 1e-4, 6.8e-4 at rtol = 1e-8. The getter returns the value in effect. */
PETSC_EXTERN PetscErrorCode TSRadauIIASetNewtonTolerance(TS ts, PetscReal kappa);
PETSC_EXTERN PetscErrorCode TSRadauIIAGetNewtonTolerance(TS ts, PetscReal *kappa);

/* Simplified Newton iterations per step attempt, >= 1 (-ts_radauiia_newton_max_it, default 7). */
PETSC_EXTERN PetscErrorCode TSRadauIIASetNewtonMaxIterations(TS ts, PetscInt max_it);
PETSC_EXTERN PetscErrorCode TSRadauIIAGetNewtonMaxIterations(TS ts, PetscInt *max_it);

/* Functions composed on a TS of type radauiia (PetscObjectComposeFunction), removed when its type
   changes. Code that must work whichever TS type it gets can ask for one with
   PetscObjectQueryFunction() (e.g. "TSRadauIIASetJacobianReuse_C": the Jacobian reuse control
   exists) instead of comparing type names, which also covers the radau5 alias:
     "TSRadauIIAGetCounters_C"
     "TSRadauIIASetJacobianReuse_C"        "TSRadauIIAGetJacobianReuse_C"
     "TSRadauIIASetNewtonTolerance_C"      "TSRadauIIAGetNewtonTolerance_C"
     "TSRadauIIASetNewtonMaxIterations_C"  "TSRadauIIAGetNewtonMaxIterations_C" */

/* The constants the implementation uses, for tests and documentation. Lambda = Tinv Ainv T is
   block diagonal: gamma (the real eigenvalue of Ainv) and the 2x2 block [[alpha, beta], [-beta, alpha]]
   of the complex pair alpha +- i beta. The embedded error estimate is
   (M - h gamma0 J)^-1 [gamma0 h f(t_n, U_n) + M (e_1 Z_1 + e_2 Z_2 + e_3 Z_3)], gamma0 = 1/gamma. */
typedef struct {
  PetscReal c[3], b[3], A[3][3], Ainv[3][3];
  PetscReal T[3][3], Tinv[3][3], Lambda[3][3];
  PetscReal gamma, alpha, beta, gamma0;
  PetscReal e[3];
} TSRadauIIATableau;

PETSC_EXTERN PetscErrorCode TSRadauIIAGetTableau(TSRadauIIATableau *tableau);
