#include <turgor/material/acoustic_tensor.h>
#include <cmath>

namespace turgor {

/* Voigt row/column of the index pair (i, j): 11 -> 0, 22 -> 1, 12 and 21 -> 2. */
static int Voigt(int i, int j)
{
  return i == j ? i : 2;
}

void AcousticTensor(const PetscReal De[3][3], const Tensor2 &sigma, const PetscReal n[2], PetscReal Q[2][2])
{
  const PetscReal sn = n[0] * (sigma(0, 0) * n[0] + sigma(0, 1) * n[1]) + n[1] * (sigma(1, 0) * n[0] + sigma(1, 1) * n[1]);
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 2; k++) {
      PetscReal q = i == k ? sn : 0.0;
      for (int j = 0; j < 2; j++)
        for (int l = 0; l < 2; l++) q += n[j] * De[Voigt(i, j)][Voigt(k, l)] * n[l];
      Q[i][k] = q;
    }
}

static PetscReal DetAt(const PetscReal De[3][3], const Tensor2 &sigma, PetscReal angle)
{
  const PetscReal n[2] = {std::cos(angle), std::sin(angle)};
  PetscReal       Q[2][2];
  AcousticTensor(De, sigma, n, Q);
  return Q[0][0] * Q[1][1] - Q[0][1] * Q[1][0];
}

/* det Q(n(angle)) is a trigonometric polynomial of degree 4 in the angle, of period pi (Q is
   quadratic in n). Its minimum in closed form needs the roots of a polynomial of degree 8; instead:
   180 samples over [0, pi) (one degree apart, at least 22 per period of the highest harmonic, so
   the sampled minimum lies in the basin of the true one) and golden-section search on the two
   intervals beside the best sample, to 1e-12 rad. */
AcousticMinimum MinAcousticDeterminant(const PetscReal De[3][3], const Tensor2 &sigma)
{
  const int       n     = 180;
  const PetscReal h     = PETSC_PI / n;
  int             best  = 0;
  PetscReal       fbest = PETSC_MAX_REAL;
  for (int k = 0; k < n; k++) {
    const PetscReal f = DetAt(De, sigma, k * h);
    if (f < fbest) {
      fbest = f;
      best  = k;
    }
  }
  const PetscReal r = 0.5 * (std::sqrt(5.0) - 1.0);
  PetscReal       a = (best - 1) * h, b = (best + 1) * h;
  PetscReal       c = b - r * (b - a), d = a + r * (b - a);
  PetscReal       fc = DetAt(De, sigma, c), fd = DetAt(De, sigma, d);
  while (b - a > 1e-12) {
    if (fc < fd) {
      b  = d;
      d  = c;
      fd = fc;
      c  = b - r * (b - a);
      fc = DetAt(De, sigma, c);
    } else {
      a  = c;
      c  = d;
      fc = fd;
      d  = a + r * (b - a);
      fd = DetAt(De, sigma, d);
    }
  }
  AcousticMinimum m;
  const PetscReal x = 0.5 * (a + b), fx = DetAt(De, sigma, x);
  m.det   = PetscMin(fx, fbest);
  m.angle = fx <= fbest ? x : best * h;
  m.angle = std::fmod(m.angle + PETSC_PI, PETSC_PI);
  return m;
}

} // namespace turgor
