#include <turgor/physics/sph_fluid.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode SPHFluid::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "sph_", "SPH cell fluid (TW 562 eqs 2-15)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-smoothing_length", "Smoothing length h [µm] (support 2h)", "SPHFluid", smoothing_length, &smoothing_length, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-sound_speed", "Speed of sound c_s in p = c_s^2 rho [µm/µs = m/s]", "SPHFluid", sound_speed, &sound_speed, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-viscosity", "2D dynamic viscosity mu x thickness [ng/µs]; 0 skips the viscous passes", "SPHFluid", viscosity,
                              &viscosity, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-correction", "Bonet-Lok corrected kernel gradient in the velocity gradient (eqs 13-15)", "SPHFluid", correction,
                              &correction, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-correction_guard",
                              "Correction fades out where lambda_min/lambda_max of its inverse falls below 2 guard (zero below guard)", "SPHFluid", guard,
                              &guard, NULL));
  PetscOptionsEnd();
  PetscCheck(smoothing_length > 0 && std::isfinite(smoothing_length), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -sph_smoothing_length = %g: must be finite and > 0", (double)smoothing_length);
  PetscCheck(sound_speed >= 0 && std::isfinite(sound_speed), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -sph_sound_speed = %g: must be finite and >= 0",
             (double)sound_speed);
  PetscCheck(viscosity >= 0 && std::isfinite(viscosity), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -sph_viscosity = %g: must be finite and >= 0",
             (double)viscosity);
  PetscCheck(guard > 0 && guard <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -sph_correction_guard = %g: must be in (0, 1]", (double)guard);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFluid::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  const PetscReal h = smoothing_length;
  norm_             = 10.0 / (7.0 * PETSC_PI * h * h);
  W0_               = norm_;
  slot_.assign(P.n, -1);
  const PetscInt nf = P.Count(KIND_FLUID);
  fluid_.assign(nf, 0);
  for (PetscInt i = 0, s = 0; i < P.NumOwned(); i++)
    if (P.kind[i] == KIND_FLUID) {
      fluid_[s] = i;
      slot_[i]  = s++;
    }
  for (PetscInt i = P.NumOwned(); i < P.n; i++) /* the pairs' j must have a slot */
    PetscCheck(P.kind[i] != KIND_FLUID, PETSC_COMM_SELF, PETSC_ERR_PLIB, "SPH: halo particle %" PetscInt_FMT " is fluid (a cell's fluid is its owner's)", i);
  vol_.assign(nf, 0);
  P_.assign(nf, 0);
  { /* the groups: runs of one cell's slots, if no cell has two runs */
    std::vector<PetscInt> run_cell;
    group_start_.assign(1, 0);
    for (PetscInt s = 1; s <= nf; s++)
      if (s == nf || P.cell[fluid_[s]] != P.cell[fluid_[s - 1]]) group_start_.push_back(s), run_cell.push_back(P.cell[fluid_[s - 1]]);
    std::sort(run_cell.begin(), run_cell.end());
    const bool split = std::adjacent_find(run_cell.begin(), run_cell.end()) != run_cell.end() || (!run_cell.empty() && run_cell.front() < 0);
    if (split) group_start_ = {0, nf};
    PetscInt g = 0;
    for (size_t k = 0; k + 1 < group_start_.size(); k++) g = std::max(g, group_start_[k + 1] - group_start_[k]);
    M_.assign(3 * g, 0);
    GA_.assign(4 * g, 0);
  }
  pair_start_.assign(nf + 1, 0);
  pair_j_.clear();
  pair_F_.clear();
  nb.RequestFluidPairs(2.0 * h);
  PetscCall(PetscLogEventRegister("TgSPHDensity", PETSC_OBJECT_CLASSID, &ev_density_));
  PetscCall(PetscLogEventRegister("TgSPHGradient", PETSC_OBJECT_CLASSID, &ev_gradient_));
  PetscCall(PetscLogEventRegister("TgSPHForce", PETSC_OBJECT_CLASSID, &ev_force_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal SPHFluid::Kernel(PetscReal r) const
{
  const PetscReal s = r / smoothing_length;
  if (s < 1) return norm_ * (1 - 1.5 * s * s + 0.75 * s * s * s);
  if (s < 2) return norm_ * 0.25 * (2 - s) * (2 - s) * (2 - s);
  return 0;
}

PetscReal SPHFluid::KernelDerivative(PetscReal r) const
{
  const PetscReal s = r / smoothing_length, c = norm_ / smoothing_length;
  if (s < 1) return c * (-3 * s + 2.25 * s * s);
  if (s < 2) return -c * 0.75 * (2 - s) * (2 - s);
  return 0;
}

/* Pass 1: rho_i = m_i W(0) + sum_j m_j W_ij, and the pairs within 2h with F = W'/r cached for the
   later passes (the neighbour list carries a skin, so some listed pairs are out). The density
   accumulates in vol_, which then becomes m / rho; each(s, rho) sees every slot's density first
   (energy, time-step limit, output: no density array kept). */
template <class Each>
PetscErrorCode SPHFluid::DensityPass(const ForceInput &in, Each each)
{
  const PetscReal *x = in.x, *m = in.P->mass.data();
  const PairList  &L  = in.nb->FluidPairs();
  const PetscInt   nf = (PetscInt)fluid_.size();
  const PetscReal  h = smoothing_length, ih = 1.0 / h, r2max = 4 * h * h, c = norm_, cd = norm_ * ih;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_density_, 0, 0, 0, 0));
  PetscReal *rho = vol_.data();
  for (PetscInt s = 0; s < nf; s++) rho[s] = m[fluid_[s]] * W0_;
  pair_j_.resize(L.size());
  pair_F_.resize(L.size());
  PetscInt na = 0, row = 0;
  /* the list's rows are by i (so by slot): row i accumulates in a register */
  for (PetscInt i = 0; i < L.Rows(); i++) {
    if (L.start[i] == L.start[i + 1]) continue;
    const PetscInt  si = slot_[i];
    const PetscReal xi = x[2 * i], yi = x[2 * i + 1], mi = m[i];
    PetscReal       rho_i = 0;
    while (row <= si) pair_start_[row++] = na;
    for (PetscInt q = L.start[i]; q < L.start[i + 1]; q++) {
      const PetscInt  j  = L.j[q];
      const PetscReal ex = xi - x[2 * j], ey = yi - x[2 * j + 1], r2 = ex * ex + ey * ey;
      if (r2 >= r2max) continue;
      const PetscReal r = std::sqrt(r2), s = r * ih;
      PetscReal       W, dW;
      if (s < 1) {
        W  = c * (1 - 1.5 * s * s + 0.75 * s * s * s);
        dW = cd * (-3 * s + 2.25 * s * s);
      } else {
        const PetscReal t = 2 - s;
        W                 = c * 0.25 * t * t * t;
        dW                = -cd * 0.75 * t * t;
      }
      const PetscInt sj = slot_[j];
      rho_i += m[j] * W;
      rho[sj] += mi * W;
      pair_j_[na]   = sj;
      pair_F_[na++] = r > 0 ? dW / r : 0;
    }
    rho[si] += rho_i;
  }
  while (row <= nf) pair_start_[row++] = na;
  pair_j_.resize(na);
  pair_F_.resize(na);
  for (PetscInt s = 0; s < nf; s++) {
    const PetscReal r = rho[s];
    each(s, r);
    P_[s]   = sound_speed * sound_speed / r; /* p / rho^2 with p = c_s^2 rho */
    vol_[s] = m[fluid_[s]] / r;
  }
  PetscCall(PetscLogFlops(30.0 * L.size()));
  PetscCall(PetscLogEventEnd(ev_density_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Guarded inverse of the symmetric positive semi-definite 2x2 matrix M = [a b; b c] (eq 14).
   A particle whose neighbours are (nearly) collinear, or that has at most one neighbour, has no
   well-defined 2D velocity gradient: M is singular. We then fade the correction out with a scalar
   weight, L = w M^{-1}, w = 1 for lambda_min/lambda_max >= 2 guard, w = 0 below guard, smooth in
   between. A scalar weight keeps L M = w I, so tau L M stays symmetric and the viscous forces remain
   exactly torque-free (angular momentum) in every configuration, while L stays bounded; a
   regularised inverse (raising lambda_min) would break L M = I and with it angular momentum. */
static inline void GuardedInverse(PetscReal a, PetscReal b, PetscReal c, PetscReal guard, PetscReal L[3])
{
  const PetscReal mean = 0.5 * (a + c), dev = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const PetscReal lmax = mean + dev, ratio = lmax > 0 ? (mean - dev) / lmax : 0;
  PetscReal       w = 1;
  if (ratio <= guard) w = 0;
  else if (ratio < 2 * guard) {
    const PetscReal s = (ratio - guard) / guard;
    w                 = s * s * (3 - 2 * s);
  }
  if (w == 0) {
    L[0] = L[1] = L[2] = 0;
    return;
  }
  const PetscReal wdet = w / (a * c - b * b);
  L[0]                 = c * wdet;
  L[1]                 = -b * wdet;
  L[2]                 = a * wdet;
}

/* Pass 2: M_i = sum_j V_j (-W'/r) e (x) e (the inverse of L_i, eq 14) and
   G_i = sum_j V_j (v_j - v_i) (x) grad_i W_ij; then grad v_i = G_i L_i (into gradv[4 n] when asked),
   tau_i, and A_i = tau_i L_i, which replaces G_i. */
PetscErrorCode SPHFluid::GradientPass(const ForceInput &in, PetscInt s0, PetscInt s1, PetscReal *gradv)
{
  const PetscReal *x = in.x, *v = in.v;
  const PetscInt  *fl = fluid_.data(), *start = pair_start_.data(), *pj = pair_j_.data();
  const PetscReal *pF = pair_F_.data(), *vol = vol_.data();
  PetscReal       *M = M_.data(), *G = GA_.data(); /* by slot - s0 */

  PetscFunctionBeginUser;
  std::fill(M_.begin(), M_.begin() + 3 * (s1 - s0), 0);
  std::fill(GA_.begin(), GA_.begin() + 4 * (s1 - s0), 0);
  /* rows by slot: accumulate row i in registers, scatter only to j */
  for (PetscInt si = s0; si < s1; si++) {
    if (start[si] == start[si + 1]) continue;
    const PetscInt  i  = fl[si];
    const PetscReal Vi = vol[si], xi = x[2 * i], yi = x[2 * i + 1], vxi = v[2 * i], vyi = v[2 * i + 1];
    PetscReal       Mi[3] = {0, 0, 0}, Gi[4] = {0, 0, 0, 0};
    for (PetscInt q = start[si]; q < start[si + 1]; q++) {
      const PetscInt  sj = pj[q], j = fl[sj];
      const PetscReal Vj = vol[sj], F = pF[q];
      const PetscReal ex = xi - x[2 * j], ey = yi - x[2 * j + 1];
      const PetscReal gx = ex * F, gy = ey * F;
      const PetscReal sxx = -gx * ex, sxy = -gx * ey, syy = -gy * ey;
      const PetscReal dvx = v[2 * j] - vxi, dvy = v[2 * j + 1] - vyi;
      const PetscReal t0 = dvx * gx, t1 = dvx * gy, t2 = dvy * gx, t3 = dvy * gy;
      Mi[0] += Vj * sxx;
      Mi[1] += Vj * sxy;
      Mi[2] += Vj * syy;
      Gi[0] += Vj * t0;
      Gi[1] += Vj * t1;
      Gi[2] += Vj * t2;
      Gi[3] += Vj * t3;
      M[3 * (sj - s0)] += Vi * sxx;
      M[3 * (sj - s0) + 1] += Vi * sxy;
      M[3 * (sj - s0) + 2] += Vi * syy;
      G[4 * (sj - s0)] += Vi * t0;
      G[4 * (sj - s0) + 1] += Vi * t1;
      G[4 * (sj - s0) + 2] += Vi * t2;
      G[4 * (sj - s0) + 3] += Vi * t3;
    }
    for (int k = 0; k < 3; k++) M[3 * (si - s0) + k] += Mi[k];
    for (int k = 0; k < 4; k++) G[4 * (si - s0) + k] += Gi[k];
  }
  const PetscReal mu = viscosity;
  for (PetscInt s = s0; s < s1; s++) {
    PetscReal L[3] = {1, 0, 1};
    if (correction) GuardedInverse(M[3 * (s - s0)], M[3 * (s - s0) + 1], M[3 * (s - s0) + 2], guard, L);
    PetscReal *g = &G[4 * (s - s0)];
    /* grad v = G L (L symmetric) */
    const PetscReal gv0 = g[0] * L[0] + g[1] * L[1], gv1 = g[0] * L[1] + g[1] * L[2];
    const PetscReal gv2 = g[2] * L[0] + g[3] * L[1], gv3 = g[2] * L[1] + g[3] * L[2];
    if (gradv) {
      PetscReal *gr = &gradv[4 * fl[s]];
      gr[0] = gv0, gr[1] = gv1, gr[2] = gv2, gr[3] = gv3;
    }
    const PetscReal dxy = 0.5 * (gv1 + gv2), tr = gv0 + gv3;
    /* tau = mu (2 d - 2/3 tr(d) I): the seed's 3D deviator, i.e. plane strain (d_zz = 0) */
    const PetscReal txx = mu * (2 * gv0 - (2.0 / 3.0) * tr), tyy = mu * (2 * gv3 - (2.0 / 3.0) * tr), txy = mu * 2 * dxy;
    g[0] = txx * L[0] + txy * L[1]; /* A = tau L replaces G */
    g[1] = txx * L[1] + txy * L[2];
    g[2] = txy * L[0] + tyy * L[1];
    g[3] = txy * L[1] + tyy * L[2];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

template <bool VIRIAL, bool ROUND>
PetscErrorCode SPHFluid::ForcePass(const ForceInput &in, PetscInt s0, PetscInt s1, PetscReal *f, PetscReal w[4])
{
  const PetscReal  *x = in.x, *m = in.P->mass.data(), *A = GA_.data() /* by slot - s0 */, *Pp = P_.data(), *vol = vol_.data(), *pF = pair_F_.data();
  const PetscInt   *fl = fluid_.data(), *start = pair_start_.data(), *pj = pair_j_.data();
  const bool        visc  = viscosity > 0;
  const ForceGrain &grain = in.Grain();

  PetscFunctionBeginUser;
  for (PetscInt si = s0; si < s1; si++) {
    if (start[si] == start[si + 1]) continue;
    const PetscInt  i  = fl[si];
    const PetscReal mi = m[i], Pi = Pp[si], Vi = vol[si], xi = x[2 * i], yi = x[2 * i + 1];
    const PetscReal A0 = A[4 * (si - s0)], A1 = A[4 * (si - s0) + 1], A2 = A[4 * (si - s0) + 2], A3 = A[4 * (si - s0) + 3];
    PetscReal       fxi = 0, fyi = 0;
    for (PetscInt q = start[si]; q < start[si + 1]; q++) {
      const PetscInt  sj = pj[q], j = fl[sj];
      const PetscReal ex = xi - x[2 * j], ey = yi - x[2 * j + 1];
      const PetscReal gx = ex * pF[q], gy = ey * pF[q];
      const PetscReal pp = -mi * m[j] * (Pi + Pp[sj]);
      PetscReal       fx = pp * gx, fy = pp * gy;
      if (visc) {
        const PetscReal vv = Vi * vol[sj];
        fx += vv * ((A0 + A[4 * (sj - s0)]) * gx + (A1 + A[4 * (sj - s0) + 1]) * gy);
        fy += vv * ((A2 + A[4 * (sj - s0) + 2]) * gx + (A3 + A[4 * (sj - s0) + 3]) * gy);
      }
      if (ROUND) grain(fx, fy); /* a template argument: no test per pair without */
      fxi += fx;
      fyi += fy;
      f[2 * j] -= fx;
      f[2 * j + 1] -= fy;
      if (VIRIAL) { /* -(f_ij (x) x_i - f_ij (x) x_j) = -f_ij (x) e */
        w[0] -= fx * ex;
        w[1] -= fx * ey;
        w[2] -= fy * ex;
        w[3] -= fy * ey;
      }
    }
    f[2 * i] += fxi;
    f[2 * i + 1] += fyi;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFluid::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const bool visc = viscosity > 0, rounded = in.Grain().On();
  PetscReal  w[4] = {0, 0, 0, 0};
  PetscFunctionBeginUser;
  if (fluid_.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DensityPass(in, [](PetscInt, PetscReal) {}));
  /* a group at a time: its gradients (A), then its forces (the events time the two together) */
  PetscCall(PetscLogEventBegin(ev_force_, 0, 0, 0, 0));
  for (size_t k = 0; k + 1 < group_start_.size(); k++) {
    const PetscInt s0 = group_start_[k], s1 = group_start_[k + 1];
    if (visc) PetscCall(GradientPass(in, s0, s1, NULL));
    if (virial) PetscCall(rounded ? ForcePass<true, true>(in, s0, s1, f, w) : ForcePass<true, false>(in, s0, s1, f, w));
    else PetscCall(rounded ? ForcePass<false, true>(in, s0, s1, f, w) : ForcePass<false, false>(in, s0, s1, f, w));
  }
  if (virial)
    for (int k = 0; k < 4; k++) virial[k] += w[k];
  PetscCall(PetscLogFlops((visc ? 70.0 : 12.0) * pair_j_.size() + (visc ? 40.0 * fluid_.size() : 0)));
  PetscCall(PetscLogEventEnd(ev_force_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFluid::DensityAndVelocityGradient(const ForceInput &in, std::vector<PetscReal> &rho, std::vector<PetscReal> &gradv)
{
  PetscFunctionBeginUser;
  rho.assign(in.P->n, 0);
  PetscCall(DensityPass(in, [&](PetscInt s, PetscReal r) { rho[fluid_[s]] = r; }));
  gradv.assign(4 * in.P->n, 0);
  PetscCall(PetscLogEventBegin(ev_gradient_, 0, 0, 0, 0));
  for (size_t k = 0; k + 1 < group_start_.size(); k++) PetscCall(GradientPass(in, group_start_[k], group_start_[k + 1], gradv.data()));
  PetscCall(PetscLogEventEnd(ev_gradient_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFluid::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  *E = 0;
  PetscCall(DensityPass(in, [&](PetscInt s, PetscReal r) { *E += in.P->mass[fluid_[s]] * sound_speed * sound_speed * std::log(r); }));
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TW 562 eq 40: dt <= 0.25 h / c_s, dt <= 0.125 h^2 / nu, nu = mu / rho (smallest density), and
   dt <= 0.25 sqrt(h / |a|_max). */
PetscErrorCode SPHFluid::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  const PetscReal h = smoothing_length;
  char            why[256];
  PetscFunctionBeginUser;
  if (in.a_max > 0) limits.push_back({0.25 * std::sqrt(h / in.a_max), "largest acceleration: 0.25 sqrt(h / |a|) (eq 40)"}); /* with all terms' forces */
  if (fluid_.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  if (sound_speed > 0) {
    PetscCall(PetscSNPrintf(why, sizeof why, "sound speed: 0.25 h / c_s (eq 40), c_s = %g µm/µs", (double)sound_speed));
    limits.push_back({0.25 * h / sound_speed, why});
  }
  if (viscosity > 0) {
    PetscReal rmin = PETSC_MAX_REAL;
    PetscCall(DensityPass(in, [&](PetscInt, PetscReal r) { rmin = PetscMin(rmin, r); }));
    const PetscReal nu = viscosity / rmin;
    PetscCall(PetscSNPrintf(why, sizeof why, "viscosity: 0.125 h^2 / nu (eq 40), nu = %.3g µm^2/µs", (double)nu));
    limits.push_back({0.125 * h * h / nu, why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SPHFluid::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "sph: h = %g µm, c_s = %g µm/µs, mu = %g ng/µs, Bonet-Lok correction %s (guard %g), %zu fluid particles\n",
                                   (double)smoothing_length, (double)sound_speed, (double)viscosity, correction ? "on" : "off", (double)guard, fluid_.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
