#pragma once
/* Profiling helpers: PETSc refuses to register a log stage twice, but a program may run several
   simulations (tests, studies); stages are looked up by name first. */
#include <turgor/core/petsc_compat.h>

namespace turgor {

PetscErrorCode RegisterLogStage(const char *name, PetscLogStage *stage);

} // namespace turgor
