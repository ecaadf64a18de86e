#pragma once
/* One run, start to end, as the turgor executable and TurgorRunMode() run it. */
#include <turgor/core/petsc_compat.h>
#include <memory>

namespace turgor {

class Simulation;

/* Runs one mode as the turgor executable does: -mode (default `mode`, NULL: fe2), -strict, set-up,
   the unused-option check, solve, summary; after a failure in any phase it leaves summary.json
   with status "failed". *status: 0 completed, 130 interrupted (SIGINT/SIGTERM: after a step, or
   an error raised for it in set-up or inside a step, which is returned too); a failure is
   returned as the error. `keep` (may be NULL): the simulation is handed over instead of being
   destroyed here, so that the caller destroys it once every rank has ended (its destructors close
   files collectively: after a failure on one rank only they would wait for the others). */
PetscErrorCode RunMode(MPI_Comm comm, const char mode[], int *status, std::unique_ptr<Simulation> *keep = nullptr);

} // namespace turgor
