#pragma once
/* Biquadratic Lagrange quadrilateral (Q2, 9 nodes: 4 vertices, 4 edge midpoints, the centre) and its
   quadrature rules, tabulated from PETSc: the basis is PetscFE's Lagrange space of degree 2 on the
   quadrilateral (whose basis order is the DMPlex closure order of the model's section), the points
   are PetscDT's Gauss-Legendre tensor rules.

   Rules (-coarse_quadrature):
     sri   the deviatoric stress at the 3 x 3 Gauss points, the pressure tr(sigma)/2 at the 2 x 2
           Gauss points: 13 material points. The tissue is nearly incompressible (the fluid's
           c_s^2 rho against the walls' shear stiffness, bulk/shear ~ 100), so the pressure must be
           sampled at fewer points than the element has degrees of freedom for volume changes, or
           the element locks. 2 x 2 points impose 4 volume constraints per element against 8 new
           displacement dofs (Hughes' constraint ratio 2, the optimum); the integration is
           equivalent to the mixed Q2 / discontinuous-Q1-pressure element (Malkus & Hughes). The
           deviator needs the 3 x 3 rule: fewer points leave zero-energy (hourglass) modes. Q2's
           quadratic displacement bends without the parasitic shear that makes Q1 stiff in bending.
     full  the whole stress at the 3 x 3 Gauss points: 9 material points (exact for a
           parallelogram's linear-elastic stiffness; 9 volume constraints per element lock
           mildly as the tissue approaches incompressibility). */
#include "reference_element.h"

namespace turgor {
namespace q2 {

PetscErrorCode Tabulate(CoarseQuadrature rule, ReferenceElement *ref);

} // namespace q2
} // namespace turgor
