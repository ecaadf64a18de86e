#pragma once
/* The explicit stability limit of a mode: the largest step dt with which an explicit Runge-Kutta
   method keeps a mode of the linearised coarse system M u'' + C u' + K u = 0 bounded, from the
   mode's undamped angular frequency omega and damping ratio zeta. The mode's first-order
   eigenvalues are s = omega (-zeta +- i sqrt(1 - zeta^2)) (underdamped) or the real
   s = -omega (zeta +- sqrt(zeta^2 - 1)) (overdamped: the faster one limits), and dt s must lie in
   the method's stability region |R(z)| <= 1. */
#include <turgor/core/petsc_compat.h>

namespace turgor {

/* Dormand-Prince 5(4) advancing with the fifth-order solution (PETSc's -ts_rk_type 5dp):
   R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 + z^5/120 + z^6/600. Its region's real interval is
   [-3.3066, 0]; it touches the imaginary axis only near 0, so an undamped mode (zeta = 0) limits
   dt omega to about 1 (and slightly beyond, growth below 1e-5 per step). */
PetscReal DormandPrinceStepLimit(PetscReal omega, PetscReal zeta);

/* The stability boundary r of DP5 along the ray z = r e^{i theta} (theta in [pi/2, pi]). */
PetscReal DormandPrinceBoundary(PetscReal theta);

} // namespace turgor
