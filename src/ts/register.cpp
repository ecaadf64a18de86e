/* TurgorRegisterAll(): turgor's TS types with PETSc's TSRegister(). */
#include <turgor/ts_register.h>
#include <turgor/ts_am.h>
#include <turgor/ts_radau5.h>
#include "ts_types_internal.h"

namespace {

PetscBool registered = PETSC_FALSE; /* PETSc-style registration flag, cleared at PetscFinalize() */

PetscErrorCode TurgorUnregister(void)
{
  PetscFunctionBeginUser;
  registered = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode TurgorTSRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSRegister(TSRADAU5, TSCreate_Radau5));
  PetscCall(TSRegister(TSAM, TSCreate_AM));
  PetscCall(PetscRegisterFinalize(TurgorUnregister));
  registered = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
