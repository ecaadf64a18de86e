/* TurgorTSRegisterAll(): turgor's TS types with PETSc's TSRegister(). */
#include <turgor/ts/ts_register.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/adapt_dsp.h>
#include <turgor/ts/low_storage_rk.h>
#include <turgor/ts/radau_iia.h>
#include <turgor/ts/velocity_verlet.h>
#include "ts_types_internal.h"

namespace {

PetscBool registered = PETSC_FALSE; /* PETSc-style registration flag, cleared at PetscFinalize() */

PetscErrorCode TurgorTSUnregister(void)
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
  PetscCall(TSRegister(TSRADAUIIA, TSCreate_RadauIIA));
#if !defined(PETSC_HAVE_RADAU5)
  /* "radau5" is the name of PETSc's own TSRADAU5 (its wrapper of Hairer's code), present when PETSc
     is configured with it; TSRegister() would silently replace that type. Only without it is the
     name free, and then it keeps scripts and option files written for turgor's former name working. */
  PetscCall(TSRegister("radau5", TSCreate_RadauIIA));
#endif
  PetscCall(TSRegister(TSAM, TSCreate_AM));
  PetscCall(TSRegister(TSVERLET, TSCreate_Verlet));
  PetscCall(TSRegister(TSLSRK, TSCreate_LSRK));
  /* turgor's "dsp" in the place of PETSc's (the same controller, whose history a checkpoint keeps):
     PETSc's list first, so that its registration cannot come later and replace this one */
  PetscCall(TSAdaptInitializePackage());
  PetscCall(TSAdaptRegister(TSADAPTDSP, TSAdaptCreate_TurgorDSP));
  PetscCall(PetscRegisterFinalize(TurgorTSUnregister));
  registered = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
