#pragma once
/* The hinges' bending, the one formula of the scalar kernel and of the loop the compiler vectorises
   (the hinge term's cost: a division and a series of some 30 operations a hinge). A hinge's angle
   deviation theta - theta0 is atan2(Y, X) of its bars rotated back by the reference angle; hinges bend
   little, so nearly always X > 0 and |Y| <= 0.1 X, where the series of atan(Y / X) is truncated below
   rounding and shares its division with 1/|w|^2. Element by element the loop's arithmetic is the scalar code's,
   in the same order and without fused multiply-adds: a vector build gives the same bits. */
#include <petscsys.h>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace turgor {

/* atan(t) for |t| <= 0.1: the Taylor series to t^15 (the first omitted term t^17/17 < 1e-18: the
   truncation below rounding; with the rounding of its operations within 2.4 ulps, test_hinge_atan2),
   its even and odd halves in t^4 side by side (half the dependency chain of Horner) */
inline PetscReal HingeAtanSeries(PetscReal t)
{
  const PetscReal t2 = t * t, t4 = t2 * t2;
  const PetscReal pe = 1.0 + t4 * (1.0 / 5 + t4 * (1.0 / 9 + t4 * (1.0 / 13)));
  const PetscReal po = -1.0 / 3 + t4 * (-1.0 / 7 + t4 * (-1.0 / 11 + t4 * (-1.0 / 15)));
  return t * (pe + t2 * po);
}

/* atan2(y, x) everywhere, without a branch (a loop of it vectorises; libm's atan2 does neither and
   cost a crushed tissue's hinges twice their series' time): t = min(|x|, |y|) / max(|x|, |y|) in
   [0, 1]; above tan(pi/12) reduced by atan t = pi/6 + atan((sqrt3 t - 1)/(sqrt3 + t)), in one
   division, to |u| <= tan(pi/12), where atan's Taylor series to u^27 is truncated below rounding (the
   first omitted term u^29/29 < 4e-18 u); then the octant undone (pi/2 - a where |y| > |x|, pi - a
   where x < 0, the sign of y). Within 2.83 ulps of the true angle (test_hinge_atan2); 0 at (0, 0). */
inline PetscReal HingeAtan2Wide(PetscReal y, PetscReal x)
{
  /* every branch's value computed, then selected: a select of values the compiler may vectorise, an
     operation under a condition it may not (it could trap) */
  const PetscReal ax = std::fabs(x), ay = std::fabs(y), mx = std::max(ax, ay), mn = std::min(ax, ay);
  const PetscReal s3 = 1.7320508075688772, tan15 = 0.2679491924311227;
  const bool      far = mn > tan15 * mx;
  const PetscReal nf = s3 * mn - mx, df = s3 * mx + mn;
  const PetscReal den = far ? df : mx, u = (far ? nf : mn) / (mx > 0 ? den : 1.0);
  const PetscReal u2 = u * u, u4 = u2 * u2;
  /* even and odd halves in u^4 (half Horner's chain), 14 coefficients 1, -1/3, ..., -1/27 */
  const PetscReal pe = 1.0 + u4 * (1.0 / 5 + u4 * (1.0 / 9 + u4 * (1.0 / 13 + u4 * (1.0 / 17 + u4 * (1.0 / 21 + u4 * (1.0 / 25))))));
  const PetscReal po = -1.0 / 3 + u4 * (-1.0 / 7 + u4 * (-1.0 / 11 + u4 * (-1.0 / 15 + u4 * (-1.0 / 19 + u4 * (-1.0 / 23 + u4 * (-1.0 / 27))))));
  /* the constants pi/6, pi/2, pi as a double and its rest (Cody and Waite), the rest added first */
  const PetscReal a0 = u * (pe + u2 * po), f1 = 0.5235987755982989 + (-5.360408832255455e-17 + a0);
  const PetscReal a1 = far ? f1 : a0, f2 = (1.5707963267948966 - a1) + 6.123233995736766e-17;
  const PetscReal a2 = ay > ax ? f2 : a1, f3 = (3.141592653589793 - a2) + 1.2246467991473532e-16;
  const PetscReal a = x < 0 ? f3 : a2;
  return std::copysign(a, y);
}

/* atan2(y, x) for the hinge angle deviation: where x > 0 and y/x is small, the Taylor series of
   atan(t), t = y/x, truncated where the first omitted term is below 1e-18 relative (cheaper still);
   elsewhere HingeAtan2Wide. */
inline PetscReal HingeAtan2(PetscReal y, PetscReal x)
{
  if (x > 0 && std::fabs(y) <= 0.1 * x) return HingeAtanSeries(y / x);
  return HingeAtan2Wide(y, x);
}

