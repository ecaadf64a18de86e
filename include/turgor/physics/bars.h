#pragma once
/* Bars of polygonal cells (the L-hyphen model): axial springs along ParticleSet::springs with an
   optional dashpot, the wall-spring kernel with the bar parameters (wall_springs.h). */
#include <turgor/physics/force_term.h>
#include <turgor/physics/spring_order.h>
#include <vector>

namespace turgor {

class Bars : public ForceTermBase<Bars> {
public:
  const char    *Name() const override { return "bars"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscReal      CharacteristicForce(PetscReal length, PetscReal density) const override { return stiffness * length; }
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscErrorCode OutputFields(const ForceInput &in, std::vector<TermField> &fields) override;
  /* the dashpot's part of the force reported apart (the energy balance counts its work) */
  bool   HasDashpotForce() const override { return damping > 0; }
  bool   InNodeOrder() const { return order_.in_order; }                              /* the bars' loops in node order (spring_order.h) */
  size_t BarsInNodeOrder() const { return order_.in_order ? order_.rest.size() : 0; } /* ... for the first this many, the others one by one */

  PetscReal stiffness = 1.0e4; /* k_b [µN/µm = N/m] */
  PetscReal damping   = 0.0;   /* dashpot coefficient along the bar [ng/µs = µN µs/µm] */

private:
  std::vector<PetscReal> gamma_;   /* per bar (all `damping`) */
  SpringOrder            order_;   /* the bars in node order, where they are */
  std::vector<PetscReal> scratch_; /* its per-bar values */
};

} // namespace turgor
