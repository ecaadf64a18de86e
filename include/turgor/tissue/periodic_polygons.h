#pragma once
/* The cells of a periodic polygonal tissue (the polygon RVE's geometry): K cells tiling a periodic
   box, from seeds in the box and their eight periodic images -- a Voronoi tessellation of random
   seeds (with Lloyd steps), or of a square or hexagonal lattice for verification -- each cell whole
   (unwrapped around its seed, so that it may reach over the box's faces) and shrunk by the bar
   radius (and half of -prve_gap), so that neighbours, across the faces too, are 2 r (+ gap) apart. */
#include <turgor/core/parameters.h>
#include <turgor/tissue/polygon_tissue.h>
#include <vector>

namespace turgor {

enum class PeriodicLattice {
  Voronoi,
  Square,
  Hexagonal
};

/* Options -prve_lattice, -prve_cells, -prve_cell_size, -prve_seed, -prve_lloyd_steps, -prve_halo_margin, -prve_gap (prefix prve_). */
struct PeriodicPolygonSpec {
  PeriodicLattice lattice     = PeriodicLattice::Voronoi;
  PetscInt        cells       = 16; /* K: a square number for square, 4 m^2 for hexagonal */
  PetscReal       cell_size   = 25; /* µm: the square root of the mean cell area (before shrinking) */
  PetscInt        seed        = 1;  /* Voronoi: the random seeds' seed (same seed: same cells, bit for bit) */
  PetscInt        lloyd_steps = 2;  /* Voronoi: each seed moved to its cell's centroid, this many times */
  PetscReal       halo_margin = 0;  /* µm beyond the interactions' reach kept as periodic images; 0: half the cell size */
  PetscReal       gap         = 0;  /* µm between neighbouring cells' bar surfaces (a middle lamella's thickness); 0: touching */

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
  const char    *LatticeName() const;
};

/* The cells' rings (counter-clockwise, shrunk by bar_radius + gap / 2) and the box period[2]; the box is
   [0, period[0]) x [0, period[1]) and every cell's seed lies in it. */
PetscErrorCode PeriodicPolygonRings(MPI_Comm comm, const PeriodicPolygonSpec &spec, PetscReal bar_radius, std::vector<PolygonRing> *rings, PetscReal period[2]);

} // namespace turgor
