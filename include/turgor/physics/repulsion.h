#pragma once
/* Repulsion of particles from wall springs (TW 562 eq 17). Every particle (fluid or wall) is
   pushed away from the closest point x^ = c x1 + (1-c) x2 of the springs within the cutoff x0,
   except the springs it is an end point of; the reaction -F is split c, 1-c over the spring's end
   points, so linear and angular momentum are preserved exactly (F is parallel to x - x^).

   Each wall pushes once: where two springs continue one straight wall (Spring::joint), a particle
   belongs to one of them only, the one on its side of the bisector of the joint, so that the force
   near a straight wall does not depend on how many springs it is cut into. Walls that meet at a
   corner push independently (docs/model.md). */
#include <turgor/physics/force_term.h>
#include <vector>

namespace turgor {

class Repulsion : public ForceTermBase<Repulsion> {
public:
  const char    *Name() const override { return "repulsion"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscReal      Reach(const ParticleSet &P) const override { return cutoff; }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  /* Energy lambda (r^-5/5 + r/x0^6 - 6/(5 x0^5)) per pair that counts; the force is its gradient
     wherever the angle factor is 1 (closest point inside the spring) or when the angle factor is off. */
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscErrorCode View(PetscViewer viewer) const override;

  PetscReal strength      = 5e5; /* lambda [µN µm^6] */
  PetscReal cutoff        = 5.0; /* x0 [µm] */
  PetscBool angle_factor  = PETSC_TRUE;
  PetscBool damping       = PETSC_TRUE;
  PetscBool damping_taper = PETSC_TRUE; /* damping x (1 - (r/x0)^6): zero at the cutoff */

private:
  struct Segment {                   /* 64 B; the image shifts of x2 are read from PeriodicImages (32 B a spring less than stored) */
    PetscReal tx, ty, inv_L2, inv_L; /* x2 - x1 and its inverse squared length and length */
    PetscReal gx[2], gy[2];          /* at end i (0) and j (1): u - u', u' the joined spring's outward
                                        direction (0 where the wall ends): p counts iff (p - x_end) . g > 0 */
  };
  struct PairGeometry {
    PetscReal dx, dy, t, r2; /* d = x - x^, x^ = x1 + t (x2 - x1), r2 = |d|^2 */
  };
  void        Segments(const ForceInput &in);
  inline bool Pair(const ForceInput &in, const PointSegmentList &L, size_t q, PairGeometry &g) const;
  template <bool VIRIAL>
  PetscErrorCode             Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial);
  std::vector<Segment>       seg_;                 /* per spring, refreshed each evaluation */
  std::vector<PetscInt>      joint_;               /* [2 s + e] the joined spring end (Spring::joint), fixed */
  std::vector<unsigned char> ties_;                /* [s] bit e: end e takes a particle exactly on the bisector */
  std::vector<PetscReal>     damping_coefficient_; /* 2 sqrt(6 lambda m_p) per particle */
};

} // namespace turgor
