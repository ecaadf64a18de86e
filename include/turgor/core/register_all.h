#pragma once
/* Registration of everything pluggable in turgor (src/core/register_all.cpp): turgor's TS types,
   physics terms, materials, tissue generators and run modes. Call once after PetscInitialize();
   calling it again is harmless. C linkage: callable from C through <turgor/turgor.h>. */
#include <turgor/core/petsc_compat.h>

PETSC_EXTERN PetscErrorCode TurgorRegisterAll(void);
