#include <turgor/physics/contact_first_pass.h>
#include <turgor/core/vector_clones.h>
#if defined(__SSE2__)
  #include <emmintrin.h>
#endif
#if defined(TURGOR_AVX_PATHS)
  #include <immintrin.h>
#endif
#include <algorithm>

namespace turgor {

/* Hand-written with SSE2 intrinsics because GCC keeps the scalar loop's clamp max(proj, 0) as a
   branch (that mispredicts where nodes sit at the bars' ends) and does each (x, y) operation twice;
   here each point is one register, the clamp maxsd/minsd. The same operations in the same order as
   the scalar formula, so the same comparisons (the clamp's sign of a zero t may differ, which changes
   no product's magnitude). */
#if defined(__SSE2__)
static inline bool PairTouches(const PetscReal *x, std::uint32_t p2, std::uint32_t a2, std::uint32_t b2, PetscReal R2)
{
  const __m128d zero = _mm_setzero_pd();
  const __m128d xa = _mm_loadu_pd(x + a2), e = _mm_sub_pd(_mm_loadu_pd(x + b2), xa), p = _mm_sub_pd(_mm_loadu_pd(x + p2), xa);
  const __m128d ee = _mm_mul_pd(e, e), pe = _mm_mul_pd(p, e);
  const __m128d L2 = _mm_add_sd(ee, _mm_unpackhi_pd(ee, ee)), proj = _mm_add_sd(pe, _mm_unpackhi_pd(pe, pe)); /* ex ex + ey ey, px ex + py ey */
  const __m128d t   = _mm_min_sd(_mm_max_sd(proj, zero), L2);
  const __m128d d   = _mm_sub_pd(_mm_mul_pd(p, _mm_unpacklo_pd(L2, L2)), _mm_mul_pd(_mm_unpacklo_pd(t, t), e)); /* p L2 - t e */
  const __m128d dd  = _mm_mul_pd(d, d);
  const double  L2s = _mm_cvtsd_f64(L2), d2 = _mm_cvtsd_f64(_mm_add_sd(dd, _mm_unpackhi_pd(dd, dd)));
  return d2 < R2 * L2s * L2s;
}
#endif

TURGOR_VECTOR_CLONES
size_t ContactTouchingPairsOneByOne(const ContactNearPair *near, size_t n, const PetscReal *x, PetscReal R2, PetscInt *touch)
{
  size_t nt = 0;
  for (size_t j = 0; j < n; j++) {
    const ContactNearPair &C = near[j];
    touch[nt]                = (PetscInt)j;
#if defined(__SSE2__)
    nt += PairTouches(x, C.p2, C.a2, C.b2, R2);
#else
    const PetscReal ex = x[C.b2] - x[C.a2], ey = x[C.b2 + 1] - x[C.a2 + 1];
    const PetscReal px = x[C.p2] - x[C.a2], py = x[C.p2 + 1] - x[C.a2 + 1];
    const PetscReal L2 = ex * ex + ey * ey, t = std::min(std::max(px * ex + py * ey, (PetscReal)0), L2);
    const PetscReal dx = px * L2 - t * ex, dy = py * L2 - t * ey;
    nt += (dx * dx + dy * dy < R2 * L2 * L2);
#endif
  }
  return nt;
}

#if defined(TURGOR_AVX_PATHS)
/* the points x[i..i+1] and x[j..j+1] in one register */
TURGOR_AVX_TARGET static inline __m256d TwoPoints(const PetscReal *x, std::uint32_t i, std::uint32_t j)
{
  return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(x + i)), _mm_loadu_pd(x + j), 1);
}

/* Two pairs in one 256-bit register each (the first pair's (x, y) in the low half): the horizontal
   adds give |e|^2 and proj of both at once. Lane by lane the SSE2 pass's operations in its order,
   so the same comparisons. */
TURGOR_AVX_TARGET static size_t TouchingPairsAVX(const ContactNearPair *near, size_t n, const PetscReal *x, PetscReal R2, PetscInt *touch)
{
  const __m256d zero = _mm256_setzero_pd(), R2v = _mm256_set1_pd(R2);
  size_t        nt = 0, j = 0;
  for (; j + 1 < n; j += 2) {
    const ContactNearPair &C = near[j], &D = near[j + 1];
    const __m256d          xa = TwoPoints(x, C.a2, D.a2), e = _mm256_sub_pd(TwoPoints(x, C.b2, D.b2), xa), p = _mm256_sub_pd(TwoPoints(x, C.p2, D.p2), xa);
    const __m256d          h  = _mm256_hadd_pd(_mm256_mul_pd(e, e), _mm256_mul_pd(p, e)); /* |e|^2, proj of C; of D */
    const __m256d          L2 = _mm256_movedup_pd(h), t = _mm256_min_pd(_mm256_max_pd(_mm256_permute_pd(h, 0xF), zero), L2);
    const __m256d          d  = _mm256_sub_pd(_mm256_mul_pd(p, L2), _mm256_mul_pd(t, e)); /* p L2 - t e */
    const __m256d          dd = _mm256_mul_pd(d, d);
    const int              m  = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_hadd_pd(dd, dd), _mm256_mul_pd(_mm256_mul_pd(R2v, L2), L2), _CMP_LT_OQ));
    touch[nt]                 = (PetscInt)j;
    nt += m & 1;
    touch[nt] = (PetscInt)j + 1;
    nt += (m >> 2) & 1;
  }
  if (j < n) {
    touch[nt] = (PetscInt)j;
    nt += PairTouches(x, near[j].p2, near[j].a2, near[j].b2, R2);
  }
  return nt;
}
#endif

size_t ContactTouchingPairs(const ContactNearPair *near, size_t n, const PetscReal *x, PetscReal R2, PetscInt *touch)
{
#if defined(TURGOR_AVX_PATHS)
  if (TURGOR_HAS_AVX()) return TouchingPairsAVX(near, n, x, R2, touch);
#endif
  return ContactTouchingPairsOneByOne(near, n, x, R2, touch);
}

} // namespace turgor
