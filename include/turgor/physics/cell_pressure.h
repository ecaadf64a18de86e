#pragma once
/* Pressure of closed polygonal cells: p(A) x bar length along each bar's outward normal, half on
   each end node -- exactly p(A) dA/dx, so the potential is E = -int_{A0}^{A} p(a) da. Laws
   (-pressure_law): constant p = p0; gas p = p0 A0 / A (isothermal); elastic p = p0 - K (A - A0)/A0.
   A0 is the cell's area in the reference geometry. Open cells get none. With -pressure_ramp_time T
   the turgor builds up: p(A, t) = min(t / T, 1) p(A) (a turgor switched on at once sends a shock
   through the walls; the energy balance counts dE/dt of the ramp as work done on the tissue). */
#include <turgor/physics/force_term.h>
#include <vector>

namespace turgor {

class CellPressure : public ForceTermBase<CellPressure> {
public:
  enum Law {
    CONSTANT = 0,
    GAS      = 1,
    ELASTIC  = 2
  };
  const char    *Name() const override { return "pressure"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  PetscReal      CharacteristicForce(PetscReal length, PetscReal density) const override { return p0 * length; }
  bool           TimeDependent() const override { return ramp_time > 0; }
  PetscReal      ExplicitTimePower(const ForceInput &in) override;
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscErrorCode OutputFields(const ForceInput &in, std::vector<TermField> &fields) override;

  void      SetReference(const PetscReal *X); /* A0 from X; without a call, the first evaluation's */
  PetscReal Pressure(PetscReal A, PetscReal A0) const;
  PetscReal Scale(PetscReal t) const { return ramp_time > 0 && t < ramp_time ? t / ramp_time : 1; }
  PetscReal ReferenceArea(size_t c) const { return A0_[c]; }

  Law       law          = CONSTANT;
  PetscReal p0           = 0.2; /* [N/m = µN/µm] */
  PetscReal bulk_modulus = 0;   /* K [N/m] (elastic law) */
  PetscReal ramp_time    = 0;   /* [µs]: the turgor builds up linearly over this time; 0: at once */

private:
  std::vector<PetscInt>  closed_;      /* closed polygons */
  std::vector<char>      consecutive_; /* beside closed_: its nodes numbered i0, i0 + 1, ... (a tissue's own layout) */
  std::vector<PetscReal> A0_;
  const ParticleSet     *P_        = nullptr;
  bool                   have_ref_ = false;
};

} // namespace turgor
