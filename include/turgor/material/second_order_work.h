#pragma once
/* Material stability of a material point between two equilibrium states: Hill's second-order work
   dS : dE over the increment, in the objective pair of the Green-Lagrange strain E = (F^T F - I)/2
   and the second Piola-Kirchhoff stress S = J F^-1 sigma F^-T. Where it is negative the stress falls
   along the strain increment: the point softens (Hill's loss of material stability), as a periodic
   RVE does when it gives way -- a crack across its period, the stress dropping at once. A rigid
   rotation changes neither S nor E, so a point that only turns is never flagged (dP : dF with the
   first Piola stress would flag a turning, pressurised point).

   The acoustic tensor (acoustic_tensor.h) sees a tangent that softens smoothly into loss of
   ellipticity; an RVE that snaps keeps an elliptic tangent up to the state before the snap, and
   only the stresses of the two states show it. */
#include <turgor/core/tensor2.h>

namespace turgor {

struct StrainStress {
  Tensor2 E; /* Green-Lagrange strain */
  Tensor2 S; /* second Piola-Kirchhoff stress [N/m] */
};

/* E and S of a point at F with Cauchy stress sigma (2D: J = det F). */
StrainStress GreenLagrangeAndPiola(const Tensor2 &F, const Tensor2 &sigma);

/* The cosine of the angle between the increments dS and dE from a to b, dS : dE / (|dS| |dE|), in
   [-1, 1]; 1 (no decision) when the increment is too small to judge: |dE| <= strain_floor or
   |dS| <= stress_floor x max(|S_a|, |S_b|) (the material's own accuracy, e.g. an RVE's relaxation
   tolerance, would otherwise decide the sign). */
PetscReal SecondOrderWorkCosine(const StrainStress &a, const StrainStress &b, PetscReal strain_floor, PetscReal stress_floor);

} // namespace turgor
