#pragma once
/* The regular grid of square cells of the seed paper (TW 562 §5): shared walls discretised by
   springs, each cell filled with a square lattice of SPH particles. */
#include <turgor/core/parameters.h>
#include <turgor/tissue/tissue_generator.h>

namespace turgor {

/* Geometry and particle masses of square cells (prefix tissue_). Units: µm, ng (docs/model.md). */
struct SquareGridSpec {
  PetscInt  cells_x          = 16;
  PetscInt  cells_y          = 16;
  PetscReal cell_size        = 25.0; /* µm */
  PetscInt  springs_per_side = 2;
  PetscInt  fluid_per_cell   = 16;   /* a square number k*k: k x k lattice per cell */
  PetscReal wall_mass        = 0.5;  /* ng, m_DEM */
  PetscReal fluid_density    = 0.01; /* ng/µm², 2D density = 1000 kg/m³ x 10 µm thickness */
  PetscReal fluid_mass       = 0.0;  /* ng, m_SPH; 0 means fluid_density * cell area / fluid_per_cell */

  /* The cell options, and with `layout` also -tissue_cells_x/y (an RVE sets its own number of
     cells, -rve_cells, and leaves those unread so that a stray one is reported as unused). */
  PetscErrorCode SetFromOptions(MPI_Comm comm, bool layout, ParameterList *params = nullptr);
  PetscReal      FluidParticleMass() const;
  /* Particles and springs of nx x ny cells, in floating point (a periodic grid has fewer walls). */
  void Count(PetscReal nx, PetscReal ny, bool periodic, PetscReal *particles, PetscReal *springs) const;
};

PetscErrorCode GenerateSquareGridTissue(MPI_Comm comm, const SquareGridSpec &spec, Tissue *tissue);
/* Rows of that grid (TissueGenerator::GeneratePart): the rows of cells [c0, c1), the rows of cells
   within `distance` of them and one row more on each side, numbered as in the whole grid. */
PetscErrorCode GenerateSquareGridPart(MPI_Comm comm, const SquareGridSpec &spec, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part);
/* The same grid as one period of an infinite tissue (an RVE): the top row and right column of wall
   points are the periodic images of the bottom row and left column, so springs that cross the
   boundary bond to an image (Spring::image); the corner particle at the origin is fixed. */
PetscErrorCode GeneratePeriodicSquareGridTissue(MPI_Comm comm, const SquareGridSpec &spec, Tissue *tissue);

/* -tissue_type square_grid */
class SquareGridGenerator : public TissueGenerator {
public:
  const char    *Name() const override { return "square_grid"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) override { return spec.SetFromOptions(comm, true, params); }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GenerateSquareGridTissue(comm, spec, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscInt       NumCellsOfParts() const override { return spec.cells_x * spec.cells_y; }
  PetscErrorCode GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const override
  {
    return GenerateSquareGridPart(comm, spec, c0, c1, distance, part);
  }

  SquareGridSpec spec;
};

} // namespace turgor
