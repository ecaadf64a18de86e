#pragma once
/* Constructors of turgor's TS types, for TSRegister() in ts_register.cpp, and their shared helpers (not installed). */
#include <petscts.h>

PetscErrorCode TSCreate_RadauIIA(TS ts);
PetscErrorCode TSCreate_AM(TS ts);
PetscErrorCode TSCreate_Verlet(TS ts);
PetscErrorCode TSCreate_LSRK(TS ts);

/* A duplicate of U (same layout) whose array has `room` spare entries after its local part, for a
   right-hand side that uses them as scratch (*array: allocated here, freed by the caller after the
   Vec). The same kind of Vec on every rank (creating one is collective): where no rank asks for
   room, a plain VecDuplicate and *array = NULL. */
PetscErrorCode TurgorVecDuplicateWithRoom(Vec U, PetscInt room, Vec *R, PetscScalar **array);
