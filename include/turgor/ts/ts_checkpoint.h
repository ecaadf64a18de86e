#pragma once
/* What an integrator carries from one step to the next besides the solution, time and step size,
   for checkpoints (-checkpoint_interval, -restart): the step's reused derivative.
     verlet: the acceleration at the last step's end (velocity_verlet.h);
     rk with an FSAL tableau (5dp, 3bs): the last stage's derivative, the next step's first;
     other explicit types (rk without FSAL, euler, ssp, basicsymplectic): nothing.
   and the step-size controller's history (TSAdapt: the DSP filter's past control errors and step
   ratios, and every adapter's -ts_adapt_time_step_increase_delay count).
   Multistep and implicit types (am, bdf, radauiia, arkimex, ...) carry more (several steps of
   history, Newton starting values, Jacobian factors) and are refused. A C header (PETSC_EXTERN). */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

/* *supported: whether a run of this TS type can be checkpointed; *why says why not. */
PETSC_EXTERN PetscErrorCode TSCheckpointSupported(TS ts, PetscBool *supported, const char **why);
/* The history Vec (owned by the TS; NULL when the type has none or no step was taken yet). */
PETSC_EXTERN PetscErrorCode TSCheckpointGetHistory(TS ts, Vec *H);
/* Local length of the history on this rank, 0 when none (a set-up TS; for the layout of a file). */
PETSC_EXTERN PetscErrorCode TSCheckpointHistorySize(TS ts, PetscInt *n);
/* Restore the history on a set-up TS at the restored solution and time; the next TSSolve step uses
   it (call TSCheckpointPreStep from the TS pre-step: an RK TS restarts its FSAL otherwise). */
PETSC_EXTERN PetscErrorCode TSCheckpointSetHistory(TS ts, Vec H);
PETSC_EXTERN PetscErrorCode TSCheckpointPreStep(TS ts);
/* The step-size controller's state: *n numbers (at most TS_CHECKPOINT_ADAPT_MAX) into state.
   Set restores it on a set-up TS (TSCheckpointPreStep then keeps it at the first step, where a
   DSP controller would otherwise reset its history). *type names the adapter, for the file. */
#define TS_CHECKPOINT_ADAPT_MAX 8
PETSC_EXTERN PetscErrorCode TSCheckpointGetAdaptState(TS ts, const char **type, PetscInt *n, PetscReal state[]);
PETSC_EXTERN PetscErrorCode TSCheckpointSetAdaptState(TS ts, PetscInt n, const PetscReal state[]);
/* The step rejections so far (summary.json), restored. */
PETSC_EXTERN PetscErrorCode TSCheckpointSetRejections(TS ts, PetscInt rejections);
