#pragma once
/* Load controls of the fine run (-controls a,b and -control_<name>_*): groups of nodes with an
   imposed velocity (per component, or `free`) or an imposed force, scaled in time by a profile.

   A velocity-controlled component is an exact constraint: x(t) = X + v S(t), v(t) = v s(t), where
   s is the profile (step: 1; ramp: min(t / T, 1); cyclic: +1, -1 alternating every half period),
   started at the group's delay (s = 0 before it: a velocity group holds still, a force group
   pushes nothing) and, with a duration, stopped after it (s = 0 again: a velocity group holds still
   where it got to, a force group lets go), and S its integral. The driver overwrites those components wherever the state is read (forces,
   outputs), integrates dx/dt = v s(t) and leaves their velocity un-integrated (dv/dt = 0). A force
   control applies the total force F s(t) to the group, shared by mass (every node gets the same
   acceleration F s(t) / M). Nodes are wall particles (box and cells select wall particles only;
   -control_<name>_nodes may name any particle). See docs/model.md, "Controls". */
#include <turgor/core/parameters.h>
#include <turgor/tissue/tissue.h>
#include <string>
#include <vector>

namespace turgor {

enum ControlProfile {
  CONTROL_STEP,
  CONTROL_RAMP,
  CONTROL_CYCLIC
};

struct ControlGroup {
  std::string name;
  /* selection (union of all given): particle ids, cells, named cells (plates), a box of reference positions */
  std::vector<PetscInt>    node_ids, cells;
  std::vector<std::string> named; /* Tissue::named_cells, e.g. the plates "top", "bottom" */
  bool                     has_box = false;
  PetscReal                box[4]  = {0, 0, 0, 0}; /* xmin, ymin, xmax, ymax */
  /* what is imposed */
  bool           velocity    = true;           /* false: force */
  PetscReal      value[2]    = {0, 0};         /* velocity [µm/µs] or total force [µN] */
  bool           free[2]     = {false, false}; /* velocity components left free */
  ControlProfile profile     = CONTROL_STEP;
  PetscReal      ramp_time   = 0; /* [µs] */
  PetscReal      half_period = 0; /* [µs] */
  PetscReal      delay       = 0; /* [µs]: the profile starts at t = delay */
  PetscReal      duration    = 0; /* [µs]: the profile stops at t = delay + duration; 0: never */

  /* set up from the tissue: the nodes (local indices), their reference positions, total mass */
  std::vector<PetscInt>  nodes;
  std::vector<PetscReal> X0;
  PetscReal              mass = 0;

  PetscReal Scale(PetscReal t) const;    /* s(t) */
  PetscReal Integral(PetscReal t) const; /* S(t) = int_0^t s */
  PetscReal Rate(PetscReal t) const;     /* ds/dt (the smooth part: 1/T on a ramp, else 0) */
};

class Controls {
public:
  /* Read -controls and every listed group's options (prefix -control_<name>_), validated. */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
  /* Add a configured group (tests), before SetUp. */
  void Add(const ControlGroup &g) { groups_.push_back(g); }
  /* Resolve the groups' nodes on the full tissue (every rank holds it at this point, so the checks
     agree on all ranks); `owner` false: this rank keeps the groups but no nodes. */
  PetscErrorCode SetUp(MPI_Comm comm, const Tissue &tissue, bool owner);
  /* A distributed run: after SetUp on the whole tissue, keep the nodes this rank has (local_of[g]:
     the local index of global particle g, -1 if none) in the local numbering of `P`; the first
     P.NumOwned() are this rank's own (observed, integrated), the halo copies are only imposed. */
  void Localize(const std::vector<PetscInt> &local_of, const ParticleSet &P);

  bool                             Active() const { return !groups_.empty(); }
  const std::vector<ControlGroup> &Groups() const { return groups_; }

  /* Overwrite the velocity-controlled components of x and v (either may be NULL) with their values
     at time t. */
  void Impose(PetscReal t, PetscReal *x, PetscReal *v, PetscInt n = PETSC_MAX_INT) const; /* nodes below n only (arrays of n particles) */
  /* Velocity-controlled components of xdot: the mean velocity over [t, t + tau] (tau > 0: a drift of
     a splitting integrator, exact for any profile), or the velocity at t (tau = 0). */
  void PositionRates(PetscReal t, PetscReal tau, PetscReal *xdot) const;
  /* Accelerations: the velocity-controlled components are not integrated (set to 0); force groups
     add F s(t) / M. */
  void AdjustAccelerations(PetscReal t, PetscReal *a) const;
  /* r[2n] = the force every control applies to its nodes at time t, given the other forces f on them:
     the reaction m v rate(t) - f on a velocity-controlled component, the applied share F s(t) m_i/M
     of a force group; 0 elsewhere. */
  void ControlForces(PetscReal t, const PetscReal *f, PetscReal *r, PetscInt n) const;
  /* Per group (ux, uy, fx, fy, mz): the mean displacement, the reaction (velocity components:
     M a_c - sum of the other forces f on the group; `inertia` false, a static equilibrium: the
     minus sum alone) or the applied force, and the moment of those forces about the group's centre
     of mass. Collective. */
  PetscErrorCode           Observe(MPI_Comm comm, PetscReal t, const PetscReal *x, const PetscReal *f, std::vector<PetscReal> &row, bool inertia = true) const;
  std::vector<std::string> Columns() const;
  std::vector<std::string> Names() const;
  PetscErrorCode           View(MPI_Comm comm) const;

private:
  std::vector<ControlGroup> groups_;
  /* the velocity-controlled components: state index 2 i + d, and its group */
  std::vector<PetscInt>  comp_, comp_group_;
  std::vector<PetscReal> node_mass_;               /* of every local particle (the centre of mass of a group); empty without groups */
  PetscInt               n_owned_ = PETSC_MAX_INT; /* nodes from here on are halo copies (Localize) */
};

/* -fine_clamp: the tissue sides whose wall particles are fixed (left, right, bottom, top; none),
   the fine modes' other boundary condition; *clamp keeps its value when the option is not given. */
PetscErrorCode ClampFromOptions(MPI_Comm comm, std::vector<std::string> *clamp, ParameterList *params = nullptr);

} // namespace turgor
