#pragma once
/* A tissue: its particles (wall and fluid), wall springs and cells, whichever generator made it
   (tissue_generator.h). Units: µm, µs, ng (1e-12 kg); see docs/model.md. */
#include <turgor/particles/particles.h>
#include <string>
#include <vector>

namespace turgor {

/* A generated tissue: reference positions X, constant particle data, and per-cell wall polygons. */
struct Tissue {
  ParticleSet                                   particles;
  std::vector<PetscReal>                        X;                              /* [2n] reference positions */
  std::vector<PetscReal>                        V;                              /* [2n] initial velocities; empty means at rest */
  std::vector<std::vector<PetscInt>>            cell_walls;                     /* wall particles of each cell, counter-clockwise */
  std::vector<std::vector<int>>                 cell_wall_images;               /* periodic tissues: the image of each ring point */
  PetscReal                                     lo[2] = {0, 0}, hi[2] = {0, 0}; /* bounding box of X */
  PetscReal                                     period[2] = {0, 0};             /* periodic cell [0,Lx) x [0,Ly); 0: not periodic */
  std::vector<std::pair<std::string, PetscInt>> named_cells;                    /* cells with a name (the plates: "bottom", ...) */
  /* A part of a tissue (TissueGenerator::GeneratePart): the whole tissue's number of each cell here,
     increasing; empty: the whole tissue, numbered as here. Its particles' and springs' numbers are
     ParticleSet::gid and spring_gid, its fluid's ParticleSet::cell the whole tissue's cell. */
  std::vector<PetscInt> cell_gid;

  PetscInt NumCells() const { return (PetscInt)cell_walls.size(); }
  PetscInt CellGid(PetscInt c) const { return cell_gid.empty() ? c : cell_gid[c]; }
  /* Build a tissue by hand (tests, custom geometries): add particles and springs, then Finalize(),
     which sets global ids, clears the clamps, computes the bounding box and finds the straight
     joints of the walls (Spring::joint; a periodic tissue sets `period` first). */
  PetscInt AddParticle(PetscReal x, PetscReal y, PetscReal mass, ParticleKind kind, PetscInt cell = -1);
  void     AddSpring(PetscInt i, PetscInt j); /* rest length = current distance */
  /* A generator that knows its counts reserves them: no push_back growth (a copy of every vector at
     each doubling, and up to twice the memory kept). */
  void Reserve(PetscInt n_particles, size_t n_springs);
  void Finalize();
  /* lo, hi: the bounding box of X (Finalize's; a tissue assembled otherwise calls it itself). */
  void UpdateBounds();
  /* Wall particle closest to the point (px, py). */
  PetscInt ClosestWallParticle(PetscReal px, PetscReal py) const;
  /* Clamp (fix) the wall particles on the named sides: any of left, right, bottom, top; "none"
     clamps nothing. Unknown names are an error naming `option`. */
  PetscErrorCode Clamp(MPI_Comm comm, const std::vector<std::string> &sides, const char *option);
};

} // namespace turgor
