#include <turgor/tissue/tissue.h>
#include <cmath>

namespace turgor {

PetscErrorCode TissueSpec::SetFromOptions(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_", "Tissue geometry (square cells with shared walls; units µm, ng)", "turgor");
  PetscCall(PetscOptionsInt("-cells_x", "Cells in x", "TissueSpec", cells_x, &cells_x, NULL));
  PetscCall(PetscOptionsInt("-cells_y", "Cells in y", "TissueSpec", cells_y, &cells_y, NULL));
  PetscCall(PetscOptionsReal("-cell_size", "Cell side length [µm]", "TissueSpec", cell_size, &cell_size, NULL));
  PetscCall(PetscOptionsInt("-springs_per_side", "Wall springs along one cell side", "TissueSpec", springs_per_side, &springs_per_side, NULL));
  PetscCall(PetscOptionsInt("-fluid_per_cell", "SPH particles per cell (a square number k^2)", "TissueSpec", fluid_per_cell, &fluid_per_cell, NULL));
  PetscCall(PetscOptionsReal("-wall_particle_mass", "Wall (DEM) particle mass m_DEM [ng]", "TissueSpec", wall_mass, &wall_mass, NULL));
  PetscCall(PetscOptionsReal("-fluid_density", "2D fluid density = 3D density x thickness [ng/µm^2]", "TissueSpec", fluid_density, &fluid_density, NULL));
  PetscCall(PetscOptionsReal("-fluid_particle_mass", "SPH particle mass m_SPH [ng]; 0: fluid_density x cell area / fluid_per_cell", "TissueSpec", fluid_mass, &fluid_mass, NULL));
  PetscOptionsEnd();

  PetscCheck(cells_x >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cells_x = %" PetscInt_FMT ": must be >= 1", cells_x);
  PetscCheck(cells_y >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cells_y = %" PetscInt_FMT ": must be >= 1", cells_y);
  PetscCheck(cell_size > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cell_size = %g: must be > 0", (double)cell_size);
  PetscCheck(springs_per_side >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_springs_per_side = %" PetscInt_FMT ": must be >= 1", springs_per_side);
  PetscInt k = (PetscInt)std::lround(std::sqrt((double)fluid_per_cell));
  PetscCheck(fluid_per_cell >= 0 && k * k == fluid_per_cell, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_per_cell = %" PetscInt_FMT ": must be a square number (k x k lattice per cell)", fluid_per_cell);
  PetscCheck(wall_mass > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_wall_particle_mass = %g: a particle mass must be > 0", (double)wall_mass);
  PetscCheck(fluid_density > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_density = %g: must be > 0", (double)fluid_density);
  PetscCheck(std::isfinite(fluid_mass) && fluid_mass >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_particle_mass = %g: a particle mass must be > 0 (or 0 to derive it from -tissue_fluid_density)", (double)fluid_mass);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal TissueSpec::FluidParticleMass() const
{
  if (fluid_mass > 0) return fluid_mass;
  if (fluid_per_cell == 0) return 0;
  return fluid_density * cell_size * cell_size / (PetscReal)fluid_per_cell;
}

} // namespace turgor
