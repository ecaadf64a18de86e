#pragma once
/* A run mode (-mode): configure, set up, solve, summarise. A new mode is one file (a class derived
   from Simulation, or from TimeRun for a time-dependent one) plus one line in
   src/core/register_all.cpp: SimulationRegister("name", CreateInstance<Simulation, Mode>). */
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
  /* summary.json and the final report; call after Solve */
  virtual PetscErrorCode WriteSummary() = 0;
};

using SimulationCreator = Registry<Simulation>::Creator;
PetscErrorCode SimulationRegister(const char name[], SimulationCreator create);
PetscErrorCode SimulationCreate(MPI_Comm comm, const std::string &mode, std::unique_ptr<Simulation> *sim);
std::string    SimulationNames();

} // namespace turgor