/* A hinge with bars u = x_a - x_b and w = x_c - x_b and reference angle (cos0, sin0): Y, X are the
   sine and cosine of theta - theta0 times |u| |w|. */
struct HingeBend {
  PetscReal Y, X, w2;
};
inline HingeBend HingeBendOf(PetscReal ux, PetscReal uy, PetscReal wx, PetscReal wy, PetscReal cos0, PetscReal sin0)
{
  const PetscReal s = ux * wy - uy * wx, c = ux * wx + uy * wy;
  return {s * cos0 - c * sin0, c * cos0 + s * sin0, wx * wx + wy * wy};
}
/* The usual case, X > 0 and |Y| <= 0.1 X (HingeAtan2's first series; `&`, not `&&`: no branch, so
   that the loop vectorises): d = theta - theta0 and 1/|w|^2 from one division, q = 1 / (X |w|^2). */
inline bool HingeSeriesHolds(const HingeBend &B)
{
  return (B.X > 0) & (std::fabs(B.Y) <= 0.1 * B.X);
}
inline void HingeSeries(const HingeBend &B, PetscReal *d, PetscReal *iw2)
{
  const PetscReal q = 1 / (B.X * B.w2);
  *d                = HingeAtanSeries(B.Y * B.w2 * q);
  *iw2              = B.X * q;
}
/* Elsewhere: HingeAtan2Wide and a division of its own. */
inline void HingeGeneral(const HingeBend &B, PetscReal *d, PetscReal *iw2)
{
  *d   = HingeAtan2Wide(B.Y, B.X);
  *iw2 = 1 / B.w2;
}
/* The moment k (d - theta_p), capped at +-M_max (std::clamp's values, without its branches) */
inline PetscReal HingeMoment(PetscReal k, PetscReal d, PetscReal theta_p, PetscReal Mmax)
{
  return std::min(std::max(k * (d - theta_p), -Mmax), Mmax);
}

/* Per-hinge values of one evaluation, by field. */
struct HingeScratch {
  PetscReal *ux, *uy, *wx, *wy; /* the bars from the hinge node to its previous and next nodes */
  PetscReal *d, *iw2, *M;       /* theta - theta0, 1/|w|^2, the moment */
  PetscReal *general;           /* 1 where the series does not hold: d, iw2 and M to be redone by HingeGeneral */
};

/* w = x_c - x_b of every hinge (nodes b[k], c[k]); where the hinges' nodes are consecutive (b[k] =
   b[0] + k, contiguous: true), x_(b+1) - x_b read in order, without gathering (c is b + 1 but at a
   polygon's last hinge: the caller sets those, and the very last hinge's). */
void HingeNextBars(size_t n, const PetscInt *b, const PetscInt *c, bool contiguous, const PetscReal *x, const HingeScratch &S);
/* u = -(the previous hinge's w) of every hinge but the first (the caller sets each polygon's first). */
void HingePreviousBars(size_t n, const HingeScratch &S);
/* Every hinge's bend and moment from u and w, by the series whether it holds or not (`general` marks
   where it does not). */
void HingeSeriesMoments(size_t n, const PetscReal *cos0, const PetscReal *sin0, const PetscReal *theta_p, PetscReal k, PetscReal Mmax, const HingeScratch &S);

/* The forces M/l perpendicular to each bar at its far node, f_a = M/|u|^2 perp(u) with perp(v) =
   (-v_y, v_x) and f_c = -M/|w|^2 perp(w), of every hinge but the first, with 1/|u|^2 the 1/|w|^2 of
   the hinge before (the caller sets those of each polygon's first hinge). */
void HingeEndForces(size_t n, const HingeScratch &S, PetscReal *fax, PetscReal *fay, PetscReal *fcx, PetscReal *fcy);

/* The hinges outside the series (`general`), their d, 1/|w|^2 and M redone by HingeGeneral: their
   indices listed without a branch (in a crushed tissue a branch per hinge mispredicts), then
   computed in a loop that vectorises. idx: room for n indices, work: for 3 n values. */
void HingeGeneralMoments(size_t n, const PetscReal *cos0, const PetscReal *sin0, const PetscReal *theta_p, PetscReal k, PetscReal Mmax, const HingeScratch &S,
                         PetscInt *idx, PetscReal *work);

/* The hinges' nodes in order (b_h = b_0 + h, fb = f + 2 b_0): every interior hinge's node (interior[h]
   all ones: neither the first nor the last of its polygon; else 0) takes f += ((fc_(h-1) - fa_h) - fc_h) + fa_(h+1),
   the one-pass kernel's sum for it; the others are left to the caller. */
void HingeInteriorNodeForces(size_t n, const std::uint64_t *interior, const PetscReal *fax, const PetscReal *fay, const PetscReal *fcx, const PetscReal *fcy,
                             PetscReal *fb);

} // namespace turgor
