/* The C entry point of <turgor/turgor.h> that is not a TS type's own: TurgorRunMode(). */
#include <turgor/turgor.h>
#include <turgor/modes/run_mode.h>

PetscErrorCode TurgorRunMode(MPI_Comm comm, const char mode[])
{
  int status;
  PetscFunctionBeginUser;
  PetscCall(TurgorRegisterAll());
  PetscCall(turgor::RunMode(comm, mode, &status));
  PetscCheck(status == 0, comm, PETSC_ERR_SIG, "TurgorRunMode(): the run was interrupted (SIGINT/SIGTERM); its summary.json says how far it got");
  PetscFunctionReturn(PETSC_SUCCESS);
}
