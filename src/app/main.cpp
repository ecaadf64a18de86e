static const char help[] = "turgor: mechanics of plant tissue from single cells to organs.\n"
                           "\n"
                           "  turgor                      (the seed's bending bar, FE^2: config/bending_bar_fe2.yaml)\n"
                           "  turgor -mode fine -options_file_yaml config/bending_bar_fine.yaml [options]\n"
                           "  turgor -mode rve -options_file_yaml config/rve_uniaxial.yaml [options]\n"
                           "\n"
                           "A scene is a PETSc YAML options file (config/*.yaml). Units: µm, µs, ng (1e-12 kg);\n"
                           "forces in µN, 2D stresses in N/m. Every option below is listed with its default;\n"
                           "PETSc's own TS options (-ts_type, -ts_max_time, -ts_rtol, -ts_atol, -ts_dt, ...)\n"
                           "choose the time integrator. Outputs go to -output_dir (default ./out), which must be\n"
                           "empty or new unless -output_overwrite. Options nobody reads are reported before the\n"
                           "run starts (an error with -strict). Exit status: 0 completed, 1 failed, 130 interrupted.\n"
                           "\n"
                           "Modes:\n"
                           "  fine   full fine-scale run: wall (DEM) + cell fluid (SPH) particles in a DMSwarm\n"
                           "  rve    one material point (RVE or closed form) along a strain path: stress, density, tangents\n"
                           "  fe2    (default) coarse Q1 model on DMPlex whose stress comes from RVEs at the quadrature points\n\n";

#include <turgor/turgor.h>
#include <turgor/core/errors.h>
#include <turgor/core/yaml_check.h>

/* Options nobody read are reported before any work (misspelled, or not for this -mode): an error
   with -strict, a warning otherwise. */
static PetscErrorCode CheckUnusedOptions(MPI_Comm comm, PetscBool strict)
{
  PetscInt    n;
  char      **names, **values;
  std::string list;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++) {
    list += std::string(list.empty() ? "" : ", ") + "-" + names[k] + (values[k] ? std::string(" ") + values[k] : std::string());
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  if (list.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(!strict, comm, PETSC_ERR_ARG_WRONG, "Options not used by -mode (misspelled, or for another mode): %s", list.c_str());
  PetscCall(PetscPrintf(comm, "WARNING: options not used by this -mode (misspelled, or for another mode; -strict makes this an error): %s\n", list.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Configure, set up, and (unless -help: every object is then configured, so all options are
   listed, but nothing is solved) solve and summarise the chosen mode. */
static PetscErrorCode Run(MPI_Comm comm, std::unique_ptr<turgor::Simulation> &sim)
{
  char      mode[64] = "fe2"; /* the default scene: the seed's bending bar with FE^2 */
  PetscBool help, strict = PETSC_FALSE, set;
  PetscFunctionBeginUser;
  try {
    const std::string modes = "What to run: " + turgor::SimulationNames();
    PetscOptionsBegin(comm, NULL, "turgor", "turgor");
    PetscCall(PetscOptionsString("-mode", modes.c_str(), "turgor", mode, mode, sizeof mode, &set));
    PetscCall(PetscOptionsBool("-strict", "Unused (misspelled) options are an error, not a warning", "turgor", strict, &strict, NULL));
    PetscOptionsEnd();
    PetscCheck(mode[0], comm, PETSC_ERR_ARG_WRONG, "Option -mode: empty (known: %s)", turgor::SimulationNames().c_str());
    PetscCall(turgor::SimulationCreate(comm, mode, &sim));
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    PetscCall(sim->SetFromOptions());
    PetscCall(sim->SetUp());
    if (help) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(CheckUnusedOptions(comm, strict));
    PetscCall(sim->Solve());
    PetscCall(sim->WriteSummary());
  }
  TURGOR_CATCH
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  std::unique_ptr<turgor::Simulation> sim;
  PetscErrorCode                      ierr;
  int                                 status = 0;

  /* A scene that does not parse is reported with its line before PETSc reads it (PETSc's message
     has no line number). */
  if (!turgor::CheckYAMLScenes(argc, argv)) return 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(turgor::PushOptionValueErrorHandler());
  PetscCall(turgor::InstallInterruptHandler());
  PetscCall(TurgorRegisterAll()); /* TS types, physics terms, materials, tissues, modes */
  ierr = Run(PETSC_COMM_WORLD, sim);
  if (ierr) {
    /* the error and its trace are printed; leave a summary.json that says so */
    const char *text = NULL;
    char       *specific = NULL;
    (void)PetscErrorMessage(ierr, &text, &specific);
    if (sim) (void)sim->WriteFailure(specific && specific[0] ? specific : (text ? text : "error"));
    status = 1;
  } else if (sim && sim->Interrupted()) status = 130;
  sim.reset();
  PetscCall(PetscFinalize());
  return status;
}
