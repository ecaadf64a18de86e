#pragma once
/* Constructors of turgor's TS types, for TSRegister() in ts_register.cpp only (not installed). */
#include <petscts.h>

PetscErrorCode TSCreate_RadauIIA(TS ts);
PetscErrorCode TSCreate_AM(TS ts);
PetscErrorCode TSCreate_Verlet(TS ts);
PetscErrorCode TSCreate_LSRK(TS ts);
