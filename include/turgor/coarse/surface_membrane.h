#pragma once
/* A membrane along chosen boundary faces of the coarse mesh (-coarse_skin_stiffness EA): the
   surface stiffness first-order homogenisation leaves out. A periodic RVE has no faces; a tissue
   has an outer layer of walls running along its faces (an epidermis; in a Voronoi bar, the walls
   along its cut sides), which stiffens bending far more than stretching: with a core of modulus E
   and depth H, E_stretch = E + 2 EA / H but E_bend = E + 6 EA / H. docs/model.md, "Surface
   membrane".

   On each face edge, with x = X + u interpolated by the element's edge functions (Q1: 2 nodes,
   Q2: 3) and the stretch lambda = |x'| / |X'| (' = d/dxi), the energy int EA (lambda - 1)^2 / 2 |X'|
   dxi gives the nodal forces f_i = int EA (lambda - 1) t N_i' dxi, t = x' / |x'|, and the stiffness
   K_ij = int N_i' N_j' [EA / |X'| t t^T + EA (lambda - 1) / |x'| (I - t t^T)] dxi, by Gauss rules
   exact for the straight reference edge (2 and 3 points). No mass, no prestress. */
#include <turgor/core/parameters.h>
#include <petscdmplex.h>
#include <string>
#include <vector>

namespace turgor {

class SurfaceMembrane {
public:
  /* -coarse_skin_stiffness EA [µN] (0: none), -coarse_skin_label, -coarse_skin_values (box: 1
     bottom, 3 top) */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
  /* The face edges of this rank's cells [c_start, c_end) (each edge once: a face edge has one
     cell); nodes per edge 2 (Q1) or 3 (Q2, the edge's own node first, as in its closure). */
  PetscErrorCode SetUp(DM dm, PetscInt c_start, PetscInt c_end, PetscInt edge_nodes);
  bool           Active() const { return stiffness > 0; }
  /* + f_int of the membrane into the momentum rows of Floc (local, ADD), at the displacement Uloc */
  PetscErrorCode AddForce(DM dm, Vec Uloc, Vec Floc) const;
  /* + d f_int / d u into J (closures, ADD_VALUES; J assembled by the caller) */
  PetscErrorCode AddStiffness(DM dm, Vec Uloc, Mat J) const;
  PetscInt       NumEdges() const { return (PetscInt)edges_.size(); }

  PetscReal             stiffness = 0; /* EA [µN] */
  std::string           label     = "Face Sets";
  std::vector<PetscInt> values    = {1, 3};

private:
  struct EdgeState { /* at each Gauss point: weight, dN/dxi of the nodes, |X'|, x' */
    int       points = 0;
    PetscReal w[3], dN[3][3], lX[3], xp[3][2];
  };
  /* The edge's reference and current node positions (2 per node, in closure order) */
  PetscErrorCode        EdgeNodes(DM dm, Vec Uloc, PetscInt e, PetscReal *X, PetscReal *x) const;
  PetscErrorCode        EdgeKinematics(DM dm, Vec Uloc, PetscInt e, EdgeState *k) const;
  std::vector<PetscInt> edges_;
  PetscInt              nodes_ = 2;
};

} // namespace turgor
