#include <turgor/core/vector_clones.h>
#include <turgor/physics/hinge_moments.h>

namespace turgor {

namespace {
/* Branch-free (the series for every hinge, `general` marking where it does not hold), so that GCC
   vectorises it; the pointers restrict-qualified for the same reason. */
TURGOR_VECTOR_CLONES void SeriesLoop(size_t n, const PetscInt *__restrict a, const PetscInt *__restrict b, const PetscInt *__restrict c,
                                     const PetscReal *__restrict cos0, const PetscReal *__restrict sin0, const PetscReal *__restrict theta_p,
                                     const PetscReal *__restrict x, PetscReal k, PetscReal Mmax, PetscReal *__restrict ux, PetscReal *__restrict uy,
                                     PetscReal *__restrict wx, PetscReal *__restrict wy, PetscReal *__restrict d, PetscReal *__restrict iw2,
                                     PetscReal *__restrict M, PetscReal *__restrict general)
{
  for (size_t h = 0; h < n; h++) {
    const PetscReal vx = x[2 * a[h]] - x[2 * b[h]], vy = x[2 * a[h] + 1] - x[2 * b[h] + 1];
    const PetscReal zx = x[2 * c[h]] - x[2 * b[h]], zy = x[2 * c[h] + 1] - x[2 * b[h] + 1];
    const HingeBend B = HingeBendOf(vx, vy, zx, zy, cos0[h], sin0[h]);
    PetscReal       dh, ih;
    HingeSeries(B, &dh, &ih);
    ux[h] = vx, uy[h] = vy, wx[h] = zx, wy[h] = zy;
    d[h] = dh, iw2[h] = ih, M[h] = HingeMoment(k, dh, theta_p[h], Mmax);
    general[h] = HingeSeriesHolds(B) ? 0 : 1;
  }
}

/* h >= 1: iu2 is the previous hinge's 1/|w|^2 (the caller redoes the first hinge of each polygon) */
TURGOR_VECTOR_CLONES void EndForceLoop(size_t n, const PetscReal *__restrict ux, const PetscReal *__restrict uy, const PetscReal *__restrict wx,
                                       const PetscReal *__restrict wy, const PetscReal *__restrict iw2, const PetscReal *__restrict M,
                                       PetscReal *__restrict fax, PetscReal *__restrict fay, PetscReal *__restrict fcx, PetscReal *__restrict fcy)
{
  for (size_t h = 1; h < n; h++) {
    const PetscReal iu = M[h] * iw2[h - 1], iw = M[h] * iw2[h];
    fax[h] = -uy[h] * iu, fay[h] = ux[h] * iu; /* -M dtheta/dx_a */
    fcx[h] = wy[h] * iw, fcy[h] = -wx[h] * iw; /* -M dtheta/dx_c */
  }
}
} // namespace

void HingeSeriesMoments(size_t n, const PetscInt *a, const PetscInt *b, const PetscInt *c, const PetscReal *cos0, const PetscReal *sin0,
                        const PetscReal *theta_p, const PetscReal *x, PetscReal k, PetscReal Mmax, const HingeScratch &S)
{
  SeriesLoop(n, a, b, c, cos0, sin0, theta_p, x, k, Mmax, S.ux, S.uy, S.wx, S.wy, S.d, S.iw2, S.M, S.general);
}

void HingeEndForces(size_t n, const HingeScratch &S, PetscReal *fax, PetscReal *fay, PetscReal *fcx, PetscReal *fcy)
{
  EndForceLoop(n, S.ux, S.uy, S.wx, S.wy, S.iw2, S.M, fax, fay, fcx, fcy);
}

} // namespace turgor
