/* The C entry point of <turgor/turgor.h> that is not a TS type's own: TurgorRunMode(). It runs a
   mode as src/app/main.cpp does and stops every C++ exception at the C boundary. */
#include <turgor/turgor.h>
#include <turgor/run/simulation.h>
#include "c_boundary.h"
#include <memory>
#include <string>

namespace {

/* Configure, set up, and (unless -help: every object is then configured, so all options are
   listed, but nothing is solved) solve and summarise the chosen mode. */
PetscErrorCode RunMode(MPI_Comm comm, const char default_mode[])
{
  std::unique_ptr<turgor::Simulation> sim;
  char                                mode[64] = "fe2"; /* the executable's default: the seed's bending bar with FE^2 */
  size_t                              len;
  PetscBool                           help;
  PetscFunctionBeginUser;
  PetscCall(TurgorRegisterAll());
  if (default_mode) {
    PetscCall(PetscStrlen(default_mode, &len));
    PetscCheck(len > 0 && len < sizeof mode, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "TurgorRunMode(): mode '%s' must have 1 to %d characters", default_mode,
               (int)sizeof mode - 1);
    PetscCall(PetscStrncpy(mode, default_mode, sizeof mode));
  }
  const std::string modes = "What to run: " + turgor::SimulationNames();
  PetscOptionsBegin(comm, NULL, "turgor", "turgor");
  PetscCall(PetscOptionsString("-mode", modes.c_str(), "TurgorRunMode", mode, mode, sizeof mode, NULL));
  PetscOptionsEnd();
  PetscCall(turgor::SimulationCreate(comm, mode, &sim));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(sim->SetFromOptions());
  PetscCall(sim->SetUp());
  if (help) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(sim->Solve());
  PetscCall(sim->WriteSummary());
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode TurgorRunMode(MPI_Comm comm, const char mode[])
{
  PetscFunctionBeginUser;
  PetscCall(turgor::CatchExceptions(PETSC_FUNCTION_NAME, __LINE__, __FILE__, [&] { return RunMode(comm, mode); }));
  PetscFunctionReturn(PETSC_SUCCESS);
}
