#pragma once
/* The equations of a fine run for PETSc TS: the state U = [x (2n) | v (2n)] of this rank's own
   particles, dx/dt = v and dv/dt = f(x, v, t) / m, with the clamped particles held and the load
   controls' components imposed (controls.h). On several ranks the model sees a halo of the
   neighbouring ranks' particles (tissue_distribution.h): the particle fields declared for the halo
   (position, velocity) are gathered before every evaluation, and the halo's force shares returned.

   The split integrators (TSBASICSYMPLECTIC, TSVERLET) evaluate dx/dt = v and dv/dt = a(x)
   separately; the dashpots and the viscosity also need v, and use the velocity of the preceding
   position update (the "drift velocity", declared for the checkpoints). */
#include <turgor/fine/controls.h>
#include <turgor/parallel/tissue_distribution.h>
#include <turgor/particles/particle_fields.h>
#include <turgor/physics/force_model.h>
#include <petscts.h>
#include <functional>

namespace turgor {

class FineEquations {
public:
  /* The model of this rank's particles P (owned first, then the halo's), the controls, and the
     halo's exchange (nullptr: one rank holds every particle it needs). Declares position and
     velocity (halo, snapshots, checkpoints) in `fields`. */
  void SetUp(ForceModel &model, Controls &controls, TissueDistribution *halo, const ParticleSet &P, ParticleFields &fields);
  /* The TS right-hand sides (whole, and the position/momentum split over is_x, is_v) and the domain
     check; `observe`: asked first by the whole right-hand side (a restart's first derivative). */
  PetscErrorCode SetTS(TS ts, IS is_x, IS is_v, std::function<PetscErrorCode(PetscReal, Vec, Vec, PetscBool *)> observe);
  /* After TSSetFromOptions: a split integrator's set-up (its velocity of the last drift, declared
     for the checkpoints in `fields`; TSVERLET's room for the halo's forces), and TSLSRK's room for
     them in its rates. predict_velocity
     (TSVERLET only): the velocity-dependent forces at x_{n+1} see the velocity predicted to the
     step's end, v_n + h a_n, instead of the drift's v_n + h/2 a_n -- second order with dashpots
     and viscosity instead of first, for half the stability limit of a damping-dominated step (the
     limits are halved); a_n is kept (and checkpointed) for it. */
  PetscErrorCode ConfigureIntegrator(TS ts, ParticleFields &fields, bool predict_velocity = false);

  /* The model's view of a state (x, v of the owned particles): every local particle's x and v, the
     halo's from their owners, with the controlled components imposed at t (work arrays); a serial
     run without controls gets the state's own arrays. Collective in a distributed run. */
  PetscErrorCode LocalState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc);
  /* The same, of a state vector U. */
  PetscErrorCode LocalState(PetscReal t, const PetscScalar *u, const PetscReal **xc, const PetscReal **vc)
  {
    return LocalState(t, u, u + 2 * n_owned_, xc, vc);
  }
  /* The same, of the integrator's own state at a force evaluation or a step's end: where the
     integrator holds the controlled components itself (TS verlet, TSVerletSetConstraints), a serial
     run reads the state's arrays as they are (no copies); otherwise LocalState. */
  PetscErrorCode IntegratorState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc);
  PetscErrorCode IntegratorState(PetscReal t, const PetscScalar *u, const PetscReal **xc, const PetscReal **vc)
  {
    return IntegratorState(t, u, u + 2 * n_owned_, xc, vc);
  }
  /* The terms' internal state at the state (x, v) a step accepted at t (IntegratorState's): TS
     verlet's last force evaluation is known to be at its positions when no other came after it. */
  PetscErrorCode AcceptStep(PetscReal t, const PetscReal *x, const PetscReal *v);
  /* f[2 n_all] = the forces at the local state (x, v); on the owned particles whole (the halo's
     shares returned by the other ranks). */
  PetscErrorCode TotalForces(const PetscReal *x, const PetscReal *v, PetscReal *f);
  /* Every share of the forces rounded to a grain chosen from the state, so that the sums are exact
     and the same bits on any number of ranks (force_grain.h); Regrains(): evaluations repeated
     because the grain changed. */
  void     SetReproducibleSums(bool on);
  PetscInt Regrains() const { return regrains_; }
  /* The stability limits at the initial state U (every rank's, the smallest of each kind), sorted,
     and the smallest (1e-3 µs where no term has one). */
  PetscErrorCode StabilityLimits(Vec U, std::vector<TimeStepLimit> &limits, PetscReal *dt);

  /* The position and velocity fields' values from now on (a checkpoint's view of the state, until
     the next LocalState). */
  void Present(PetscReal *x, PetscReal *v)
  {
    x_local_ = x;
    v_local_ = v;
  }

  PetscInt RHSEvaluations() const { return rhs_evals_; }
  bool     Split() const { return split_; }
  /* The velocities of the split integrators' last drift (owned first). */
  std::vector<PetscReal> &DriftVelocity() { return v_stale_; }

