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
                           "  fine   full fine-scale run in a DMSwarm: wall (DEM) + cell fluid (SPH) particles, or polygonal cells\n"
                           "  rve    one material point (RVE or closed form) along a strain path: stress, density, tangents\n"
                           "  fe2    (default) coarse Q1 or Q2 model on DMPlex whose stress comes from RVEs at the quadrature points\n"
                           "  fe2_static  the coarse model's static equilibrium under the scene's loads (SNES, load stepping)\n"
                           "  eigen  SLEPc spectra of the coarse stiffness: frequencies, modes, the explicit stability limit\n\n";

#include <turgor/turgor.hpp>
#include <turgor/core/errors.h>
#include <turgor/modes/run_mode.h>
#include <turgor/modes/simulation.h>
#include <turgor/core/yaml_check.h>

int main(int argc, char **argv)
{
  int                 status = 0;
  turgor::ErrorRecord errors; /* messages of ranks other than the first, printed only if needed */
  /* a scene that does not parse is reported with its line before PETSc reads it (PETSc's message
     has none) */
  if (!turgor::CheckYAMLScenes(argc, argv)) return 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(turgor::PushErrorHandler(&errors));
  PetscCall(turgor::InstallInterruptHandler());
  PetscCall(TurgorRegisterAll()); /* TS types, physics terms, materials, tissues, modes */
  {
    std::unique_ptr<turgor::Simulation> sim;                                           /* destroyed once every rank has ended: its files close collectively */
    if (turgor::RunMode(PETSC_COMM_WORLD, NULL, &status, &sim) && !status) status = 1; /* 130: interrupted */
    PetscCall(turgor::FinishRanks(PETSC_COMM_WORLD, status, errors, 20.0));            /* long enough for the first rank to write its failure report */
  }
  PetscCall(PetscFinalize());
  return status;
}
