#pragma once
/* Uniform body force (acceleration g on every particle), e.g. the seed's 0.2 µm/µs^2 downward.
   g and its schedule (-body_force_delay, -body_force_ramp_time) are the scene's load (LoadSpec),
   not options of this term. */
#include <turgor/physics/force_term.h>

namespace turgor {

class BodyForce : public ForceTermBase<BodyForce> {
public:
  const char    *Name() const override { return "body_force"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  bool           IsLoad() const override { return true; }
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override { return PETSC_SUCCESS; }
  /* External forces contribute no internal virial. */
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode View(PetscViewer viewer) const override;

  /* g and its schedule, as the scene gives them (the energy balance counts a load's work as the
     integral of f . v: a schedule needs no explicit-time term there) */
  LoadSpec load;
};

} // namespace turgor
