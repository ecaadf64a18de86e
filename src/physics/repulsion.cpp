#include <turgor/physics/repulsion.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode Repulsion::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "repulsion_", "Particle-spring repulsion (TW 562 eq 17)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-strength", "Strength lambda [µN µm^6]", "Repulsion", strength, &strength, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-cutoff", "Cutoff distance x0 [µm]", "Repulsion", cutoff, &cutoff, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-angle_factor", "Scale by cos(alpha), alpha = angle between x - x^ and the spring normal", "Repulsion", angle_factor,
                              &angle_factor, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-damping", "Critical damping term 2 sqrt(6 lambda m / r^7)", "Repulsion", damping, &damping, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-damping_taper",
                              "Scale the damping by 1 - (r/x0)^6 so that it vanishes at the cutoff like the force (off: the seed's literal term, which jumps "
                              "at r = x0)",
                              "Repulsion", damping_taper, &damping_taper, NULL));
  PetscOptionsEnd();
  PetscCheck(strength >= 0 && std::isfinite(strength), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -repulsion_strength = %g: must be finite and >= 0",
             (double)strength);
  PetscCheck(cutoff > 0 && std::isfinite(cutoff), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -repulsion_cutoff = %g: must be finite and > 0", (double)cutoff);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  const size_t ns = P.springs.size();
  PetscFunctionBeginUser;
  nb.RequestParticleSpringPairs(cutoff);
  seg_.resize(ns);
  joint_.resize(2 * ns);
  ties_.assign(ns, 0);
  for (size_t s = 0; s < ns; s++)
    for (int e = 0; e < 2; e++) {
      const PetscInt code = 2 * (PetscInt)s + e, other = P.springs[s].joint[e];
      PetscCheck(other < (PetscInt)(2 * ns) && (other < 0 || P.springs[other / 2].joint[other % 2] == code), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                 "Spring %" PetscInt_FMT ": its joint at end %d is not mutual", (PetscInt)s, e);
      joint_[code] = other;
      /* a particle exactly on the bisector belongs to the end with the lower code (and always to an
         end where the wall ends: g = 0 there) */
      if (other < 0 || code < other) ties_[s] |= (unsigned char)(1 << e);
    }
  damping_coefficient_.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) damping_coefficient_[i] = 2.0 * std::sqrt(6.0 * strength * P.mass[i]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Spring vectors and the bisectors of the straight joints, once per evaluation (a spring is near
   ~7 particles in a tissue). At a joint of springs s (outward unit direction u from the joint) and
   s' (u'), the bisector is the line through the joint point normal to g = u - u'; s takes the
   particles with (p - x_joint) . g > 0 and s' those with < 0 (g' = -g exactly). */
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
      seg_[s].gx[e] = sa * a.tx - sb * b.tx;
      seg_[s].gy[e] = sa * a.ty - sb * b.ty;
    }
}

/* The closest point of pair q's spring image to its particle, and whether the pair counts: p must
   be on this spring's side of the bisector at both ends. Both p - x1 and p - x2 are taken from the
   positions directly, so that a particle on a joint's bisector is seen identically from both springs
   (without periodic images: bitwise) and counted exactly once. */
inline bool Repulsion::Pair(const ForceInput &in, const PointSegmentList &L, size_t q, PairGeometry &g) const
{
  const PetscReal *x  = in.x;
  const Spring    &sp = in.P->springs[L.s[q]];
  const Segment   &sg = seg_[L.s[q]];
  const PetscInt   p = L.p[q], i1 = sp.i, i2 = sp.j;
  const PetscReal *px = in.images->x[L.Image(q)], *sx = in.images->x[sp.image]; /* the spring's image near p; x2's image */
  const PetscReal  wx = x[2 * p] - x[2 * i1] - px[0], wy = x[2 * p + 1] - x[2 * i1 + 1] - px[1];
  const PetscReal  ux = x[2 * p] - x[2 * i2] - sx[0] - px[0], uy = x[2 * p + 1] - x[2 * i2 + 1] - sx[1] - px[1];
  const PetscReal  gi = wx * sg.gx[0] + wy * sg.gy[0], gj = ux * sg.gx[1] + uy * sg.gy[1];
  const unsigned   tie = ties_[L.s[q]];
  if (gi < 0 || (gi == 0 && !(tie & 1)) || gj < 0 || (gj == 0 && !(tie & 2))) return false; /* (a NaN position still gives a NaN force) */
  g.t  = std::min((PetscReal)1, std::max((PetscReal)0, (wx * sg.tx + wy * sg.ty) * sg.inv_L2));
  g.dx = wx - g.t * sg.tx;
  g.dy = wy - g.t * sg.ty;
  g.r2 = g.dx * g.dx + g.dy * g.dy;
  return true;
}

