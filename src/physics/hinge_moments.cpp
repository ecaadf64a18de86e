#include <turgor/core/mask_select.h>
#include <turgor/core/vector_clones.h>
#include <turgor/physics/hinge_moments.h>
#include <turgor/physics/spring_order.h>
#include <cstring>

namespace turgor {

namespace {
/* The loops below are branch-free and their pointers restrict-qualified, so that GCC vectorises them. */
TURGOR_VECTOR_CLONES void NextBarsGathered(size_t n, const PetscInt *__restrict b, const PetscInt *__restrict c, const PetscReal *__restrict x,
                                           PetscReal *__restrict wx, PetscReal *__restrict wy)
{
  for (size_t h = 0; h < n; h++) wx[h] = x[2 * c[h]] - x[2 * b[h]], wy[h] = x[2 * c[h] + 1] - x[2 * b[h] + 1];
}

TURGOR_VECTOR_CLONES void PreviousBarsLoop(size_t n, const PetscReal *__restrict wx, const PetscReal *__restrict wy, PetscReal *__restrict ux,
                                           PetscReal *__restrict uy)
{
  for (size_t h = 1; h < n; h++) ux[h] = -wx[h - 1], uy[h] = -wy[h - 1];
}

TURGOR_VECTOR_CLONES void SeriesLoop(size_t n, const PetscReal *__restrict ux, const PetscReal *__restrict uy, const PetscReal *__restrict wx,
                                     const PetscReal *__restrict wy, const PetscReal *__restrict cos0, const PetscReal *__restrict sin0,
                                     const PetscReal *__restrict theta_p, PetscReal k, PetscReal Mmax, PetscReal *__restrict d, PetscReal *__restrict iw2,
                                     PetscReal *__restrict M, PetscReal *__restrict general)
{
  for (size_t h = 0; h < n; h++) {
    const HingeBend B = HingeBendOf(ux[h], uy[h], wx[h], wy[h], cos0[h], sin0[h]);
    PetscReal       dh, ih;
    HingeSeries(B, &dh, &ih);
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

TURGOR_VECTOR_CLONES std::uint64_t OrOfBits(size_t n, const PetscReal *__restrict v)
{
  std::uint64_t acc = 0;
  for (size_t h = 0; h < n; h++) {
    std::uint64_t b;
    std::memcpy(&b, v + h, sizeof b);
    acc |= b;
  }
  return acc;
}

/* the general hinges' indices, in order, without a branch */
std::size_t GeneralIndices(size_t n, const PetscReal *__restrict general, PetscInt *__restrict idx)
{
  std::size_t m = 0;
  for (size_t h = 0; h < n; h++) {
    idx[m] = (PetscInt)h;
    m += general[h] != 0;
  }
  return m;
}

/* HingeGeneral's values of the listed hinges, into compact arrays (gathered; no scatter in AVX2) */
TURGOR_VECTOR_CLONES void GeneralLoop(size_t m, const PetscInt *__restrict idx, const PetscReal *__restrict ux, const PetscReal *__restrict uy,
                                      const PetscReal *__restrict wx, const PetscReal *__restrict wy, const PetscReal *__restrict cos0,
                                      const PetscReal *__restrict sin0, const PetscReal *__restrict theta_p, PetscReal k, PetscReal Mmax,
                                      PetscReal *__restrict d, PetscReal *__restrict iw2, PetscReal *__restrict M)
{
  for (size_t j = 0; j < m; j++) {
    const PetscInt  h = idx[j];
    const HingeBend B = HingeBendOf(ux[h], uy[h], wx[h], wy[h], cos0[h], sin0[h]);
    PetscReal       dh, ih;
    HingeGeneral(B, &dh, &ih);
    d[j] = dh, iw2[j] = ih, M[j] = HingeMoment(k, dh, theta_p[h], Mmax);
  }
}

TURGOR_VECTOR_CLONES void InteriorNodeLoop(size_t n, const std::uint64_t *__restrict interior, const PetscReal *__restrict fax, const PetscReal *__restrict fay,
                                           const PetscReal *__restrict fcx, const PetscReal *__restrict fcy, PetscReal *__restrict fb)
{
  for (size_t h = 1; h + 1 < n; h++) {
    const PetscReal gx = fcx[h - 1] - fax[h] - fcx[h] + fax[h + 1], gy = fcy[h - 1] - fay[h] - fcy[h] + fay[h + 1];
    const PetscReal ox = fb[2 * h], oy = fb[2 * h + 1];
    fb[2 * h]     = MaskSelect(interior[h], ox + gx, ox);
    fb[2 * h + 1] = MaskSelect(interior[h], oy + gy, oy);
  }
}
} // namespace

void HingeNextBars(size_t n, const PetscInt *b, const PetscInt *c, bool contiguous, const PetscReal *x, const HingeScratch &S)
{
  if (contiguous) {
    if (n > 1) NextNodeDifferences(n - 1, x + 2 * b[0], S.wx, S.wy); /* not the last: its node b + 1 may not exist */
  } else NextBarsGathered(n, b, c, x, S.wx, S.wy);
}

void HingePreviousBars(size_t n, const HingeScratch &S)
{
  PreviousBarsLoop(n, S.wx, S.wy, S.ux, S.uy);
}

void HingeSeriesMoments(size_t n, const PetscReal *cos0, const PetscReal *sin0, const PetscReal *theta_p, PetscReal k, PetscReal Mmax, const HingeScratch &S)
{
  SeriesLoop(n, S.ux, S.uy, S.wx, S.wy, cos0, sin0, theta_p, k, Mmax, S.d, S.iw2, S.M, S.general);
}

void HingeEndForces(size_t n, const HingeScratch &S, PetscReal *fax, PetscReal *fay, PetscReal *fcx, PetscReal *fcy)
{
  EndForceLoop(n, S.ux, S.uy, S.wx, S.wy, S.iw2, S.M, fax, fay, fcx, fcy);
}

void HingeGeneralMoments(size_t n, const PetscReal *cos0, const PetscReal *sin0, const PetscReal *theta_p, PetscReal k, PetscReal Mmax, const HingeScratch &S,
                         PetscInt *idx, PetscReal *work)
{
  if (OrOfBits(n, S.general) == 0) return; /* none (a scan that vectorises): the usual case */
  const std::size_t m = GeneralIndices(n, S.general, idx);
  PetscReal        *d = work, *iw2 = work + m, *M = work + 2 * m;
  GeneralLoop(m, idx, S.ux, S.uy, S.wx, S.wy, cos0, sin0, theta_p, k, Mmax, d, iw2, M);
  for (std::size_t j = 0; j < m; j++) {
    const PetscInt h = idx[j];
    S.d[h] = d[j], S.iw2[h] = iw2[j], S.M[h] = M[j];
  }
}

void HingeInteriorNodeForces(size_t n, const std::uint64_t *interior, const PetscReal *fax, const PetscReal *fay, const PetscReal *fcx, const PetscReal *fcy,
                             PetscReal *fb)
{
  InteriorNodeLoop(n, interior, fax, fay, fcx, fcy, fb);
}

} // namespace turgor
