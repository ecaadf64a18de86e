#pragma once
/* Constructors of turgor's TS types, for TSRegister() in register.cpp only (not installed). */
#include <petscts.h>

PetscErrorCode TSCreate_Radau5(TS ts);
PetscErrorCode TSCreate_AM(TS ts);
