#pragma once
/* Particle storage for the force kernels: plain structure-of-arrays, free of DMSwarm, so that
   the fine-scale driver (which keeps its record in a DMSwarm) and an RVE (which owns a small
   periodic patch) call the same kernels on their own arrays.

   Positions and velocities are NOT stored here: they are the integrator's state and are passed
   to the kernels as interleaved arrays x[2*i+d], v[2*i+d]. */
#include <turgor/core/petsc_compat.h>
#include <cstdint>
#include <vector>

namespace turgor {

enum ParticleKind : PetscInt {
  KIND_WALL  = 0,
  KIND_FLUID = 1
};

/* Periodic images (RVEs): image k = 3 (n1 + 1) + (n2 + 1) of a particle sits at x + n1 a1 + n2 a2
   and moves with v + n1 a1' + n2 a2', where a1, a2 are the lattice vectors of the periodic cell and
   a' their rates (F A and Fdot A for an RVE). Image kSelf is the particle itself; a system that is
   not periodic has all shifts zero and uses kSelf everywhere. */
struct PeriodicImages {
  static constexpr int kSelf   = 4;
  PetscReal            x[9][2] = {}, v[9][2] = {};
  bool                 periodic = false;
  PetscReal            a[2][2]  = {}; /* lattice vectors a1, a2 (rows) */

  static int Index(int n1, int n2) { return 3 * (n1 + 1) + (n2 + 1); }
  void       Set(const PetscReal a1[2], const PetscReal a2[2], const PetscReal va1[2], const PetscReal va2[2])
  {
    periodic = true;
    for (int d = 0; d < 2; d++) {
      a[0][d] = a1[d];
      a[1][d] = a2[d];
    }
    for (int n1 = -1; n1 <= 1; n1++)
      for (int n2 = -1; n2 <= 1; n2++)
        for (int d = 0; d < 2; d++) {
          x[Index(n1, n2)][d] = n1 * a1[d] + n2 * a2[d];
          v[Index(n1, n2)][d] = n1 * va1[d] + n2 * va2[d];
        }
  }
};

/* A wall spring (bonded pair) with its rest length; end point j is taken at the given image of
   particle j (periodic RVEs bond across the cell boundary). joint[e] names the spring end
   (2 s' + e', e' = 0 for i, 1 for j) that continues this spring's wall straight through its end i
   (e = 0) or j (e = 1), -1 where the wall ends or turns a corner there; Tissue::Finalize sets it
   from the reference positions (the repulsion counts a straight wall once, docs/model.md). */
struct Spring {
  PetscInt  i, j;
  PetscReal rest_length;
  int       image    = PeriodicImages::kSelf;
  PetscInt  joint[2] = {-1, -1};
};

/* A polygonal cell (node-file, Voronoi and polyline tissues; the L-hyphen model): its nodes in
   order around it, counter-clockwise for a closed cell, and bars[k] the spring joining nodes[k] to
   nodes[k + 1] (for a closed cell the last bar joins the last node to the first). An open cell (a
   container, a wall, a beam) has one bar fewer than nodes, no pressure and no self-contact. */
struct PolygonCell {
  std::vector<PetscInt> nodes;
  std::vector<PetscInt> bars;
  bool                  open = false;
};

/* Constant per-particle data of this rank. In a distributed fine run (tissue_distribution.h) the
   first n_owned particles are owned by this rank (its cells' particles) and the rest are halo copies
   of other ranks' particles; gid is the global id (the tissue's numbering). Every interaction is
   computed once, by the rank that owns its anchor: a spring or bar by the owner of its end i (the
   first n_springs_owned springs), a hinge or a cell's pressure by the owner of the polygon (the
   first n_polygons_owned polygons), a particle–spring pair, a contact or a glue bond by the owner
   of its particle or node. The other springs and polygons are there as geometry (contact,
   repulsion, glue). A serial run owns everything (the counts stay -1: all). */
struct ParticleSet {
  PetscInt                 n                = 0;    /* local particles (owned + halo) */
  PetscInt                 n_owned          = -1;   /* -1: all n */
  PetscInt                 n_springs_owned  = -1;   /* -1: all springs */
  PetscInt                 n_polygons_owned = -1;   /* -1: all polygons */
  std::vector<PetscInt>    spring_gid, polygon_gid; /* the tissue's numbers of the springs and polygons (records); empty: the same as here */
  std::vector<PetscReal>   mass;                    /* [n] */
  std::vector<std::int8_t> kind;                    /* [n] ParticleKind (a byte: two kinds) */
  std::vector<PetscInt>    cell;                    /* [n] cell id for fluid particles, -1 for walls */
  std::vector<PetscInt>    gid;                     /* [n] global id */
  std::vector<char>        fixed;                   /* [n] 1 if clamped (position and velocity held) */
  std::vector<Spring>      springs;
  /* Polygonal tissues only (empty for the square grid, whose walls are shared by two cells): the
     cells, the cell of every node (-1 for a particle in none), and the bar radius (a node is a disk
     and a bar a capsule of this radius; neighbouring polygons are a distance 2 r apart at rest). */
  std::vector<PolygonCell> polygons;
  std::vector<PetscInt>    node_polygon; /* [n] when polygons is not empty */
  PetscReal                bar_radius = 0;

  /* owned particles of kind k */
  PetscInt Count(ParticleKind k) const
  {
    PetscInt c = 0;
    for (PetscInt i = 0; i < NumOwned(); i++) c += (kind[i] == k);
    return c;
  }
  PetscInt NumOwned() const { return n_owned < 0 ? n : n_owned; }
  size_t   OwnedSprings() const { return n_springs_owned < 0 ? springs.size() : (size_t)n_springs_owned; }
  size_t   OwnedPolygons() const { return n_polygons_owned < 0 ? polygons.size() : (size_t)n_polygons_owned; }
  /* the tissue's number of local spring s (polygon c) */
  PetscInt SpringGid(size_t s) const { return spring_gid.empty() ? (PetscInt)s : spring_gid[s]; }
  PetscInt PolygonGid(size_t c) const { return polygon_gid.empty() ? (PetscInt)c : polygon_gid[c]; }
};

} // namespace turgor
