#pragma once
/* A run mode (-mode): configure, set up, solve, summarise. A new mode is one file (a class derived
   from Simulation, or from TimeRun for a time-dependent one) plus one line in
   src/app/register_all.cpp: SimulationRegister("name", CreateInstance<Simulation, Mode>). */
#include <turgor/core/registry.h>
#include <memory>
#include <string>

namespace turgor {

class Simulation {
public:
  virtual ~Simulation() = default;
  /* Every option of the mode is read here (so that -help lists them all after SetUp). */
  virtual PetscErrorCode SetFromOptions() = 0;
  virtual PetscErrorCode SetUp()          = 0;
  virtual PetscErrorCode Solve()          = 0;
  /* summary.json (status "completed", or "interrupted" after SIGINT/SIGTERM) and the final
     report; call after Solve */
  virtual PetscErrorCode WriteSummary() = 0;
  /* After an error in any phase (already reported by PETSc): summary.json with `status` "failed"
     (or "interrupted": the error was SIGINT/SIGTERM's) and the reason, if the run has an output
     directory by then. Not collective (the failure may be one rank's): rank 0 writes what it
     knows. */
  virtual PetscErrorCode WriteFailure(const std::string &reason, const char status[]) { return PETSC_SUCCESS; }
  /* The run stopped early on SIGINT/SIGTERM (its summary says "interrupted"). */
  virtual bool Interrupted() const { return false; }
  /* The mode continues from checkpoints (-restart) and writes them (-checkpoint_interval): a mode that
     does not refuses those options before any work. */
  virtual bool Checkpoints() const { return false; }
};

using SimulationCreator = Registry<Simulation>::Creator;
PetscErrorCode SimulationRegister(const char name[], SimulationCreator create);
PetscErrorCode SimulationCreate(MPI_Comm comm, const std::string &mode, std::unique_ptr<Simulation> *sim);
std::string    SimulationNames();

} // namespace turgor
