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

#include <turgor/turgor.h>
#include <turgor/coarse/fe2_run.h>
#include <turgor/material/strain_path_run.h>

/* A misspelled option in a scene must not pass unnoticed. */
static PetscErrorCode WarnUnusedOptions(void)
{
  PetscInt n;
  char   **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "WARNING: option -%s%s%s was not used (misspelled, or not for -mode?)\n", names[k], values[k] ? " " : "", values[k] ? values[k] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One mode: configure, set up, and (unless -help: every object is then configured, so all options
   are listed, but nothing is solved) solve and summarise. Run is FineRun, RVERun or FE2Run. */
template <class Run>
static PetscErrorCode RunMode(MPI_Comm comm, PetscBool help_only)
{
  Run run(comm);
  PetscFunctionBeginUser;
  PetscCall(run.SetFromOptions());
  PetscCall(run.SetUp());
  if (help_only) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(run.Solve());
  PetscCall(run.WriteSummary());
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const char *const modes[] = {"fine", "rve", "fe2"};
  PetscInt          mode    = 2; /* the default scene: the seed's bending bar with FE^2 */
  PetscBool         help_requested;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll()); /* TS types, physics, materials, tissues, modes */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "turgor", "turgor");
  PetscCall(PetscOptionsEList("-mode", "What to run", "turgor", modes, (PetscInt)(sizeof modes / sizeof modes[0]), modes[mode], &mode, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &help_requested));
  switch (mode) {
  case 0:
    PetscCall(RunMode<turgor::FineRun>(PETSC_COMM_WORLD, help_requested));
    break;
  case 1:
    PetscCall(RunMode<turgor::StrainPathRun>(PETSC_COMM_WORLD, help_requested));
    break;
  case 2:
    PetscCall(RunMode<turgor::FE2Run>(PETSC_COMM_WORLD, help_requested));
    break;
  }
  PetscCall(WarnUnusedOptions());
  PetscCall(PetscFinalize());
  return 0;
}
