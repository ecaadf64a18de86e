#include <turgor/core/options.h>
#include <turgor/core/petsc_compat.h>

namespace turgor {

PetscErrorCode CheckNotEmpty(MPI_Comm comm, const char name[], const char known[])
{
  PetscBool given, set;
  char      value[8];
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &given));
  if (!given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscOptionsGetString(NULL, NULL, name, value, sizeof value, &set));
  PetscCheck(set && value[0], comm, PETSC_ERR_ARG_WRONG, "Option %s: no value given (%s)", name, known);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