template <bool VIRIAL>
PetscErrorCode Repulsion::Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const PetscReal        *v   = in.v;
  const ParticleSet      &P   = *in.P;
  const PointSegmentList &L   = in.nb->ParticleSpringPairs();
  const PetscReal         x02 = cutoff * cutoff, ix06 = 1.0 / (x02 * x02 * x02);
  PetscReal               w[4]   = {0, 0, 0, 0};
  PetscInt                active = 0;

  PetscFunctionBeginUser;
  Segments(in);
  for (size_t q = 0; q < L.size(); q++) {
    PairGeometry g;
    if (!Pair(in, L, q, g) || g.r2 >= x02) continue;
    active++;
    const PetscInt  p = L.p[q], i1 = P.springs[L.s[q]].i, i2 = P.springs[L.s[q]].j;
    const Segment  &sg = seg_[L.s[q]];
    const PetscReal t = g.t, dx = g.dx, dy = g.dy, r2 = g.r2;
    /* a particle exactly on a spring (r = 0) gets a NaN force: the caller rejects the state
       (a too large step or a crossed wall) instead of aborting */
    const PetscReal ir = 1.0 / std::sqrt(r2), ir2 = ir * ir, ir6 = ir2 * ir2 * ir2;
    const PetscReal ex = dx * ir, ey = dy * ir;
    /* cos(alpha) = |d x t| / (|d| |t|): 1 when x^ is inside the spring, < 1 beyond its ends */
    const PetscReal cosa = angle_factor ? std::fabs(dx * sg.ty - dy * sg.tx) * ir * sg.inv_L : 1.0;
    PetscReal       mag  = strength * cosa * (ir6 - ix06);
    if (damping) { /* - 2 sqrt(6 lambda m / r^7) (x - x^).(v - v^)/r, v^ interpolated like x^ */
      const PetscReal *pv = in.images->v[L.Image(q)], *sv = in.images->v[P.springs[L.s[q]].image];
      const PetscReal  vhx = (1 - t) * v[2 * i1] + t * (v[2 * i2] + sv[0]) + pv[0], vhy = (1 - t) * v[2 * i1 + 1] + t * (v[2 * i2 + 1] + sv[1]) + pv[1];
      /* the taper makes the force continuous at r = x0 for moving particles: the literal term jumps
         there, which stalls Newton in an RVE whose particles move with Fdot X (docs/model.md) */
      const PetscReal taper = damping_taper ? 1.0 - r2 * r2 * r2 * ix06 : 1.0;
      mag -= taper * damping_coefficient_[p] * ir2 * ir * std::sqrt(ir) * /* r^-3.5 */ ((v[2 * p] - vhx) * ex + (v[2 * p + 1] - vhy) * ey);
    }
    const PetscReal fx = mag * ex, fy = mag * ey;
    f[2 * p] += fx;
    f[2 * p + 1] += fy;
    f[2 * i1] -= (1 - t) * fx;
    f[2 * i1 + 1] -= (1 - t) * fy;
    f[2 * i2] -= t * fx;
    f[2 * i2 + 1] -= t * fy;
    if (VIRIAL) { /* -(F x_p - (1-t) F x1 - t F x2) = -F (x) d */
      w[0] -= fx * dx;
      w[1] -= fx * dy;
      w[2] -= fy * dx;
      w[3] -= fy * dy;
    }
  }
  if (VIRIAL)
    for (int k = 0; k < 4; k++) virial[k] += w[k];
  PetscCall(PetscLogFlops(14.0 * P.springs.size() + 24.0 * L.size() + 50.0 * active));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Repulsion::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  if (virial) PetscCall(Kernel<true>(in, f, virial));
  else PetscCall(Kernel<false>(in, f, NULL));
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
    if (r >= cutoff) continue;
    *E += strength * (1.0 / (5.0 * std::pow(r, 5)) + r / x06 - 6.0 / (5.0 * x05));
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
    if (r >= cutoff || r <= 0) continue;
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "repulsion: lambda = %g µN µm^6, x0 = %g µm, angle factor %s, damping %s, each straight wall pushes once\n",
                                   (double)strength, (double)cutoff, angle_factor ? "on" : "off",
                                   damping ? (damping_taper ? "on, tapered to 0 at x0" : "on, literal") : "off"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
