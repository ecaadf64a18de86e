#pragma once
/* Checks of option values that PETSc's readers let through. */
#include <petscsys.h>

namespace turgor {

/* An error naming `name` (the full option, e.g. "-physics") when it is given with an empty value
   (-physics "" or a bare -physics): PETSc's list readers then report "not set", and the default
   would run in its place. `known` lists what may be given. Collective. */
PetscErrorCode CheckNotEmpty(MPI_Comm comm, const char name[], const char known[]);

} // namespace turgor
