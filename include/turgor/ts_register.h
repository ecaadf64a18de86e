#pragma once
/* Registration of turgor's own PETSc TS types: radau5 (include/turgor/ts_radau5.h) and am
   (include/turgor/ts_am.h). */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

/* Registers turgor's TS types (radau5, am) with TSRegister(); call once after PetscInitialize().
   Calling it again is harmless. */
PetscErrorCode TurgorTSRegisterAll(void);
