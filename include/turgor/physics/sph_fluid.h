#pragma once
/* SPH cell fluid (TW 562 §2.1): cubic-spline kernel (eq 2), summation density (eq 4), equation
   of state p = c_s^2 rho (eq 11), viscous stress tau = mu (2d - 2/3 tr(d) I) (eqs 7-9) from the
   Bonet–Lok corrected velocity gradient (eqs 13-15), momentum equation in nested-summation form
   (eq 12). Fluid particles interact only with fluid particles of the same cell: the wall separates
   the cell contents (the wall pushes on the fluid through the repulsion term).

   Pair force on i from j, with grad_i W_ij = (x_i - x_j) W'(r)/r and L the correction matrix:
     f_ij = [ V_i V_j (tau_i L_i + tau_j L_j) - m_i m_j (p_i/rho_i^2 + p_j/rho_j^2) I ] grad_i W_ij
   The viscous part is the variational (Bonet & Lok 1999) counterpart of the corrected velocity
   gradient: it is exactly antisymmetric (linear momentum) and, because sum_j V_j grad~W (x) x_ij
   = I, it exerts no net torque (angular momentum), for any particle arrangement. */
#include <turgor/physics/force_term.h>
#include <vector>

namespace turgor {

class SPHFluid : public ForceTermBase<SPHFluid> {
public:
  const char    *Name() const override { return "sph"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) override;
  PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) override;
  PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) override;
  /* Pressure energy sum_i m_i c_s^2 ln(rho_i): the pressure forces are exactly its negative gradient. */
  PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has) override;
  /* eq 40: sound speed, viscosity and, from the accelerations, the force criterion 0.25 sqrt(h/|a|) */
  PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) override;
  bool           NeedsAccelerations() const override { return true; }
  /* c_s^2 rho x cell size: the turgor pressure's force on a cell side */
  PetscReal      CharacteristicForce(PetscReal length, PetscReal density) const override { return sound_speed * sound_speed * density * length; }
  PetscErrorCode View(PetscViewer viewer) const override;

  /* Kernel W(r) and dW/dr of eq 2 in 2D. */
  PetscReal Kernel(PetscReal r) const;
  PetscReal KernelDerivative(PetscReal r) const;
  /* Density (eq 4) and velocity gradient (eq 15, or eq 5 without correction) of every particle,
     for tests and output: rho[n], gradv[4n] row-major d v_a / d x_b. */
  PetscErrorCode DensityAndVelocityGradient(const ForceInput &in, std::vector<PetscReal> &rho, std::vector<PetscReal> &gradv);

  PetscReal smoothing_length = 5.5;   /* h [µm] */
  PetscReal sound_speed      = 100.0; /* c_s [µm/µs] */
  PetscReal viscosity        = 4e-3;  /* 2D dynamic viscosity mu x thickness [ng/µs] */
  PetscBool correction       = PETSC_TRUE;
  PetscReal guard            = 1e-2; /* eigenvalue ratio below which the correction fades out */

private:
  template <class Each>
  PetscErrorCode DensityPass(const ForceInput &in, Each each);
  /* slots [s0, s1): a group (below) */
  PetscErrorCode GradientPass(const ForceInput &in, PetscInt s0, PetscInt s1, PetscReal *gradv);
  template <bool VIRIAL, bool ROUND>
  PetscErrorCode ForcePass(const ForceInput &in, PetscInt s0, PetscInt s1, PetscReal *f, PetscReal w[4]);

  /* Memory: the per-particle arrays are over the fluid only, indexed by slot s
     (particle fluid_[s]); the pairs within 2h are rows of slots, pair_start_[s] .. pair_start_[s+1],
     each with the slot of j and F = W'(r)/r only (12 B): e = x_i - x_j is read again from x. */
  PetscReal              norm_ = 0, W0_ = 0;
  std::vector<PetscInt>  fluid_;      /* [nf] slot -> particle (owned fluid particles, ascending) */
  std::vector<PetscInt>  slot_;       /* [n] particle -> slot, -1 for a wall particle */
  std::vector<PetscInt>  pair_start_; /* [nf + 1] */
  std::vector<PetscInt>  pair_j_;     /* slot of j */
  std::vector<PetscReal> pair_F_;     /* W'(r)/r */
  std::vector<PetscReal> vol_, P_;    /* [nf], [nf]; the density passes through vol_ */
  /* A cell's fluid meets only its own cell: where every cell's slots are consecutive, the gradient
     and force passes run a cell (a group of slots) at a time, and M, G and A are kept for one group,
     not for every fluid particle (56 B a particle); the sums are made in the same order. Else one
     group of all slots. */
  std::vector<PetscInt>  group_start_; /* [groups + 1] */
  std::vector<PetscReal> M_;           /* [3 g] for the largest group g */
  std::vector<PetscReal> GA_;          /* [4 g]: G during the gradient pass, then A = tau L */
  PetscLogEvent          ev_density_ = 0, ev_gradient_ = 0, ev_force_ = 0;
};

} // namespace turgor
