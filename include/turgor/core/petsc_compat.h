#pragma once
/* Small shims so the code reads like current PETSc while building on Debian 12's PETSc 3.18. */
#include <petscsys.h>
#include <petscversion.h>

#if PETSC_VERSION_LT(3, 19, 0)
  #define PETSC_SUCCESS 0
#endif

#if PETSC_VERSION_LT(3, 19, 0)
/* public from PETSc 3.19 on; 3.18 declares it only in a private header */
PETSC_EXTERN PetscErrorCode PetscObjectStateGet(PetscObject, PetscObjectState *);
#endif
