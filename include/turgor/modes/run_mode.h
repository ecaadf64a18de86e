#pragma once
/* One run, start to end, as the turgor executable and TurgorRunMode() run it. */
#include <turgor/core/petsc_compat.h>

namespace turgor {

/* Runs one mode as the turgor executable does: -mode (default `mode`, NULL: fe2), -strict, set-up,
   the unused-option check, solve, summary; after a failure in any phase it leaves summary.json
   with status "failed". *status: 0 completed, 130 interrupted (SIGINT/SIGTERM); a failure is
   returned as the error. */
PetscErrorCode RunMode(MPI_Comm comm, const char mode[], int *status);

} // namespace turgor
