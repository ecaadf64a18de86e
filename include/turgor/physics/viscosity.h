#pragma once
/* Global viscosity (the L-hyphen seed's dissipation): f = -nu v on every node, nu a force per
   velocity [ng/µs], as the seed writes it (not -nu m v: with equal node masses the two differ
   only by the constant m). */
#include <turgor/physics/force_term.h>

namespace turgor {

class Viscosity : public ForceTermBase<Viscosity> {
public:
  const char    *Name() const override { return "viscosity"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override { return PETSC_SUCCESS; }
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscErrorCode View(PetscViewer viewer) const override;
  bool           Dissipative() const override { return true; }

  PetscReal coefficient = 0.0; /* nu [ng/µs] */
};

} // namespace turgor
