#pragma once
/* The springs of a polygonal tissue in node order: where spring s runs from node i_0 + s to the next
   node (cells and chains numbered node by node around each, the tissues' own layout) but at each
   ring's closing bar, the axial spring kernel (wall_springs.h) runs as loops that vectorise: the bars
   read from x and v in order, every spring's force at once (a square root and a division each), then
   every node that takes only -F_(s-1) and +F_s (in that order: the kernel's sum, spring by spring)
   in one pass, and the few others (each ring's first node, a chain's ends) one by one in spring
   order. Element by element the kernel's arithmetic, without fused multiply-adds: the same bits.
   Where the layout holds for the first springs only (an open chain's m nodes have m - 1 bars, so the
   next polygon's first node is not the next spring's), those run so and the others one by one after
   them, in spring order as the kernel sums them. */
#include <turgor/physics/force_term.h>
#include <cstdint>
#include <vector>

namespace turgor {

struct SpringOrder {
  bool                       in_order = false; /* the layout above holds for the first springs (at least two; no periodic image) */
  size_t                     springs  = 0;     /* all of the rank's springs when built; those after the ordered ones (rest.size()) go one by one */
  PetscInt                   i0       = 0;     /* the first spring's node i */
  std::vector<PetscReal>     rest;             /* rest lengths of the ordered springs, by field */
  std::vector<std::uint64_t> interior;         /* per spring s: all ones when node i_s takes only -F_(s-1) then +F_s */
  std::vector<PetscInt>      by_index;         /* springs whose far end is not the next node (closing bars, the last) */
  struct Share {
    PetscInt  node, s;
    PetscReal sign; /* +1: node i of spring s, -1: node j */
  };
  std::vector<Share> ends; /* the other nodes' shares, in spring order */

  /* From this rank's springs (ParticleSet::OwnedSprings()). */
  void Build(const ParticleSet &P);
};

/* dx[s], dy[s] = u_(s+1) - u_s for s < n, u of 2-vectors by node (positions or velocities from a first
   node): the bars from each node to the next, read in order, in a loop that vectorises */
void NextNodeDifferences(size_t n, const PetscReal *u, PetscReal *dx, PetscReal *dy);

/* SpringForces (no virial, no periodic images, no rounding) for springs in order. */
void SpringForcesInOrder(const ForceInput &in, const SpringOrder &O, PetscReal k, const PetscReal *gamma, bool damped, PetscReal *f,
                         std::vector<PetscReal> &scratch);

} // namespace turgor
