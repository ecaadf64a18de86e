#pragma once
/* Registration of turgor's own PETSc TS types: radauiia (include/turgor/ts/radau_iia.h), am
   (include/turgor/ts/adams_moulton.h), verlet (include/turgor/ts/velocity_verlet.h) and lsrk
   (include/turgor/ts/low_storage_rk.h). A C header
   (PETSC_EXTERN). */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

/* Registers turgor's TS types with TSRegister(): "radauiia", "am", "verlet" and "lsrk", and "radau5" as an alias of
   "radauiia" only when PETSc was built without its own TSRADAU5 (PETSC_HAVE_RADAU5 undefined), so
   that PETSc's type of that name is never replaced. Call once after PetscInitialize(); calling it
   again is harmless. Registers TS types only. */
PETSC_EXTERN PetscErrorCode TurgorTSRegisterAll(void);
