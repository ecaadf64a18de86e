#include <turgor/physics/hinges.h>
#include <turgor/physics/hinge_moments.h>
#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace turgor {

PetscErrorCode Hinges::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "hinge_", "Bending hinges at polygon nodes (elastic-perfectly plastic)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-stiffness", "Rotational stiffness k_r [µN µm/rad]", "Hinges", stiffness, &stiffness, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-max_moment", "Plastic moment M_max [µN µm]; 0 = elastic", "Hinges", max_moment, &max_moment, NULL));
  PetscOptionsEnd();
  PetscCheck(stiffness >= 0 && std::isfinite(stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -hinge_stiffness = %g: must be finite and >= 0",
             (double)stiffness);
  PetscCheck(max_moment >= 0 && std::isfinite(max_moment), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -hinge_max_moment = %g: must be finite and >= 0 (0 = elastic)", (double)max_moment);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Hinges::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  a_.clear(), b_.clear(), c_.clear();
  runs_.clear();
  for (size_t q = 0; q < P.OwnedPolygons(); q++) { /* one run of consecutive hinges per polygon (this rank's) */
    const PolygonCell &c = P.polygons[q];
    const PetscInt     N = (PetscInt)c.nodes.size(), first = (PetscInt)NumHinges();
    if (c.open)
      for (PetscInt k = 1; k + 1 < N; k++) AddHinge(c.nodes[k - 1], c.nodes[k], c.nodes[k + 1]);
    else if (N >= 3)
      for (PetscInt k = 0; k < N; k++) AddHinge(c.nodes[(k + N - 1) % N], c.nodes[k], c.nodes[(k + 1) % N]);
    if ((PetscInt)NumHinges() > first) runs_.push_back({first, (PetscInt)NumHinges() - first, !c.open});
  }
  contiguous_ = NumHinges() > 0; /* the hinges' nodes consecutive (every node of a tissue of closed cells numbered cell by cell, a chain) */
  for (size_t h = 1; h < NumHinges(); h++) contiguous_ = contiguous_ && b_[h] == b_[0] + (PetscInt)h;
  interior_.assign(NumHinges(), ~(std::uint64_t)0); /* neither the first nor the last hinge of its polygon */
  for (const Run &R : runs_) interior_[R.first] = interior_[R.first + R.count - 1] = 0;
  have_angles_ = false;
  cos0_.assign(NumHinges(), 1.0);
  sin0_.assign(NumHinges(), 0.0);
  theta_p_.assign(NumHinges(), 0.0);
  dissipated_ = 0;
  have_ref_   = false;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Hinges::SetReference(const PetscReal *X)
{
  for (size_t h = 0; h < NumHinges(); h++) {
    const Hinge     H  = HingeAt(h);
    const PetscReal ux = X[2 * H.a] - X[2 * H.b], uy = X[2 * H.a + 1] - X[2 * H.b + 1];
    const PetscReal wx = X[2 * H.c] - X[2 * H.b], wy = X[2 * H.c + 1] - X[2 * H.b + 1];
    const PetscReal th = std::atan2(ux * wy - uy * wx, ux * wx + uy * wy);
    cos0_[h]           = std::cos(th);
    sin0_[h]           = std::sin(th);
  }
  have_ref_ = true;
}

/* theta - theta0 in (-pi, pi]: the current angle rotated back by the reference one, so that a single
   atan2 gives the difference without wrapping. */
PetscReal Hinges::Angle(size_t h, const PetscReal *x) const
{
  const Hinge     H  = HingeAt(h);
  const PetscReal ux = x[2 * H.a] - x[2 * H.b], uy = x[2 * H.a + 1] - x[2 * H.b + 1];
  const PetscReal wx = x[2 * H.c] - x[2 * H.b], wy = x[2 * H.c + 1] - x[2 * H.b + 1];
  const HingeBend B = HingeBendOf(ux, uy, wx, wy, cos0_[h], sin0_[h]);
  return HingeAtan2(B.Y, B.X);
}

/* E = -M dtheta/dx: dtheta/dx_c = perp(w)/|w|^2, dtheta/dx_a = -perp(u)/|u|^2 (perp(v) = (-v_y, v_x)),
   dtheta/dx_b = -(both): forces M/l perpendicular to each bar, summing to zero with zero torque.
   Hinges are visited along each polygon, so that a bar's vector and 1/|bar|^2 serve the two hinges
   at its ends: u of hinge k is minus the w of hinge k - 1. One division per hinge gives both 1/|w|^2
   and the tangent of the angle deviation (q = 1 / (X |w|^2)). */
template <bool VIRIAL, bool CACHE, bool ROUND>
void Hinges::Kernel(const PetscReal *x, const ForceGrain &grain, PetscReal *f, PetscReal *virial)
{
  const PetscReal k = stiffness, Mmax = max_moment > 0 ? max_moment : PETSC_MAX_REAL;
  PetscReal       w4[4] = {0, 0, 0, 0};
  for (const Run &R : runs_) {
    /* the bar into the first hinge: u = x_a - x_b of hinge R.first */
    const Hinge H0 = HingeAt(R.first);
    PetscReal   ux = x[2 * H0.a] - x[2 * H0.b], uy = x[2 * H0.a + 1] - x[2 * H0.b + 1], iu2 = 1 / (ux * ux + uy * uy);
    /* A hinge node's force comes from three hinges (its own, and as the far node of the two next to
       it): it is summed in registers and written once, after the next hinge (pb: own + previous
       hinge's share, cc: this hinge's share for the next hinge node, fa0: the first hinge's share
       for its previous node, added at the end of a closed ring). */
    PetscReal pbx = 0, pby = 0, ccx = 0, ccy = 0, fa0x = 0, fa0y = 0;
    for (PetscInt h = R.first; h < R.first + R.count; h++) {
      const Hinge     H  = HingeAt(h);
      const PetscReal wx = x[2 * H.c] - x[2 * H.b], wy = x[2 * H.c + 1] - x[2 * H.b + 1];
      const HingeBend B = HingeBendOf(ux, uy, wx, wy, cos0_[h], sin0_[h]);
      PetscReal       d, iw2;
      if (HingeSeriesHolds(B)) HingeSeries(B, &d, &iw2); /* the usual case: the series, sharing its division */
      else HingeGeneral(B, &d, &iw2);
      if (CACHE) d_[h] = d;
      const PetscReal M  = HingeMoment(k, d, theta_p_[h], Mmax);
      const PetscReal iu = M * iu2, iw = M * iw2;
      PetscReal       fax = -uy * iu, fay = ux * iu; /* -M dtheta/dx_a */
      PetscReal       fcx = wy * iw, fcy = -wx * iw; /* -M dtheta/dx_c */
      if (ROUND) grain(fax, fay), grain(fcx, fcy);   /* a template argument: no test per hinge without */
      if (h == R.first) {
        if (R.closed) fa0x = fax, fa0y = fay;
        else f[2 * H.a] += fax, f[2 * H.a + 1] += fay;
      } else { /* the previous hinge node is this hinge's node a */
        f[2 * H.a] += pbx + fax;
        f[2 * H.a + 1] += pby + fay;
      }
      pbx = ccx - fax - fcx, pby = ccy - fay - fcy;
      ccx = fcx, ccy = fcy;
      if (VIRIAL) { /* -sum f (x) x = -(f_a (x) u + f_c (x) w) relative to the hinge node */
        w4[0] -= fax * ux + fcx * wx;
        w4[1] -= fax * uy + fcx * wy;
        w4[2] -= fay * ux + fcy * wx;
        w4[3] -= fay * uy + fcy * wy;
      }
      ux = -wx, uy = -wy, iu2 = iw2; /* the next hinge's u: this bar seen from its other end */
    }
    const Hinge HL = HingeAt(R.first + R.count - 1);
    f[2 * HL.b] += pbx + fa0x; /* fa0 = 0 on an open chain */
    f[2 * HL.b + 1] += pby + fa0y;
    f[2 * HL.c] += ccx; /* closed: the first hinge node; open: the chain's last node */
    f[2 * HL.c + 1] += ccy;
  }
  if (VIRIAL)
    for (int q = 0; q < 4; q++) virial[q] += w4[q];
}

/* Kernel<false, *, false> in passes that vectorise: every hinge's bars (w read from x in order where
   the hinges' nodes are consecutive; u the previous hinge's w reversed, as in Kernel; a polygon's
   closing bar and first u set one by one), every hinge's bend and moment (HingeSeriesMoments; the few
   where the series does not hold redone), its two end forces (iu2 the previous hinge's 1/|w|^2, as in
   Kernel), then the forces summed into the nodes along each polygon in Kernel's order: the same bits.
   The passes run over blocks of whole polygons of about block_hinges_ hinges, so that their eleven
   values a hinge stay in the cache between passes (a tissue of 160 000 nodes streamed 14 MB through
   each); a node's forces come from its own polygon only, so the blocks change no sum. */
void Hinges::VectorKernel(const PetscReal *x, PetscReal *f)
{
  const size_t n = NumHinges();
  if (n == 0) return; /* a rank without polygons */
  d_.resize(n);
  general_.resize(n);
  size_t r0 = 0;
  while (r0 < runs_.size()) {
    size_t r1 = r0 + 1, m = (size_t)runs_[r0].count;
    while (r1 < runs_.size() && m + (size_t)runs_[r1].count <= block_hinges_) m += (size_t)runs_[r1++].count;
    VectorBlock(x, f, r0, r1);
    r0 = r1;
  }
}

/* VectorKernel on the polygons runs_[r0, r1): hinges h0 = runs_[r0].first on, m of them */
void Hinges::VectorBlock(const PetscReal *x, PetscReal *f, size_t r0, size_t r1)
{
  const PetscInt  h0 = runs_[r0].first, m = runs_[r1 - 1].first + runs_[r1 - 1].count - h0;
  const PetscReal k = stiffness, Mmax = max_moment > 0 ? max_moment : PETSC_MAX_REAL;
  if ((PetscInt)scratch_.size() < 11 * m) scratch_.resize(11 * m);
  /* S and the force arrays by the block's hinge (h - h0); a_, b_, c_ and the per-hinge data by hinge */
  PetscReal       *v = scratch_.data(), *fax = v + 7 * m, *fay = v + 8 * m, *fcx = v + 9 * m, *fcy = v + 10 * m;
  HingeScratch     S{v, v + m, v + 2 * m, v + 3 * m, d_.data() + h0, v + 4 * m, v + 5 * m, v + 6 * m};
  const PetscReal *cos0 = cos0_.data() + h0, *sin0 = sin0_.data() + h0, *theta_p = theta_p_.data() + h0;
  HingeNextBars(m, b_.data() + h0, c_.data() + h0, contiguous_, x, S);
  HingePreviousBars(m, S);
  for (size_t r = r0; r < r1; r++) { /* a polygon's last hinge's w (the ring's closing bar), its first's u: by index */
    const Run     &R = runs_[r];
    const PetscInt l = R.first + R.count - 1, q = R.first;
    S.wx[l - h0] = x[2 * c_[l]] - x[2 * b_[l]], S.wy[l - h0] = x[2 * c_[l] + 1] - x[2 * b_[l] + 1];
    S.ux[q - h0] = x[2 * a_[q]] - x[2 * b_[q]], S.uy[q - h0] = x[2 * a_[q] + 1] - x[2 * b_[q] + 1];
  }
  HingeSeriesMoments(m, cos0, sin0, theta_p, k, Mmax, S);
  HingeGeneralMoments(m, cos0, sin0, theta_p, k, Mmax, S, general_.data(), fax); /* fax.. fcx: free until HingeEndForces */
  HingeEndForces(m, S, fax, fay, fcx, fcy);
  for (size_t r = r0; r < r1; r++) { /* a polygon's first hinge: 1/|u|^2 of its own */
    const PetscInt  h  = runs_[r].first - h0;
    const PetscReal iu = S.M[h] * (1 / (S.ux[h] * S.ux[h] + S.uy[h] * S.uy[h])), iw = S.M[h] * S.iw2[h];
    fax[h] = -S.uy[h] * iu, fay[h] = S.ux[h] * iu;
    fcx[h] = S.wy[h] * iw, fcy[h] = -S.wx[h] * iw;
  }
  if (contiguous_) { /* node b_h = b_0 + h: the interior hinges' nodes in order, in a loop that vectorises */
    HingeInteriorNodeForces(m, interior_.data() + h0, fax, fay, fcx, fcy, f + 2 * b_[h0]);
    for (size_t r = r0; r < r1; r++) { /* the ends of each polygon, as Kernel sums them there */
      const Run     &R  = runs_[r];
      const PetscInt g0 = R.first - h0, gL = g0 + R.count - 1; /* the block's indices of its first and last hinge */
      const PetscInt a = a_[R.first], b0 = b_[R.first], bL = b_[R.first + R.count - 1], c = c_[R.first + R.count - 1];
      if (!R.closed) f[2 * a] += fax[g0], f[2 * a + 1] += fay[g0];
      if (gL > g0) { /* the first hinge's node, with the next hinge's share */
        f[2 * b0] += (PetscReal)0 - fax[g0] - fcx[g0] + fax[g0 + 1];
        f[2 * b0 + 1] += (PetscReal)0 - fay[g0] - fcy[g0] + fay[g0 + 1];
      }
      const PetscReal ccx = gL > g0 ? fcx[gL - 1] : 0, ccy = gL > g0 ? fcy[gL - 1] : 0;
      f[2 * bL] += ccx - fax[gL] - fcx[gL] + (R.closed ? fax[g0] : 0);
      f[2 * bL + 1] += ccy - fay[gL] - fcy[gL] + (R.closed ? fay[g0] : 0);
      f[2 * c] += fcx[gL];
      f[2 * c + 1] += fcy[gL];
    }
    return;
  }
  for (size_t r = r0; r < r1; r++) { /* as in Kernel: pb, cc, fa0 */
    const Run     &R  = runs_[r];
    const PetscInt g0 = R.first - h0, g1 = g0 + R.count;
    PetscReal      pbx = (PetscReal)0 - fax[g0] - fcx[g0], pby = (PetscReal)0 - fay[g0] - fcy[g0], ccx = fcx[g0],
              ccy = fcy[g0]; /* 0 - fa: Kernel's bits, -0 included */
    if (!R.closed) f[2 * a_[R.first]] += fax[g0], f[2 * a_[R.first] + 1] += fay[g0];
    for (PetscInt g = g0 + 1; g < g1; g++) {
      const PetscInt a = a_[h0 + g];
      f[2 * a] += pbx + fax[g];
      f[2 * a + 1] += pby + fay[g];
      pbx = ccx - fax[g] - fcx[g], pby = ccy - fay[g] - fcy[g];
      ccx = fcx[g], ccy = fcy[g];
    }
    const PetscInt b = b_[h0 + g1 - 1], c = c_[h0 + g1 - 1];
    f[2 * b] += pbx + (R.closed ? fax[g0] : 0);
    f[2 * b + 1] += pby + (R.closed ? fay[g0] : 0);
    f[2 * c] += ccx;
    f[2 * c + 1] += ccy;
  }
}

PetscErrorCode Hinges::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  const bool cache = max_moment > 0; /* AcceptStep at the state of the last evaluation reuses its angles */
  if (cache) d_.resize(NumHinges());
  using KernelOf                            = void (Hinges::*)(const PetscReal *, const ForceGrain &, PetscReal *, PetscReal *);
  static constexpr KernelOf kernel[2][2][2] = {
  /* [virial][cache][rounded] */
    {{&Hinges::Kernel<false, false, false>, &Hinges::Kernel<false, false, true>}, {&Hinges::Kernel<false, true, false>, &Hinges::Kernel<false, true, true>}},
    {{&Hinges::Kernel<true, false, false>, &Hinges::Kernel<true, false, true>},   {&Hinges::Kernel<true, true, false>, &Hinges::Kernel<true, true, true>}  }
  };
  /* the virial's sums and the grain's rounding stay in the one-pass kernel */
  if (!virial && !in.Grain().On()) VectorKernel(in.x, f);
  else (this->*kernel[virial != nullptr][cache][in.Grain().On()])(in.x, in.Grain(), f, virial);
  have_angles_ = cache;
  PetscCall(PetscLogFlops(45.0 * NumHinges()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The potential of AddForces at the committed theta_p: k/2 e^2 for |e| <= e_max = M_max/k, and
   continued linearly (slope M_max) beyond, so that the capped force is still -dE/dx. */
PetscErrorCode Hinges::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  *E                 = 0;
  const PetscReal em = max_moment > 0 && stiffness > 0 ? max_moment / stiffness : PETSC_MAX_REAL;
  for (size_t h = 0; h < NumHinges(); h++) {
    const PetscReal e = std::fabs(Angle(h, in.x) - theta_p_[h]);
    *E += e <= em ? 0.5 * stiffness * e * e : max_moment * (e - em) + 0.5 * stiffness * em * em;
  }
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Return mapping at the accepted state: a trial moment beyond M_max moves theta_p by the excess
   rotation, so that the moment is exactly M_max, and dissipates M_max |d theta_p|. */
PetscErrorCode Hinges::AcceptStep(const ForceInput &in)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  /* velocity Verlet accepts the state it last evaluated: the angles are then those of AddForces
     (same bits in, same bits out), computed once */
  const bool same = in.same_x && have_angles_ && d_.size() == NumHinges();
  if (max_moment > 0 && stiffness > 0)
    for (size_t h = 0; h < NumHinges(); h++) {
      const PetscReal e = (same ? d_[h] : Angle(h, in.x)) - theta_p_[h], em = max_moment / stiffness;
      if (std::fabs(e) > em) {
        const PetscReal dp = e > 0 ? e - em : e + em;
        theta_p_[h] += dp;
        dissipated_ += max_moment * std::fabs(dp);
      }
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One hinge is the rank-one stiffness k_r g g^T (g = dtheta/dx); its frequency^2 is
   k_r g^T M^-1 g = k_r (1/(m_a l_a^2) + 1/(m_c l_c^2) + |g_b|^2/m_b). A node takes part in at most
   three hinges (its own and its two neighbours'), hence 3 x the largest (Gershgorin-like bound). */
PetscErrorCode Hinges::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  const PetscReal *x  = in.x;
  const auto      &m  = in.P->mass;
  PetscReal        w2 = 0;
  for (size_t h = 0; h < NumHinges(); h++) {
    const Hinge     H  = HingeAt(h);
    const PetscReal ux = x[2 * H.a] - x[2 * H.b], uy = x[2 * H.a + 1] - x[2 * H.b + 1];
    const PetscReal wx = x[2 * H.c] - x[2 * H.b], wy = x[2 * H.c + 1] - x[2 * H.b + 1];
    const PetscReal u2 = ux * ux + uy * uy, ww = wx * wx + wy * wy;
    const PetscReal gbx = uy / u2 - wy / ww, gby = -ux / u2 + wx / ww;
    w2 = std::max(w2, stiffness * (1 / (m[H.a] * u2) + 1 / (m[H.c] * ww) + (gbx * gbx + gby * gby) / m[H.b]));
  }
  if (w2 > 0) {
    char why[160];
    PetscCall(PetscSNPrintf(why, sizeof why, "hinges: omega_max <= %.4g /µs (k_r / (m l^2), 3 hinges per node)", (double)std::sqrt(3 * w2)));
    limits.push_back({2.0 / std::sqrt(3 * w2), why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Hinges::Statistics(std::vector<TermStatistic> &stats) const
{
  if (max_moment <= 0) return;
  PetscReal plastic = 0;
  for (PetscReal tp : theta_p_) plastic += tp != 0;
  stats.push_back({"hinge_plastic_dissipation", dissipated_});
  stats.push_back({"hinge_plastic_hinges", plastic});
}

PetscErrorCode Hinges::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  if (max_moment > 0)
    PetscCall(PetscViewerASCIIPrintf(viewer, "hinges: %zu, k_r = %g µN µm/rad, M_max = %g µN µm\n", NumHinges(), (double)stiffness, (double)max_moment));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "hinges: %zu, k_r = %g µN µm/rad, elastic\n", NumHinges(), (double)stiffness));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A hinge is named by its node: a node is the hinge of at most one polygon. */
void Hinges::DeclareState(const ParticleSet &P, StateDeclaration &d)
{
  d.Scalar("reference_taken", &have_ref_, Combine::Max);
  d.Scalar("plastic_dissipation", &dissipated_, Combine::Sum);
  d.Table("hinges", StateEntity::Particle)
    .Rows([this] { return NumHinges(); }, [this](size_t h) { return b_[h]; })
    .Column("cos0", cos0_)
    .Column("sin0", sin0_)
    .Column("plastic_angle", theta_p_);
}

} // namespace turgor
