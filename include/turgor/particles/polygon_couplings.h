#pragma once
/* Which positions a polygonal tissue's forces depend on (the sparsity of a static solve's Jacobian):
   the nodes of a cell with each other (bars, hinges, and the cell's area in its pressure), and each
   node with the two ends of every bar of another cell within `reach` of it (contact, glue). Cell
   bounding boxes prune the pairs of cells. */
#include <turgor/particles/particles.h>
#include <functional>
#include <set>
#include <vector>

namespace turgor {

struct CellBox {
  PetscReal lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
};
CellBox BoxOf(const std::vector<PetscInt> &nodes, const PetscReal *x);
/* the distance between the boxes a and b + shift */
PetscReal BoxGap(const CellBox &a, const CellBox &b, const PetscReal shift[2]);

/* adj[i] (i < P.NumOwned()): the owned particles coupled to owned particle i, itself included, for
   the cells P owns and every cell (halo images too) they can reach; owner(j) maps a particle of the
   halo to the owned one it copies (the identity for a tissue without one). */
void PolygonCouplings(const ParticleSet &P, const PetscReal *x, PetscReal reach, const std::function<PetscInt(PetscInt)> &owner,
                      std::vector<std::set<PetscInt>> &adj);

} // namespace turgor
