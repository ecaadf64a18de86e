#include <turgor/physics/repulsion.h>
#include <algorithm>
#include <cmath>

namespace turgor {

/* The joint weight across the wedge, z in [-1, 1] -> [0, 1]: the quintic smoothstep, whose first
   and second derivatives vanish at both edges (so the force, which holds its first derivative, is
   continuously differentiable there); S(-z) = 1 - S(z), so the two springs of a joint share 1. */
static inline PetscReal BlendWeight(PetscReal z)
{
  const PetscReal z2 = z * z;
  return 0.5 + z * (15.0 - z2 * (10.0 - 3.0 * z2)) / 16.0;
}
static inline PetscReal BlendSlope(PetscReal z)
{
  const PetscReal c = 1.0 - z * z;
  return 15.0 / 16.0 * c * c;
}

PetscErrorCode Repulsion::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "repulsion_", "Particle-spring repulsion (TW 562 eq 17)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-strength", "Strength lambda [µN µm^6]", "Repulsion", strength, &strength, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-cutoff", "Cutoff distance x0 [µm]", "Repulsion", cutoff, &cutoff, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-angle_factor",
                              "Scale by cos(alpha), alpha = angle between x - x^ and the spring normal (beyond a free end of a wall)", "Repulsion",
                              angle_factor, &angle_factor, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-damping", "Critical damping term 2 sqrt(6 lambda m / r^7)", "Repulsion", damping, &damping, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-damping_taper",
                              "Scale the damping by 1 - (r/x0)^6 so that it vanishes at the cutoff like the force (off: the seed's literal term, which jumps "
                              "at r = x0)",
                              "Repulsion", damping_taper, &damping_taper, NULL));
  PetscCall(
    TurgorOptionsReal(ctx.params, "-joint_blend",
                      "Half-angle [degrees] of the wedge around the bisector of a wall joint over which its two springs hand a particle over smoothly (0: "
                      "at the bisector, with a force that jumps at bent joints)",
                      "Repulsion", joint_blend, &joint_blend, NULL));
  PetscOptionsEnd();
  PetscCheck(strength >= 0 && std::isfinite(strength), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -repulsion_strength = %g: must be finite and >= 0",
             (double)strength);
  PetscCheck(cutoff > 0 && std::isfinite(cutoff), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -repulsion_cutoff = %g: must be finite and > 0", (double)cutoff);
  /* wider wedges overlap within x0 on walls of short springs and reach the line of the other spring
     of a strongly bent joint (docs/model.md) */
  PetscCheck(joint_blend >= 0 && joint_blend <= 30, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -repulsion_joint_blend = %g: must be in [0, 30] degrees",
             (double)joint_blend);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  const size_t ns = P.springs.size();
  PetscFunctionBeginUser;
  const PetscReal sb = std::sin(joint_blend * PETSC_PI / 180.0);
  derived_           = {cutoff * cutoff, sb, sb * sb, Extension()};
  nb.RequestParticleSpringPairs(cutoff + derived_.extension);
  seg_.resize(ns);
  joint_.resize(2 * ns);
  joined_.assign(ns, 0);
  for (size_t s = 0; s < ns; s++)
    for (int e = 0; e < 2; e++) {
      const PetscInt code = 2 * (PetscInt)s + e, other = P.springs[s].joint[e];
      PetscCheck(other < (PetscInt)(2 * ns) && (other < 0 || P.springs[other / 2].joint[other % 2] == code), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                 "Spring %" PetscInt_FMT ": its joint at end %d is not mutual", (PetscInt)s, e);
      joint_[code] = other;
      if (other >= 0) joined_[s] |= (unsigned char)(1 << e);
    }
  damping_coefficient_.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) damping_coefficient_[i] = 2.0 * std::sqrt(6.0 * strength * P.mass[i]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Spring vectors and the bisectors of the joints, once per evaluation (a spring is near ~7
   particles in a tissue). At a joint of springs s (outward unit direction u from the joint) and s'
   (u'), the bisector is the line through the joint point normal to g = u - u'; s keeps n = g/|g|,
   s' gets -n exactly. */
void Repulsion::Segments(const ForceInput &in)
{
  const PetscReal   *x = in.x;
  const ParticleSet &P = *in.P;
  for (size_t s = 0; s < P.springs.size(); s++) {
    const PetscInt   i1 = P.springs[s].i, i2 = P.springs[s].j;
    const PetscReal *sx = in.images->x[P.springs[s].image];
    const PetscReal  tx = x[2 * i2] + sx[0] - x[2 * i1], ty = x[2 * i2 + 1] + sx[1] - x[2 * i1 + 1], L2 = tx * tx + ty * ty;
    seg_[s] = {
      tx, ty, L2 > 0 ? 1.0 / L2 : 0.0, L2 > 0 ? 1.0 / std::sqrt(L2) : 0.0, {0, 0},
                          {0, 0}
    };
  }
  for (size_t s = 0; s < P.springs.size(); s++)
    for (int e = 0; e < 2; e++) {
      const PetscInt other = joint_[2 * s + e];
      if (other < 0) continue;
      const Segment  &a = seg_[s], &b = seg_[other / 2];
      const PetscReal sa = e ? -a.inv_L : a.inv_L, sb = other % 2 ? -b.inv_L : b.inv_L; /* outward: +t at end i, -t at end j */
      const PetscReal gx = sa * a.tx - sb * b.tx, gy = sa * a.ty - sb * b.ty, gn = std::sqrt(gx * gx + gy * gy);
      /* a joint folded flat onto itself has no bisector: n = 0 shares every particle half and half */
      seg_[s].nx[e] = gn > 0 ? gx / gn : 0.0;
      seg_[s].ny[e] = gn > 0 ? gy / gn : 0.0;
    }
}

/* The closest point of pair q's spring image to its particle, within the cutoff, and the pair's
   joint weight, nonzero. The closest point is sought on the spring continued by the extension
   beyond each joined end (straight: beyond the joint it stands for its neighbour's line), clamped
   at its end points elsewhere. At a joined end, with q = p - x_joint, rho = |q| and xi = q . n the
   signed distance from the bisector, the weight is S(z), z = xi / (rho sin beta), inside the wedge
   |z| < 1, and 1 or 0 outside it on this or the other spring's side. */
inline bool Repulsion::Pair(const ForceInput &in, const PointSegmentList &L, size_t q, PairGeometry &g) const
{
  const PetscReal *x  = in.x;
  const PetscInt   s  = L.s[q];
  const Segment   &sg = seg_[s];
  const PetscInt   p = L.p[q], i1 = in.P->springs[s].i;
  const PetscReal *px = in.images->x[L.Image(q)]; /* the spring's image near p */
  const PetscReal  wx = x[2 * p] - x[2 * i1] - px[0], wy = x[2 * p + 1] - x[2 * i1 + 1] - px[1];
  const unsigned   joined = joined_[s];
  const Derived   &c      = derived_;
  PetscReal        lo = 0, hi = 1, w0 = 1, w1 = 1;
  unsigned         blend = 0;
  /* the joints first: a particle on the other spring's side is rejected at once. Outside the
     wedge the weight is 1 or 0 (0.5 on the bisector itself, only without a wedge); a NaN position
     goes on, to a NaN force */
  if (joined & 1) {
    const PetscReal xi = wx * sg.nx[0] + wy * sg.ny[0], rho2 = wx * wx + wy * wy;
    if (xi * xi >= c.sin_blend2 * rho2) {
      if (xi < 0) return false;
      if (!(xi > 0)) w0 = 0.5;
    } else {
      g.z[0] = xi / (std::sqrt(rho2) * c.sin_blend);
      w0     = BlendWeight(g.z[0]);
      blend  = 1;
    }
    lo = -c.extension * sg.inv_L;
  }
  if (joined & 2) {
    const PetscReal qx = wx - sg.tx, qy = wy - sg.ty;
    const PetscReal xi = qx * sg.nx[1] + qy * sg.ny[1], rho2 = qx * qx + qy * qy;
    if (xi * xi >= c.sin_blend2 * rho2) {
      if (xi < 0) return false;
      if (!(xi > 0)) w1 = 0.5;
    } else {
      g.z[1] = xi / (std::sqrt(rho2) * c.sin_blend);
      w1     = BlendWeight(g.z[1]);
      blend |= 2;
    }
    hi = 1.0 + c.extension * sg.inv_L;
  }
  const PetscReal t = (wx * sg.tx + wy * sg.ty) * sg.inv_L2;
  g.t               = std::min(hi, std::max(lo, t));
  g.dx              = wx - g.t * sg.tx;
  g.dy              = wy - g.t * sg.ty;
  g.r2              = g.dx * g.dx + g.dy * g.dy;
  if (g.r2 >= c.cutoff2) return false; /* (a NaN position still gives a NaN force) */
  g.wx     = wx;
  g.wy     = wy;
  g.we[0]  = w0;
  g.we[1]  = w1;
  g.weight = w0 * w1;
  g.blend  = blend;
  g.clamp  = t < lo ? ((joined & 1) ? 1 : -1) : (t > hi ? ((joined & 2) ? 1 : -1) : 0);
  return true;
}

/* The forces of the joint weight's gradient at end e of spring s, for particle p at q = p - x_joint
   (wedge coordinate z): coef dz/dx on every particle z depends on -- p, the joint, this spring's
   other end a and the joined spring's other end a' (through the bisector's direction) -- with
   coef = -phi(r) w_other S'(z). z is invariant under translation and rotation, so the four forces
   add up to zero and have no torque. */
void Repulsion::BlendForces(const ForceInput &in, PetscInt p, PetscInt s, int e, const PetscReal q[2], PetscReal coef, PetscReal *f, PetscReal *virial) const
{
  const ParticleSet &P     = *in.P;
  const PetscInt     other = joint_[2 * s + e], s2 = other / 2;
  const int          e2 = (int)(other % 2);
  const Segment     &a = seg_[s], &b = seg_[s2];
  const PetscInt     J = e ? P.springs[s].j : P.springs[s].i, A = e ? P.springs[s].i : P.springs[s].j, A2 = e2 ? P.springs[s2].i : P.springs[s2].j;
  /* a - x_joint = La u and a' - x_joint = Lb u' */
  const PetscReal lax = e ? -a.tx : a.tx, lay = e ? -a.ty : a.ty, lbx = e2 ? -b.tx : b.tx, lby = e2 ? -b.ty : b.ty;
  const PetscReal ux = lax * a.inv_L, uy = lay * a.inv_L, vx = lbx * b.inv_L, vy = lby * b.inv_L;
  const PetscReal gx = ux - vx, gy = uy - vy, gn = std::sqrt(gx * gx + gy * gy);
  const PetscReal nx = a.nx[e], ny = a.ny[e];
  const PetscReal rho2 = q[0] * q[0] + q[1] * q[1], rho = std::sqrt(rho2), xi = q[0] * nx + q[1] * ny, c = 1.0 / (rho * derived_.sin_blend);
  /* dz/dq = (n - (xi/rho^2) q) / (rho sin beta) */
  const PetscReal fpx = coef * c * (nx - xi / rho2 * q[0]), fpy = coef * c * (ny - xi / rho2 * q[1]);
  /* dz/dg = (q - xi n) / (|g| rho sin beta), g = u - u', du/da = (I - u u^T)/La, du'/da' = (I - u' u'^T)/Lb */
  PetscReal fax = 0, fay = 0, fbx = 0, fby = 0;
  if (gn > 0) {
    const PetscReal Gx = c / gn * (q[0] - xi * nx), Gy = c / gn * (q[1] - xi * ny), uG = ux * Gx + uy * Gy, vG = vx * Gx + vy * Gy;
    fax = coef * a.inv_L * (Gx - uG * ux);
    fay = coef * a.inv_L * (Gy - uG * uy);
    fbx = -coef * b.inv_L * (Gx - vG * vx);
    fby = -coef * b.inv_L * (Gy - vG * vy);
  }
  const ForceGrain &grain = in.Grain();
  PetscReal         gpx = fpx, gpy = fpy, gax = fax, gay = fay, gbx = fbx, gby = fby;
  grain(gpx, gpy), grain(gax, gay), grain(gbx, gby);
  f[2 * p] += gpx;
  f[2 * p + 1] += gpy;
  f[2 * A] += gax;
  f[2 * A + 1] += gay;
  f[2 * A2] += gbx;
  f[2 * A2 + 1] += gby;
  f[2 * J] -= gpx + gax + gbx;
  f[2 * J + 1] -= gpy + gay + gby;
  if (virial) { /* -sum_k f_k (x) (x_k - x_joint) */
    virial[0] -= fpx * q[0] + fax * lax + fbx * lbx;
    virial[1] -= fpx * q[1] + fax * lay + fbx * lby;
    virial[2] -= fpy * q[0] + fay * lax + fby * lbx;
    virial[3] -= fpy * q[1] + fay * lay + fby * lby;
  }
}

/* x^ is the tip of the extension at end e, x_joint - E u: its reaction is the gradient through u
   as well (the point is not a fixed mix of the end points), -F - (E/L) F_perp on the joint and
   (E/L) F_perp on the other end, F_perp = F - (u.F) u; the virial's extra part is E (u.F) u (x) u. */
void Repulsion::TipReaction(const ForceInput &in, PetscInt s, int e, PetscReal fx, PetscReal fy, PetscReal *f, PetscReal *virial) const
{
  const Segment  &sg = seg_[s];
  const PetscInt  J = e ? in.P->springs[s].j : in.P->springs[s].i, A = e ? in.P->springs[s].i : in.P->springs[s].j;
  const PetscReal ux = (e ? -sg.tx : sg.tx) * sg.inv_L, uy = (e ? -sg.ty : sg.ty) * sg.inv_L, uF = ux * fx + uy * fy, k = derived_.extension * sg.inv_L;
  /* fx, fy: the caller's share, already rounded to the grain */
  PetscReal px = k * (fx - uF * ux), py = k * (fy - uF * uy);
  in.Grain()(px, py);
  f[2 * J] -= fx + px;
  f[2 * J + 1] -= fy + py;
  f[2 * A] += px;
  f[2 * A + 1] += py;
  if (virial) {
    virial[0] += derived_.extension * uF * ux * ux;
    virial[1] += derived_.extension * uF * ux * uy;
    virial[2] += derived_.extension * uF * uy * ux;
    virial[3] += derived_.extension * uF * uy * uy;
  }
}

/* The weight's own gradient for a pair inside one or both wedges of its spring: -phi(r) grad W,
   phi = lambda (r^-5/5 + r/x0^6 - 6/(5 x0^5)); returns the number of wedges. */
PetscInt Repulsion::WeightGradientForces(const ForceInput &in, PetscInt p, PetscInt s, const PairGeometry &g, PetscReal *f, PetscReal *virial) const
{
  const Segment  &sg = seg_[s];
  const PetscReal r = std::sqrt(g.r2), phi = strength * (1.0 / (5.0 * std::pow(r, 5)) + r / std::pow(cutoff, 6) - 1.2 / std::pow(cutoff, 5));
  PetscInt        n = 0;
  for (int e = 0; e < 2; e++) {
    if (!(g.blend & (1u << e))) continue;
    const PetscReal qe[2] = {e ? g.wx - sg.tx : g.wx, e ? g.wy - sg.ty : g.wy};
    BlendForces(in, p, s, e, qe, -phi * g.we[1 - e] * BlendSlope(g.z[e]), f, virial);
    n++;
  }
  return n;
}

template <bool VIRIAL, bool ROUND>
PetscErrorCode Repulsion::Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const PetscReal        *v   = in.v;
  const ParticleSet      &P   = *in.P;
  const PointSegmentList &L   = in.nb->ParticleSpringPairs();
  const PetscReal         x02 = cutoff * cutoff, ix06 = 1.0 / (x02 * x02 * x02);
  const ForceGrain       &grain  = in.Grain();
  PetscReal               w[4]   = {0, 0, 0, 0};
  PetscInt                active = 0, blended = 0;

  PetscFunctionBeginUser;
  Segments(in);
  for (size_t q = 0; q < L.size(); q++) {
    PairGeometry g;
    if (!Pair(in, L, q, g)) continue;
    active++;
    const PetscInt  s = L.s[q], p = L.p[q], i1 = P.springs[s].i, i2 = P.springs[s].j;
    const Segment  &sg = seg_[s];
    const PetscReal t = g.t, dx = g.dx, dy = g.dy, r2 = g.r2;
    /* a particle exactly on a spring (r = 0) gets a NaN force: the caller rejects the state
       (a too large step or a crossed wall) instead of aborting */
    const PetscReal ir = 1.0 / std::sqrt(r2), ir2 = ir * ir, ir6 = ir2 * ir2 * ir2;
    const PetscReal ex = dx * ir, ey = dy * ir;
    /* cos(alpha) = |d x t| / (|d| |t|): < 1 only beyond a free end (elsewhere d is normal to the spring
       or to its continuation) */
    const PetscReal cosa = angle_factor && g.clamp < 0 ? std::fabs(dx * sg.ty - dy * sg.tx) * ir * sg.inv_L : 1.0;
    PetscReal       mag  = strength * cosa * (ir6 - ix06);
    if (damping) { /* - 2 sqrt(6 lambda m / r^7) (x - x^).(v - v^)/r, v^ interpolated like x^ */
      const PetscReal *pv = in.images->v[L.Image(q)], *sv = in.images->v[P.springs[s].image];
      const PetscReal  vhx = (1 - t) * v[2 * i1] + t * (v[2 * i2] + sv[0]) + pv[0], vhy = (1 - t) * v[2 * i1 + 1] + t * (v[2 * i2 + 1] + sv[1]) + pv[1];
      /* the taper makes the force continuous at r = x0 for moving particles: the literal term jumps
         there, which stalls Newton in an RVE whose particles move with Fdot X (docs/model.md) */
      const PetscReal taper = damping_taper ? 1.0 - r2 * r2 * r2 * ix06 : 1.0;
      mag -= taper * damping_coefficient_[p] * ir2 * ir * std::sqrt(ir) * /* r^-3.5 */ ((v[2 * p] - vhx) * ex + (v[2 * p + 1] - vhy) * ey);
    }
    mag *= g.weight;
    PetscReal fx = mag * ex, fy = mag * ey;
    if (ROUND) grain(fx, fy); /* a template argument: no test per pair without */
    f[2 * p] += fx;
    f[2 * p + 1] += fy;
    if (PetscLikely(g.clamp <= 0)) {
      PetscReal f1x = (1 - t) * fx, f1y = (1 - t) * fy, f2x = t * fx, f2y = t * fy;
      if (ROUND) grain(f1x, f1y), grain(f2x, f2y);
      f[2 * i1] -= f1x;
      f[2 * i1 + 1] -= f1y;
      f[2 * i2] -= f2x;
      f[2 * i2 + 1] -= f2y;
    } else TipReaction(in, s, t < 0.5 ? 0 : 1, fx, fy, f, VIRIAL ? w : NULL);
    if (VIRIAL) { /* -(F x_p - (1-t) F x1 - t F x2) = -F (x) d */
      w[0] -= fx * dx;
      w[1] -= fx * dy;
      w[2] -= fy * dx;
      w[3] -= fy * dy;
    }
    if (PetscUnlikely(g.blend)) blended += WeightGradientForces(in, p, s, g, f, VIRIAL ? w : NULL);
  }
  if (VIRIAL)
    for (int k = 0; k < 4; k++) virial[k] += w[k];
  PetscCall(PetscLogFlops(16.0 * P.springs.size() + 20.0 * L.size() + 60.0 * active + 80.0 * blended));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  const bool rounded = in.Grain().On();
  if (virial) PetscCall(rounded ? Kernel<true, true>(in, f, virial) : Kernel<true, false>(in, f, virial));
  else PetscCall(rounded ? Kernel<false, true>(in, f, NULL) : Kernel<false, false>(in, f, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  const PointSegmentList &L   = in.nb->ParticleSpringPairs();
  const PetscReal         x05 = std::pow(cutoff, 5), x06 = x05 * cutoff;

  PetscFunctionBeginUser;
  Segments(in);
  *E = 0;
  for (size_t q = 0; q < L.size(); q++) {
    PairGeometry g;
    if (!Pair(in, L, q, g)) continue;
    const PetscReal r = std::sqrt(g.r2);
    *E += g.weight * strength * (1.0 / (5.0 * std::pow(r, 5)) + r / x06 - 6.0 / (5.0 * x05));
  }
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Stiffness of the repulsion at the closest current approach r_min: 6 lambda / r^7, with its
   critical damping; an explicit step needs dt < 2 / (c/2 + sqrt(c^2/4 + w^2)). */
PetscErrorCode Repulsion::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  const PointSegmentList &L    = in.nb->ParticleSpringPairs();
  const ParticleSet      &P    = *in.P;
  PetscReal               best = PETSC_MAX_REAL, rbest = 0;

  PetscFunctionBeginUser;
  Segments(in);
  for (size_t q = 0; q < L.size(); q++) {
    PairGeometry g;
    if (!Pair(in, L, q, g)) continue;
    const PetscReal r = std::sqrt(g.r2);
    if (r <= 0) continue;
    /* reduced mass of the particle against an end point */
    const PetscInt  p = L.p[q], i1 = P.springs[L.s[q]].i;
    const PetscReal m  = P.mass[p] * P.mass[i1] / (P.mass[p] + P.mass[i1]);
    const PetscReal k  = 6.0 * strength / std::pow(r, 7);
    const PetscReal w2 = k / m, cr = damping ? 2.0 * std::sqrt(k * P.mass[p]) / m : 0.0;
    const PetscReal dt = 2.0 / (0.5 * cr + std::sqrt(0.25 * cr * cr + w2));
    if (dt < best) {
      best  = dt;
      rbest = r;
    }
  }
  if (best < PETSC_MAX_REAL) {
    char why[256];
    PetscCall(PetscSNPrintf(why, sizeof why, "repulsion: stiffness 6 lambda/r^7 at the closest approach r = %.3g µm", (double)rbest));
    limits.push_back({best, why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(
    PetscViewerASCIIPrintf(viewer,
                           "repulsion: lambda = %g µN µm^6, x0 = %g µm, angle factor %s, damping %s, each wall pushes once (joints blended over %g degrees)\n",
                           (double)strength, (double)cutoff, angle_factor ? "on" : "off",
                           damping ? (damping_taper ? "on, tapered to 0 at x0" : "on, literal") : "off", (double)joint_blend));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
