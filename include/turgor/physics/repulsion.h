#pragma once
/* Repulsion of particles from wall springs (TW 562 eq 17). Every particle (fluid or wall) is
   pushed away from the closest point x^ = c x1 + (1-c) x2 of the springs within the cutoff x0,
   except the springs it is an end point of; the reaction -F is split c, 1-c over the spring's end
   points, so linear and angular momentum are preserved exactly (F is parallel to x - x^).

   Each wall pushes once, smoothly: where two springs continue one wall (Spring::joint), each
   counts for a particle with a weight that goes from 1 on its side of the joint's bisector to 0 on
   the other, smoothly across a wedge of half-angle beta around the bisector, and it reaches into
   that wedge as the straight continuation of itself. A straight wall then pushes exactly as one
   line, however it is cut into springs, and the force is continuously differentiable across the
   joints of bent walls. Walls that meet at a corner push independently (docs/model.md). */
#include <turgor/physics/force_term.h>
#include <cmath>
#include <vector>

namespace turgor {

class Repulsion : public ForceTermBase<Repulsion> {
public:
  const char    *Name() const override { return "repulsion"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  /* a spring reaches x0 beyond its joints' extensions (see Extension()) */
  PetscReal      Reach(const ParticleSet &P) const override { return cutoff + Extension(); }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  /* Energy sum over pairs of w lambda (r^-5/5 + r/x0^6 - 6/(5 x0^5)), w the pair's joint weight;
     the force is its gradient (joint weights included) wherever the angle factor is 1 (everywhere
     but beyond a free end of a wall) or when the angle factor is off. */
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscErrorCode View(PetscViewer viewer) const override;

  PetscReal strength      = 5e5; /* lambda [µN µm^6] */
  PetscReal cutoff        = 5.0; /* x0 [µm] */
  PetscBool angle_factor  = PETSC_TRUE;
  PetscBool damping       = PETSC_TRUE;
  PetscBool damping_taper = PETSC_TRUE; /* damping x (1 - (r/x0)^6): zero at the cutoff */
  PetscReal joint_blend   = 10.0;       /* beta [degrees]: half-angle of the wedge around a joint's bisector where its two springs share a particle */

private:
  struct Segment {                   /* 64 B; the image shifts of x2 are read from PeriodicImages (32 B a spring less than stored) */
    PetscReal tx, ty, inv_L2, inv_L; /* x2 - x1 and its inverse squared length and length */
    PetscReal nx[2], ny[2];          /* at end i (0) and j (1) if joined: the unit normal of the joint's bisector, into this spring's side */
  };
  struct PairGeometry {
    PetscReal wx, wy;        /* x - x1 */
    PetscReal dx, dy, t, r2; /* d = x - x^, x^ = x1 + t (x2 - x1), r2 = |d|^2 */
    PetscReal weight;        /* the product of the joint weights of both ends */
    PetscReal we[2], z[2];   /* each end's weight, and its wedge coordinate where it blends (blend bit e) */
    unsigned  blend;         /* bit e: end e's weight is inside the wedge (0 < w < 1) */
    int       clamp;         /* -1: x^ is an end point of a free end (angle factor), 0: not clamped, 1: the tip of a joint's extension */
  };
  /* How far a spring continues itself beyond a joint: x0 tan(beta), so that on a straight wall every
     particle a spring shares with its neighbour is pushed from the common line. */
  PetscReal   Extension() const { return cutoff * std::tan(joint_blend * PETSC_PI / 180.0); }
  void        Segments(const ForceInput &in);
  inline bool Pair(const ForceInput &in, const PointSegmentList &L, size_t q, PairGeometry &g) const;
  void        BlendForces(const ForceInput &in, PetscInt p, PetscInt s, int e, const PetscReal q[2], PetscReal coef, PetscReal *f, PetscReal *virial) const;
  void        TipReaction(const ForceInput &in, PetscInt s, int e, PetscReal fx, PetscReal fy, PetscReal *f, PetscReal *virial) const PETSC_ATTRIBUTE_COLD;
  PetscInt    WeightGradientForces(const ForceInput &in, PetscInt p, PetscInt s, const PairGeometry &g, PetscReal *f,
                                   PetscReal *virial) const PETSC_ATTRIBUTE_COLD;
  template <bool VIRIAL, bool ROUND>
  PetscErrorCode             Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial);
  std::vector<Segment>       seg_;                 /* per spring, refreshed each evaluation */
  std::vector<PetscInt>      joint_;               /* [2 s + e] the joined spring end (Spring::joint), fixed */
  std::vector<unsigned char> joined_;              /* [s] bit e: end e is joined to another spring */
  std::vector<PetscReal>     damping_coefficient_; /* 2 sqrt(6 lambda m_p) per particle */
  struct Derived {                                 /* from the options, in SetUp: x0^2, sin(beta), sin^2(beta), Extension() */
    PetscReal cutoff2, sin_blend, sin_blend2, extension;
  } derived_ = {0, 0, 0, 0};
};

} // namespace turgor
