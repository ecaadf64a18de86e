#pragma once
/* Registration of everything pluggable in turgor (src/app/register_all.cpp: the top of the library,
   which names the concrete types of every other folder): turgor's TS types, physics terms,
   materials, tissue generators and run modes. Call once after PetscInitialize(); calling it again
   is harmless. C linkage: callable from C through <turgor/turgor.h>. */
#include <turgor/core/petsc_compat.h>

PETSC_EXTERN PetscErrorCode TurgorRegisterAll(void);
