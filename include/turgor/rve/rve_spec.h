#pragma once
/* Settings of the RVE material (prefix rve_), read once for all material points: the size of the
   periodic cell, how its fine structure is found, and the seed's Psi-tc schedule (TW 562 §3.2,
   eq 28) in units scaled by the cell size and a characteristic force. */
#include <turgor/core/parameters.h>
#include <turgor/core/petsc_compat.h>

namespace turgor {

/* relaxed: solve eq 27; cauchy_born: u1 = 0 (the seed's Taylor-Voigt / Cauchy-Born approximation);
   frozen: u1 held at the last committed state (Cauchy-Born about a relaxed reference). */
enum class RelaxationMode {
  Relaxed,
  CauchyBorn,
  Frozen
};

/* How the pseudo time step grows (eq 28): the seed's geometric schedule delta <- increment x delta, or
   switched evolution relaxation, delta <- delta x min(increment, ||G_prev|| / ||G||), which shrinks
   the step when the residual grows (the polygon cells' contact and glue are piecewise: a Newton
   step across their kinks can overshoot). */
enum class PseudoStepRule {
  Seed,
  SER
};

struct RVESpec {
  PetscInt       cells   = 1; /* cells per side of the periodic RVE */
  RelaxationMode relax   = RelaxationMode::Relaxed;
  PetscInt       max_it  = 50; /* Psi-tc iterations before an evaluation fails */
  PetscReal      psi_dt0 = 1e-2, psi_increment = 10, psi_dt_max = 1e12;
  PetscReal      psi_atol = 1e-12, psi_steptol = 1e-12; /* stop at ||G|| < atol or ||step|| < steptol */
  PetscReal      warm_dt0 = 1e4;                        /* pseudo step of warm (modified Newton) solves (polygon RVEs: 1e8) */
  PseudoStepRule psi_rule = PseudoStepRule::Seed;
  /* a warm solve starts from w + (dw/dF) dF, the last exact tangent's derivative of the relaxed
     state, rather than from w */
  PetscBool predictor = PETSC_TRUE;
  /* warm solves: Anderson acceleration (depth one) of the modified Newton iterations */
  PetscBool anderson = PETSC_FALSE;

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
};

} // namespace turgor
