#pragma once
/* Tissue geometry: the regular grid of square cells of the seed paper (TW 562 §5), with shared
   walls discretised by springs and each cell filled with a square lattice of SPH particles. */
#include <turgor/particles/particles.h>
#include <string>
#include <vector>

namespace turgor {

/* Geometry and particle masses of a square-cell tissue, read from options with prefix tissue_.
   Units: µm, µs, ng (1e-12 kg); see docs/model.md. */
struct TissueSpec {
  PetscInt  cells_x          = 16;
  PetscInt  cells_y          = 16;
  PetscReal cell_size        = 25.0; /* µm */
  PetscInt  springs_per_side = 2;
  PetscInt  fluid_per_cell   = 16;   /* a square number k*k: k x k lattice per cell */
  PetscReal wall_mass        = 0.5;  /* ng, m_DEM */
  PetscReal fluid_density    = 0.01; /* ng/µm², 2D density = 1000 kg/m³ x 10 µm thickness */
  PetscReal fluid_mass       = 0.0;  /* ng, m_SPH; 0 means fluid_density * cell area / fluid_per_cell */

  PetscErrorCode SetFromOptions(MPI_Comm comm);
  PetscReal      FluidParticleMass() const;
};

/* A generated tissue: reference positions X, constant particle data, and per-cell wall polygons. */
struct Tissue {
  ParticleSet                        particles;
  std::vector<PetscReal>             X;          /* [2n] reference positions */
  std::vector<PetscReal>             V;          /* [2n] initial velocities; empty means at rest */
  std::vector<std::vector<PetscInt>> cell_walls; /* wall particles of each cell, counter-clockwise */
  std::vector<std::vector<int>>      cell_wall_images; /* periodic tissues: the image of each ring point */
  PetscReal                          lo[2] = {0, 0}, hi[2] = {0, 0}; /* bounding box of X */
  PetscReal                          period[2] = {0, 0};             /* periodic cell [0,Lx) x [0,Ly); 0: not periodic */

  PetscInt NumCells() const { return (PetscInt)cell_walls.size(); }
  /* Build a tissue by hand (tests, custom geometries): add particles and springs, then Finalize(),
     which sets global ids, clears the clamps and computes the bounding box. */
  PetscInt AddParticle(PetscReal x, PetscReal y, PetscReal mass, ParticleKind kind, PetscInt cell = -1);
  void     AddSpring(PetscInt i, PetscInt j); /* rest length = current distance */
  void     Finalize();
  /* Wall particle closest to the point (px, py). */
  PetscInt ClosestWallParticle(PetscReal px, PetscReal py) const;
  /* Clamp (fix) the wall particles on the named sides: any of left, right, bottom, top; "none"
     clamps nothing. Unknown names are an error naming `option`. */
  PetscErrorCode Clamp(MPI_Comm comm, const std::vector<std::string> &sides, const char *option);
};

PetscErrorCode GenerateSquareGridTissue(MPI_Comm comm, const TissueSpec &spec, Tissue *tissue);
/* The same grid as one period of an infinite tissue (an RVE): the top row and right column of wall
   points are the periodic images of the bottom row and left column, so springs that cross the
   boundary bond to an image (Spring::image); the corner particle at the origin is fixed. */
PetscErrorCode GeneratePeriodicSquareGridTissue(MPI_Comm comm, const TissueSpec &spec, Tissue *tissue);

/* Signed area of the polygon through the given particles (counter-clockwise positive). */
PetscReal PolygonArea(const std::vector<PetscInt> &ring, const PetscReal *x);

} // namespace turgor
