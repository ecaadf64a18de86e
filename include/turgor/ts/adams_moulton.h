#pragma once
/* Variable-order, variable-step Adams-Moulton predictor-corrector with functional (fixed-point)
   iteration, registered as the PETSc TS type "am": the method of SUNDIALS CVODE's CV_ADAMS with
   functional iteration (Nordsieck array, orders 1..12, Milne error estimate), with the step size
   chosen by TSAdapt. Needs no Jacobian. Problems are given as U' = f(t, U) with
   TSSetRHSFunction(); an IFunction is not supported. See docs/adams_moulton.md. */
#include <turgor/petsc_compat.h>
#include <petscts.h>
#include <turgor/ts/ts_register.h> /* TurgorTSRegisterAll() registers it */

#define TSAM "am"

/* Work done by an am TS since the first step of its current TSSolve(): fixed-point (functional)
   iterations, i.e. corrector evaluations of f; attempts rejected because the fixed point did not
   converge; and the order the next step will use (CVODE's "current order"). NULL pointers are
   skipped; errors if ts is not of type am. */
PetscErrorCode TSAMGetCounters(TS ts, PetscInt *fixed_point_its, PetscInt *fixed_point_failures, PetscInt *current_order);
