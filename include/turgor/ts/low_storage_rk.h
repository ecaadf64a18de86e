#pragma once
/* An adaptive explicit Runge-Kutta method in three registers, registered as the PETSc TS type
   "lsrk": Ketcheson's RK4(3)5[3S*] (D. I. Ketcheson, "Runge-Kutta methods with minimum storage
   implementations", J. Comput. Phys. 229 (2010) 1763-1773, table 5), five stages, fourth order,
   with an embedded third-order solution for the step-size control. Per step, with S1 = u_n:

       S3 = u_n,  S2 = 0
       for i = 1 .. 5:   S2 += delta_i S1
                         S1  = gamma_i1 S1 + gamma_i2 S2 + gamma_i3 S3 + beta_i h f(t_n + c_i h, S1)
       u_{n+1} = S1,   u_hat = (S2 + delta_6 S1 + delta_7 S3) / sum(delta)

   The stages live in the solution itself (S1), S2 and S3, and one vector takes f: four state-size
   vectors in all, where PETSc's TSRK keeps every stage and every rate (DOPRI: 15). S3 keeps u_n,
   so a rejected step returns to it by one copy.

   TSAdapt chooses the step from ||u_{n+1} - u_hat|| (order 4 in the controller's sense, as DOPRI's
   pair is order 5), by default with the DSP (PI) controller, which holds a step at the stability
   limit without the basic controller's cycle of growth and rejection; TSAdaptCheckStage sees every stage (TSSetFunctionDomainError rejects a step).
   TSInterpolate: a cubic Hermite interpolant over the last step from u_n, u_{n+1} and f at both
   ends, third order (O(h^4) inside the step); the two rates are evaluated when a step is first
   interpolated (in S2 and the rate register, free between steps), and f(u_{n+1}) is then the next
   step's first stage. Besides the solution and the step size, nothing passes from one step to the
   next: a checkpoint of (t, u, h) restarts it bit for bit. A C header (PETSC_EXTERN). */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>
#include <turgor/ts/ts_register.h> /* TurgorTSRegisterAll() registers it */

#define TSLSRK "lsrk"

/* The method as a Butcher tableau, reconstructed from its register coefficients at creation: s
   stages, A (s x s, row-major, strictly lower), b (the solution's weights), bembed (the embedded
   solution's), c (the abscissae), and the orders of both. Arrays owned by the TS. */
PETSC_EXTERN PetscErrorCode TSLSRKGetTableau(TS ts, PetscInt *s, const PetscReal **A, const PetscReal **b, const PetscReal **bembed, const PetscReal **c,
                                             PetscInt *order, PetscInt *embedded_order);

/* Right-hand side evaluations since set-up: those of the steps' stages (rejected steps included)
   and those that interpolation asked for (at most one a step: f(u_n); f(u_{n+1}) is counted with
   the next step's stages, which reuse it). Errors on a TS of another type. */
PETSC_EXTERN PetscErrorCode TSLSRKGetCounters(TS ts, PetscInt *stage_evaluations, PetscInt *interpolation_evaluations);

/* Before TSSetUp: the vectors that the right-hand side fills (the rate register, and S2, which
   receives f(u_n) for an interpolation) get `extra` spare entries after their local part, which
   that function may use as scratch (a distributed particle code computes its halo particles'
   forces there before returning them to their owners: no separate force array). 0 (the default):
   none. */
PETSC_EXTERN PetscErrorCode TSLSRKSetRateRoom(TS ts, PetscInt extra);
