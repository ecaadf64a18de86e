static const char help[] = "turgor: mechanics of plant tissue from single cells to organs.\n"
                           "\n"
                           "  turgor                      (the seed's bending bar, FE^2: config/bending_bar_fe2.yaml)\n"
                           "  turgor -mode fine -options_file_yaml config/bending_bar_fine.yaml [options]\n"
                           "  turgor -mode rve -options_file_yaml config/rve_uniaxial.yaml [options]\n"
                           "\n"
                           "A scene is a PETSc YAML options file (config/*.yaml). Units: µm, µs, ng (1e-12 kg);\n"
                           "forces in µN, 2D stresses in N/m. Every option below is listed with its default;\n"
                           "PETSc's own TS options (-ts_type, -ts_max_time, -ts_rtol, -ts_atol, -ts_dt, ...)\n"
                           "choose the time integrator. Outputs go to -output_dir (default ./out).\n"
                           "\n"
                           "Modes:\n"
                           "  fine   full fine-scale run: wall (DEM) + cell fluid (SPH) particles in a DMSwarm\n"
                           "  rve    one material point (RVE or closed form) along a strain path: stress, density, tangents\n"
                           "  fe2    (default) coarse Q1 model on DMPlex whose stress comes from RVEs at the quadrature points\n\n";

#include <turgor/turgor.hpp>

/* A misspelled option in a scene must not pass unnoticed. */
static PetscErrorCode WarnUnusedOptions(void)
{
  PetscInt n;
  char   **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "WARNING: option -%s%s%s was not used (misspelled, or not for -mode?)\n", names[k], values[k] ? " " : "",
                          values[k] ? values[k] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Configure, set up, and (unless -help: every object is then configured, so all options are
   listed, but nothing is solved) solve and summarise the chosen mode. */
static PetscErrorCode Run(MPI_Comm comm)
{
  std::unique_ptr<turgor::Simulation> sim;
  char                                mode[64] = "fe2"; /* the default scene: the seed's bending bar with FE^2 */
  PetscBool                           help;
  PetscFunctionBeginUser;
  const std::string modes = "What to run: " + turgor::SimulationNames();
  PetscOptionsBegin(comm, NULL, "turgor", "turgor");
  PetscCall(PetscOptionsString("-mode", modes.c_str(), "turgor", mode, mode, sizeof mode, NULL));
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

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll()); /* TS types, physics terms, materials, tissues, modes */
  PetscCall(Run(PETSC_COMM_WORLD));
  PetscCall(WarnUnusedOptions());
  PetscCall(PetscFinalize());
  return 0;
}
