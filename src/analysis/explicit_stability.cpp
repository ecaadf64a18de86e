#include <turgor/analysis/explicit_stability.h>
#include <cmath>
#include <complex>

namespace turgor {

static PetscReal DP5Modulus(std::complex<double> z)
{
  const double         c[7] = {1, 1, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 600};
  std::complex<double> r    = 0;
  for (int k = 6; k >= 0; k--) r = r * z + c[k]; /* Horner */
  return std::abs(r);
}

/* Neither PETSc nor SLEPc gives a method's stability region, so the boundary is found here: march
   out along the ray in steps of 1e-3 to the first point where |R| > 1 (+1e-12 for round-off on the
   imaginary axis, which the region touches), then bisect to 1e-12. Accurate to the step where the
   ray crosses the boundary once (any theta in [pi/2, pi] for DP5). */
PetscReal DormandPrinceBoundary(PetscReal theta)
{
  const std::complex<double> e  = std::polar(1.0, (double)theta);
  double                     lo = 0, hi = 0;
  for (double r = 1e-3; r < 10; r += 1e-3) {
    if (DP5Modulus(r * e) > 1 + 1e-12) {
      hi = r;
      break;
    }
    lo = r;
  }
  if (hi == 0) return 10;
  while (hi - lo > 1e-12) {
    const double m                            = 0.5 * (lo + hi);
    (DP5Modulus(m * e) > 1 + 1e-12 ? hi : lo) = m;
  }
  return lo;
}

PetscReal DormandPrinceStepLimit(PetscReal omega, PetscReal zeta)
{
  if (!(omega > 0)) return PETSC_MAX_REAL;
  if (zeta >= 1) return DormandPrinceBoundary(PETSC_PI) / (omega * (zeta + std::sqrt(zeta * zeta - 1)));
  const PetscReal z = PetscMax(zeta, 0.0);
  return DormandPrinceBoundary(0.5 * PETSC_PI + std::asin(z)) / omega; /* |s| = omega */
}

} // namespace turgor
