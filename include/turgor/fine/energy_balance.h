#pragma once
/* The energy balance of a fine run (-fine_energy, energy.csv): kinetic energy, each
   term's stored energy, the work of the controls and of the loads (the body force), and what is
   dissipated -- by global viscosity and by the dashpots inside a stored term's force (contact's
   normal damping) (their works), plasticity, friction and fracture (each term's own count, from its
   committed internal state) -- and the residual

     residual = (K + sum E) - (K0 + sum E0) - W_controls - W_loads + D,

   which is zero for an exact integration and consistent dissipation counts.

   Works are summed over accepted steps from the forces the integrator used: each term's force at
   the accepted positions (the last evaluation of velocity Verlet and of DOPRI), per step
   W = (F_n + F_n+1)/2 . (v_n + v_n+1)/2 h. With velocity Verlet the works of all forces then sum
   to the kinetic energy's change exactly, so the residual is the conservative terms' integration
   error (O(h^2)) plus whatever dissipation no term counts. */
#include <turgor/fine/controls.h>
#include <turgor/physics/force_model.h>
#include <string>
#include <vector>

namespace turgor {

class EnergyBalance {
public:
  /* Decide the columns from the model's terms; the model keeps every term's force from now on. */
  PetscErrorCode           SetUp(ForceModel &model, const Controls &controls, const ParticleSet &P);
  std::vector<std::string> Columns() const; /* after "time" */
  /* The initial state (t, x, v): the forces there (one evaluation) and the reference energies. */
  PetscErrorCode Start(MPI_Comm comm, PetscReal t, const PetscReal *x, const PetscReal *v);
  /* After an accepted step to (t, x, v): add the step's works (the forces of the model's last
     evaluation if it was at x, else of a new one at (x, v)). */
  PetscErrorCode Step(PetscReal t, const PetscReal *x, const PetscReal *v);
  /* The current row (collective; every rank gets it): energies at x, and the residual relative to
     the external work so far (or to the total energy where none was done). */
  PetscErrorCode Row(MPI_Comm comm, const PetscReal *x, const PetscReal *v, std::vector<PetscReal> &row, PetscReal *relative);
  PetscReal      LargestRelativeResidual() const { return worst_relative_; }
  /* The energy of the tissue's round-off: the residual is relative to it where the works and
     energies are smaller (a tissue at rest before a delayed load holds energies of 1e-25 from its
     coordinates' last bits, whose changes are no integration error). */
  void      SetRoundOffEnergy(PetscReal e) { round_off_ = e; }
  PetscReal ExternalWork() const; /* this rank's */
  /* Declared state: the running sums (works, references) as each rank's shares, and the last
     step's forces and velocities per particle (a halo copy's forces are this rank's share of its
     force: on another layout they are added up on the particle's owner, since the works are sums of
     f . v over ranks and particles; its velocity is the owner's). */
  void DeclareState(StateDeclaration &d);

private:
  PetscErrorCode Forces(const PetscReal *x, const PetscReal *v, std::vector<std::vector<PetscReal>> &F, std::vector<std::vector<PetscReal>> &D,
                        std::vector<PetscReal> &reaction);
  PetscReal      Kinetic(const PetscReal *v) const;

  ForceModel                         *model_    = nullptr;
  const Controls                     *controls_ = nullptr;
  const ParticleSet                  *P_        = nullptr;
  std::vector<size_t>                 stored_, loads_, dissipative_, counting_, timed_, dashpots_; /* terms by role */
  std::vector<PetscReal>              W_time_, P_time_prev_;                                       /* per term: the work of dE/dt */
  std::vector<PetscReal>              W_, W_dashpot_;                                              /* per term: the work of its force, of its dashpot part */
  PetscReal                           W_controls_ = 0, K0_ = 0, E0_ = 0, t_ = 0, worst_relative_ = 0, round_off_ = 0;
  std::vector<std::vector<PetscReal>> F_prev_;
  std::vector<PetscReal>              v_prev_, R_prev_, F_work_total_, R_work_;
  std::vector<std::vector<PetscReal>> F_work_;
  std::vector<std::vector<PetscReal>> D_prev_, D_work_; /* the dashpot parts, per term (those in dashpots_ filled) */
};

} // namespace turgor
