#pragma once
/* What an integrator carries from one step to the next besides the solution, the time and the step
   size, as declared state (io/declared_state.h) for checkpoints:
     verlet: the acceleration at the last step's end (reused as the next step's first);
     rk with an FSAL tableau (5dp, 3bs): the last stage's derivative, the next step's first;
     other explicit types (rk without FSAL, euler, ssp, basicsymplectic, lsrk): nothing;
   the step rejections so far, and the step-size controller's history: every controller's
   -ts_adapt_time_step_increase_delay count, and the "dsp" controller's past control errors and
   step ratios (turgor's own controller, ts/adapt_dsp.h). Multistep and implicit types (am, bdf,
   radauiia, arkimex, ...) carry more (several steps of history, Newton starting values, Jacobian
   factors) and are refused.

   PETSc's rk keeps its stage derivatives to itself. The run's right-hand side tells this object
   every evaluation (ObserveRHS): the evaluation at the last stage is the FSAL derivative (its
   vector is remembered, not copied); after a restart the first step's first evaluation, at the
   restored solution, is answered with the restored derivative instead of being computed -- what
   the uninterrupted run's step took from its previous step. Also here: which TS types are
   explicit (TSIsExplicit), the list the modes and the checkpoints decide by. */
#include <turgor/io/declared_state.h>
#include <petscts.h>

namespace turgor {

/* Whether the TS integrates U' = f(t, U) from TSSetRHSFunction (an explicit method: rk, euler, ssp,
   lsrk, am; basicsymplectic and verlet also need the splits of TSRHSSplitSetIS). One list: a mode
   gives its equations in explicit form exactly to these, and an implicit form to the others (an
   explicit method given only an implicit form sees a zero right-hand side). */
PetscErrorCode TSIsExplicit(TS ts, PetscBool *is);

/* Whether a run of this TS type can be checkpointed (the one-step explicit methods); *why says why
   not. */
PetscErrorCode TSCheckpointSupported(TS ts, PetscBool *supported, const char **why);

/* The step-size controller's type and the norm it measures the error in (after TSSetFromOptions):
   the controller's own value, however it was set (PETSc has no getter for the norm). */
PetscErrorCode TSAdaptGetTypeAndNorm(TS ts, TSAdaptType *type, NormType *norm);

class IntegratorState {
public:
  ~IntegratorState();
  /* The run's RHS function calls this first, with its arguments; *answered: F holds the restored
     derivative and the evaluation must not be done (nor counted). */
  PetscErrorCode ObserveRHS(TS ts, PetscReal t, Vec U, Vec F, PetscBool *answered);
  /* The integrator's declarations ("integrator"): its history vector, the rejections, the
     controller's history. The history is offered to `keep` first (its values and global size: a run
     whose state's entries belong to its entities keeps it with them, a fine run as columns of its
     particle table); if not kept, a table of state entries (StateEntity::StateEntry: the run's
     numbering of its state, of which the history takes the first entries when it is half the state:
     Verlet's dv/dt). On a set-up TS (a restart: before the file is read). */
  using KeepVector = std::function<bool(std::vector<PetscReal> &values, PetscInt global_size)>;
  PetscErrorCode Declare(TS ts, StateDeclaration &d, const KeepVector &keep = nullptr);
  /* After the file was read into Declare's declaration, at the restored solution and time. */
  PetscErrorCode Restore(TS ts);

private:
  enum Kind {
    NONE,
    FSAL,
    VERLET
  };
  PetscErrorCode         KindOf(TS ts, Kind *kind);
  Vec                    fsal_      = nullptr; /* the vector the last stage's derivative was evaluated into (rk's own) */
  Vec                    pending_   = nullptr; /* a restored FSAL derivative, until the first step takes it */
  PetscReal              t_pending_ = 0;
  std::vector<PetscReal> history_; /* Declare's view of the history vector */
  PetscInt               rejections_ = 0;
};

} // namespace turgor
