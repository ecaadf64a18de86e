#pragma once
/* Kick-drift-kick velocity Verlet with a fixed step, registered as the PETSc TS type "verlet": the
   scheme of the L-hyphen seed code,
       v+ = v_n + h/2 a(x_n),   x_{n+1} = x_n + h v+,   v_{n+1} = v+ + h/2 a(x_{n+1}),
   one force evaluation per step, the last one (at x_{n+1}, the accepted positions) reused as the
   first of the next step. PETSc's basicsymplectic "2" is the drift-kick-drift form, whose only
   force evaluation is at the half-step positions x_n + h/2 v_n: both are second order and
   symplectic, but only this one evaluates the forces at the positions a step accepts, so terms with
   internal state (plastic hinges, friction) commit what the step used without evaluating again.

   Like basicsymplectic, it needs the two splits "position" (dx/dt = v) and "momentum" (dv/dt = a)
   of TSRHSSplitSetIS/TSRHSSplitSetRHSFunction; a force that depends on v (dashpots, viscosity)
   sees the velocity of the preceding drift, v+. The step is fixed (no TSAdapt); TSInterpolate is a
   cubic Hermite interpolation of x (with v) and of v (with a) over the last step. Work vectors: the
   two accelerations only (no copy of the state: the step's start is recovered from its end to
   round-off, for the interpolation and for the rollback of a step the domain check rejects).
   A step whose end (x_{n+1}, v_{n+1}) is not finite is rejected: the step's own loops check the
   values they write, so a domain check (TSSetFunctionDomainError, called as well where set) need not
   scan for them.
   A C header: the functions have C linkage (PETSC_EXTERN). */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>
#include <turgor/ts/ts_register.h> /* TurgorTSRegisterAll() registers it */

#define TSVERLET "verlet"

/* Momentum evaluations since the TS was set up, and how many of them were reused from the previous
   step's end (the first step evaluates twice, every later step once). Errors on a TS of another
   type. */
PETSC_EXTERN PetscErrorCode TSVerletGetCounters(TS ts, PetscInt *evaluations, PetscInt *reused);

/* Checkpoints: the acceleration of the last step's end (reused as the next step's first), and
   setting it on a restarted TS (after TSSetUp, at the restored solution and time), so that the next
   step reuses it as an uninterrupted run would. *have is PETSC_FALSE before the first step. */
PETSC_EXTERN PetscErrorCode TSVerletGetLastAcceleration(TS ts, Vec *A1, PetscBool *have);
PETSC_EXTERN PetscErrorCode TSVerletSetLastAcceleration(TS ts, Vec A1);

/* Before TSSetUp: the acceleration vectors that the "momentum" right-hand side fills get `extra`
   spare entries after their local part, which that function may use as scratch (a distributed
   particle code computes its halo particles' forces there before sending them to their owners: no
   separate force array, 16 B a particle). 0 (the default): none. */
PETSC_EXTERN PetscErrorCode TSVerletSetAccelerationRoom(TS ts, PetscInt extra);

/* Components held to prescribed values (a velocity control: x(t) and v(t) given): before each force
   evaluation the step calls impose(ts, t, q, p, ctx) on the solution's own parts at the evaluation's
   time (q: positions, p: velocities), which overwrites the prescribed components in place; the
   momentum right-hand side keeps their accelerations at 0, so that the state the integrator holds
   satisfies them at every step's end and the right-hand sides may read it as it is (no copy with the
   prescribed values put in). NULL: none (the default). */
PETSC_EXTERN PetscErrorCode TSVerletSetConstraints(TS ts, PetscErrorCode (*impose)(TS, PetscReal, Vec, Vec, void *), void *ctx);