private:
  static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx);
  static PetscErrorCode RHSPosition(TS ts, PetscReal t, Vec V, Vec Xdot, void *ctx);
  static PetscErrorCode RHSMomentum(TS ts, PetscReal t, Vec X, Vec Vdot, void *ctx);
  static PetscErrorCode CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept);
  static PetscErrorCode ImposeControls(TS ts, PetscReal t, Vec X, Vec V, void *ctx);
  /* a[2 n] of the owned particles at the local state (x, v); a_has_halo_room: a has 2 n_all entries
     (TSVerletSetAccelerationRoom), the halo's forces pass through its tail instead of fw_ */
  PetscErrorCode Accelerations(const PetscReal *x, const PetscReal *v, PetscScalar *a, bool a_has_halo_room = false);

  ForceModel                                                     *model_    = nullptr;
  Controls                                                       *controls_ = nullptr;
  TissueDistribution                                             *halo_     = nullptr;
  const ParticleSet                                              *P_        = nullptr;
  TS                                                              ts_       = nullptr;
  std::function<PetscErrorCode(PetscReal, Vec, Vec, PetscBool *)> observe_;
  PetscInt                                                        n_owned_ = 0, n_all_ = 0;
  std::vector<PetscInt>                                           fixed_;     /* the owned particles that are fixed (clamped) */
  std::vector<PetscReal>                                          xw_, vw_;   /* controls or a distributed run: the local state (halo, constraints imposed) */
  PetscReal                         *x_local_ = nullptr, *v_local_ = nullptr; /* the local state being made (the halo fields' values) */
  std::vector<const ParticleField *> halo_fields_;
  std::vector<PetscReal *>           halo_arrays_;
  std::vector<PetscReal>             fw_;                     /* forces of the local particles */
  std::vector<PetscReal>             v_stale_;                /* velocities seen by the last position update (Verlet; room for the halo's: LocalState) */
  bool                               split_          = false; /* a splitting integrator (v_stale_ is used; on every rank, empty or not) */
  bool                               predict_        = false; /* ConfigureIntegrator's predict_velocity */
  bool                               held_           = false; /* the integrator's state holds the controls (ImposeControls) */
  bool                               kdk_            = false; /* TS verlet */
  std::uint64_t                      step_end_stamp_ = 0;     /* TS verlet: the model's EvaluationStamp after its last momentum evaluation */
  bool                               reproducible_   = false; /* SetReproducibleSums */
  PetscInt                           regrains_       = 0;
  std::vector<PetscReal>             a_last_;                    /* with predict_: the owned particles' last accelerations */
  bool                               acceleration_room_ = false; /* TSVERLET's accelerations have room for the halo's forces */
  bool                               rate_room_         = false; /* TSLSRK's rates have room for them after their accelerations */
  PetscReal                          drift_fraction_    = 0;     /* splitting integrators: a position update's share of the step */
  PetscInt                           rhs_evals_         = 0;
};

} // namespace turgor
