#pragma once
/* Dashpots along every bar (or wall spring): force on i c (e . v_ij) e, e = (x_j - x_i)/|x_j - x_i|,
   v_ij = v_j - v_i, a coefficient c [ng/µs] (-dashpot_coefficient). Unlike the global viscosity it
   resists only the bars' stretching rate, not a rigid or slow uniform motion, so it damps the
   vibrations of a tissue without dragging on a slow (quasi-static) loading. A purely dissipative
   term: the energy balance counts its work as its dissipation, exactly. */
#include <turgor/physics/force_term.h>
#include <turgor/physics/spring_order.h>
#include <vector>

namespace turgor {

class Dashpots : public ForceTermBase<Dashpots> {
public:
  const char    *Name() const override { return "dashpots"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  bool           Dissipative() const override { return true; }
  PetscErrorCode View(PetscViewer viewer) const override;

  PetscReal coefficient = 1.0; /* c [ng/µs] */

private:
  std::vector<PetscReal> gamma_;   /* per spring (all c) */
  SpringOrder            order_;   /* the springs in node order, where they are */
  std::vector<PetscReal> scratch_; /* its per-spring values */
};

} // namespace turgor
