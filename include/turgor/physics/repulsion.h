#pragma once
/* Repulsion of particles from wall springs (TW 562 eq 17). Every particle (fluid or wall) is
   pushed away from the closest point x^ = c x1 + (1-c) x2 of every spring within the cutoff x0,
   except the springs it is an end point of; the reaction -F is split c, 1-c over the spring's end
   points, so linear and angular momentum are preserved exactly (F is parallel to x - x^). */
#include <turgor/physics/force_term.h>
#include <vector>

namespace turgor {

class Repulsion : public ForceTermBase<Repulsion> {
public:
  const char    *Name() const override { return "repulsion"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  /* Energy lambda (r^-5/5 + r/x0^6 - 6/(5 x0^5)) per pair; the force is its gradient wherever the
     angle factor is 1 (closest point inside the spring) or when the angle factor is off. */
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscErrorCode View(PetscViewer viewer) const override;

  PetscReal strength      = 5e5; /* lambda [µN µm^6] */
  PetscReal cutoff        = 5.0; /* x0 [µm] */
  PetscBool angle_factor  = PETSC_TRUE;
  PetscBool damping       = PETSC_TRUE;
  PetscBool damping_taper = PETSC_TRUE; /* damping x (1 - (r/x0)^6): zero at the cutoff */

private:
  struct Segment {
    PetscReal tx, ty, inv_L2, inv_L; /* x2 - x1 and its inverse squared length and length */
    PetscReal vx, vy;                /* velocity shift of the image of x2 */
  };
  template <bool VIRIAL>
  PetscErrorCode         Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial);
  std::vector<Segment>   seg_;                 /* per spring, refreshed each evaluation */
  std::vector<PetscReal> damping_coefficient_; /* 2 sqrt(6 lambda m_p) per particle */
};

} // namespace turgor
