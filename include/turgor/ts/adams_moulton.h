#pragma once
/* Variable-order, variable-step Adams-Moulton predictor-corrector with functional (fixed-point)
   iteration, registered as the PETSc TS type "am": the method of SUNDIALS CVODE's CV_ADAMS with
   functional iteration (Nordsieck array, orders 1..12, Milne error estimate), with the step size
   chosen by TSAdapt. Needs no Jacobian. Problems are given as U' = f(t, U) with
   TSSetRHSFunction(); an IFunction is not supported. See docs/adams_moulton.md.
   A C header: the functions have C linkage (PETSC_EXTERN), callable from C and C++. */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>
#include <turgor/ts/ts_register.h> /* TurgorTSRegisterAll() registers it */

#define TSAM "am"

/* Work done by an am TS since the first step of its current TSSolve(): fixed-point (functional)
   iterations, i.e. corrector evaluations of f; attempts rejected because the fixed point did not
   converge; and the order the next step will use (CVODE's "current order"). NULL pointers are
   skipped; errors if ts is not of type am. */
PETSC_EXTERN PetscErrorCode TSAMGetCounters(TS ts, PetscInt *fixed_point_its, PetscInt *fixed_point_failures, PetscInt *current_order);

/* Defaults set through the API, PETSc style: call them after TSSetType() and before
   TSSetFromOptions(), so that the command-line options (named beside each) still override them,
   and before TSSolve(). The setters are a silent no-op on a TS of another type (PetscTryMethod);
   the getters error there (PetscUseMethod). Values out of range are errors naming the value. */

/* Highest order used, 1..12 (-ts_am_max_order, default 12, CVODE's limit for Adams). */
PETSC_EXTERN PetscErrorCode TSAMSetMaxOrder(TS ts, PetscInt max_order);
PETSC_EXTERN PetscErrorCode TSAMGetMaxOrder(TS ts, PetscInt *max_order);

/* PETSC_TRUE: no order selection; the order rises to the maximum as the start-up allows, then
   stays there (-ts_am_fixed_order, default PETSC_FALSE). */
PETSC_EXTERN PetscErrorCode TSAMSetFixedOrder(TS ts, PetscBool fixed);
PETSC_EXTERN PetscErrorCode TSAMGetFixedOrder(TS ts, PetscBool *fixed);

/* Fixed-point iterations (f evaluations) per step attempt, >= 1 (-ts_am_max_iterations, default
   3, CVODE's maxcor). */
PETSC_EXTERN PetscErrorCode TSAMSetMaxIterations(TS ts, PetscInt max_it);
PETSC_EXTERN PetscErrorCode TSAMGetMaxIterations(TS ts, PetscInt *max_it);

/* Fixed-point failures allowed in one step, >= 1; the solve stops with
   TS_DIVERGED_NONLINEAR_SOLVE when they are reached (-ts_am_max_conv_fails, default 10, CVODE's
   maxncf). */
PETSC_EXTERN PetscErrorCode TSAMSetMaxConvergenceFailures(TS ts, PetscInt max_fails);
PETSC_EXTERN PetscErrorCode TSAMGetMaxConvergenceFailures(TS ts, PetscInt *max_fails);

/* Functions composed on a TS of type am (PetscObjectComposeFunction), removed when its type
   changes; PetscObjectQueryFunction() on one tells whether a TS has the control:
     "TSAMGetCounters_C"
     "TSAMSetMaxOrder_C"                "TSAMGetMaxOrder_C"
     "TSAMSetFixedOrder_C"              "TSAMGetFixedOrder_C"
     "TSAMSetMaxIterations_C"           "TSAMGetMaxIterations_C"
     "TSAMSetMaxConvergenceFailures_C"  "TSAMGetMaxConvergenceFailures_C" */
