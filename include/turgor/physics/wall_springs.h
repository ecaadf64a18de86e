#pragma once
/* Wall springs with dashpots (TW 562 eq 16): linear springs between neighbouring wall particles,
   damped along the bond with gamma = zeta * 2 sqrt(m k) (zeta = 1: the seed's critical damping). */
#include <turgor/physics/force_term.h>
#include <turgor/physics/spring_order.h>
#include <cmath>
#include <vector>

namespace turgor {

/* One spring along d = x_j - x_i (rest length l0): its direction e = d/|d| and the elastic axial force
   k (|d| - l0); the one formula of the kernel below and of its in-order loops (spring_order.cpp) */
struct SpringAxial {
  PetscReal ex, ey, mag;
};
inline SpringAxial SpringAxialAt(PetscReal dx, PetscReal dy, PetscReal k, PetscReal l0)
{
  const PetscReal r = std::sqrt(dx * dx + dy * dy), ir = 1.0 / r;
  return {dx * ir, dy * ir, k * (r - l0)};
}
/* its dashpot's axial force gamma (e . v_ij), v_ij = v_j - v_i */
inline PetscReal SpringDashpotAt(const SpringAxial &a, PetscReal gamma, PetscReal dvx, PetscReal dvy)
{
  return gamma * (dvx * a.ex + dvy * a.ey);
}

/* The axial spring kernel shared by `springs` (wall springs) and `bars` (polygon bars): along every
   ParticleSet::springs entry, force on i [k (r - l0) + gamma_s (e . v_ij)] e, e = (x_j - x_i)/r;
   gamma[s] per spring, read only if `damped` (false: no dashpot). virial may be NULL. With the
   springs' order (spring_order.h) and room for its values, the loops that vectorise where they can. */
void SpringForces(const ForceInput &in, PetscReal k, const std::vector<PetscReal> &gamma, bool damped, PetscReal *f, PetscReal *virial,
                  const SpringOrder *order = nullptr, std::vector<PetscReal> *scratch = nullptr);
/* Every spring's axial force [k (r - l0) + gamma (e . v_ij)] (positive in tension), per spring. */
std::vector<PetscReal> SpringAxialForces(const ForceInput &in, PetscReal k, const std::vector<PetscReal> &gamma, bool damped);
/* sum_s k/2 (r_s - l0_s)^2 */
PetscReal SpringEnergy(const ForceInput &in, PetscReal k);
/* Gershgorin bound on the spring block (see wall_springs.cpp); `label` names the term in the report. */
PetscErrorCode SpringTimeStepLimit(const ParticleSet &P, PetscReal k, const std::vector<PetscReal> &gamma, const char *label,
                                   std::vector<TimeStepLimit> &limits);

class WallSprings : public ForceTermBase<WallSprings> {
public:
  const char    *Name() const override { return "springs"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  /* k_w x cell size: the force of a wall stretched by its own length */
  PetscReal      CharacteristicForce(PetscReal length, PetscReal density) const override { return stiffness * length; }
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscErrorCode OutputFields(const ForceInput &in, std::vector<TermField> &fields) override;

  PetscReal stiffness     = 4000.0; /* k_w [µN/µm = N/m] */
  PetscReal damping_ratio = 1.0;    /* zeta: 1 = critical, 0 = undamped */

private:
  std::vector<PetscReal> gamma_; /* per spring */
};

} // namespace turgor
