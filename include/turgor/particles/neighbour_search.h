#pragma once
/* Neighbour search by cell lists with a Verlet skin.

   Lists are built with cutoff + skin and stay valid until some particle has moved more than
   skin/2 since the last build (then no pair can have crossed the cutoff unseen); the check costs
   O(n) per evaluation, a rebuild O(n) with a bin grid. Only the lists a force term asked for are
   ever built: a scene without SPH does no fluid neighbour search. */
#include <turgor/particles/particles.h>
#include <algorithm>
#include <vector>

namespace turgor {

struct PairList {                 /* half list: each unordered pair once, as rows: particle i's pairs (i, j), j > i, are j[start[i] .. start[i + 1]) */
  std::vector<PetscInt> start, j; /* [n + 1] (empty: no pairs), [pairs] */
  size_t                size() const { return j.size(); }
  PetscInt              Rows() const { return start.empty() ? 0 : (PetscInt)start.size() - 1; }
};

struct PointSegmentList { /* particle p near image `img` of spring s (p is not an end point of s) */
  std::vector<PetscInt> p, s;
  std::vector<int>      img; /* empty without periodic images: every pair is the spring itself (4 B a pair saved) */
  size_t                size() const { return p.size(); }
  int                   Image(size_t q) const { return img.empty() ? PeriodicImages::kSelf : img[q]; }
};

class NeighbourSearch {
public:
  /* Ask for fluid–fluid pairs of the same cell closer than `cutoff`. */
  void RequestFluidPairs(PetscReal cutoff);
  /* Ask for (particle, spring) pairs closer than `cutoff` (point-to-segment distance). */
  void      RequestParticleSpringPairs(PetscReal cutoff);
  void      SetSkin(PetscReal skin) { skin_ = skin; }
  PetscReal Skin() const { return skin_; }
  void      Reset();

  /* Rebuild the requested lists if any particle moved more than skin/2 since the last build (for a
     periodic system: if twice the largest move plus the change of the lattice exceeds the skin).
     Periodic systems (small RVEs) are searched directly over all pairs and the 3 x 3 images; fluid
     pairs never use images (each cell's fluid lies inside its own cell). */
  PetscErrorCode Update(const ParticleSet &P, const PetscReal *x, const PeriodicImages &images);

  /* A second reference for one client (contact's near list): Mark(x) records x; every Update then
     also finds the largest squared move since the mark, in the same pass as its own check
     (PETSC_MAX_REAL when unknown: no mark, or the lists were rebuilt). */
  void      Mark(const PetscReal *x, PetscInt n) const;
  PetscReal MaxMoveSinceMark2() const { return mark_move2_; }

  const PairList         &FluidPairs() const { return fluid_pairs_; }
  const PointSegmentList &ParticleSpringPairs() const { return particle_spring_; }
  PetscInt                Rebuilds() const { return rebuilds_; }
  bool                    WantsFluidPairs() const { return fluid_cutoff_ > 0; }
  bool                    WantsParticleSpringPairs() const { return spring_cutoff_ > 0; }
  /* Checkpoints: the positions the lists were last built at (empty: never built), and Restore,
     which builds them there again and sets the build count, so that a restarted run rebuilds at the
     same steps and visits the pairs in the same order as an uninterrupted one. */
  const std::vector<PetscReal> &ReferencePositions() const { return x_ref_; }
  PetscErrorCode                Restore(const ParticleSet &P, const std::vector<PetscReal> &x_ref, PetscInt rebuilds, const PeriodicImages &images);

private:
  PetscErrorCode Build(const ParticleSet &P, const PetscReal *x);
  PetscErrorCode BuildPeriodic(const ParticleSet &P, const PetscReal *x, const PeriodicImages &images);
  void           SortFluidPairs();
  PetscErrorCode StartBuild(const ParticleSet &P, const PetscReal *x);
  void           BinParticles(const ParticleSet &P, const PetscReal *x, PetscReal bin);

  PetscReal                      fluid_cutoff_ = 0, spring_cutoff_ = 0, skin_ = 1.0;
  PetscInt                       rebuilds_ = 0;
  std::vector<PetscReal>         x_ref_;
  mutable std::vector<PetscReal> x_mark_; /* the client's mark (not the lists' state) */
  mutable PetscReal              mark_move2_  = PETSC_MAX_REAL;
  PetscReal                      a_ref_[2][2] = {};
  PairList                       fluid_pairs_;
  PointSegmentList               particle_spring_;
  /* bin grid (counting sort) */
  PetscReal             x0_ = 0, y0_ = 0, bin_ = 1;
  PetscInt              nbx_ = 0, nby_ = 0;
  std::vector<PetscInt> bin_start_, bin_items_;
  /* a particle's bin, computed where needed (not stored: 4 B a particle) */
  PetscInt BinOf(const PetscReal *x, PetscInt k) const
  {
    const PetscInt bx = std::min(nbx_ - 1, (PetscInt)((x[2 * k] - x0_) / bin_));
    const PetscInt by = std::min(nby_ - 1, (PetscInt)((x[2 * k + 1] - y0_) / bin_));
    return by * nbx_ + bx;
  }
};

} // namespace turgor
