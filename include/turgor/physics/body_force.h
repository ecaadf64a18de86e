#pragma once
/* Uniform body force (acceleration g on every particle), e.g. the seed's 0.2 µm/µs^2 downward.
   g is the scene's load (-body_force, LoadSpec), not an option of this term. */
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

  PetscReal g[2] = {0.0, -0.2}; /* [µm/µs^2] */
};

} // namespace turgor
