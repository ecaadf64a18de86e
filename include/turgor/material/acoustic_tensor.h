#pragma once
/* Material stability of a material point: the acoustic tensor of its incremental moduli and its
   smallest determinant over directions (loss of ellipticity where it reaches zero).

   The moduli are those the coarse stiffness K sees (CoarseModel's assembly: B^T D^e B plus the
   initial-stress term): A_ijkl = c_ijkl + delta_ik sigma_jl, with c the Truesdell-rate tangent D^e
   (Voigt (11, 22, 12) acting on [d11, d22, 2 d12], so c_ij12 = c_ij21 = D^e[ij][12]) and sigma the
   Cauchy stress. For a unit direction n the acoustic tensor is Q_ik(n) = n_j A_ijkl n_l; the
   incremental problem is strongly elliptic while det Q(n) > 0 for every n. */
#include <turgor/core/tensor2.h>

namespace turgor {

/* Q(n) for D^e (3 x 3 Voigt) and sigma. */
void AcousticTensor(const PetscReal De[3][3], const Tensor2 &sigma, const PetscReal n[2], PetscReal Q[2][2]);

struct AcousticMinimum {
  PetscReal det   = 0; /* min over n of det Q(n) [(N/m)^2] */
  PetscReal angle = 0; /* the minimising n = (cos angle, sin angle), angle in [0, pi) */
};

/* min over unit n of det Q(n). */
AcousticMinimum MinAcousticDeterminant(const PetscReal De[3][3], const Tensor2 &sigma);

} // namespace turgor
