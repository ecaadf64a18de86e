#include <turgor/physics/wall_springs.h>
#include <cmath>

namespace turgor {

PetscErrorCode WallSprings::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "wall_", "Wall springs with dashpots (TW 562 eq 16)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-stiffness", "Spring stiffness k_w [µN/µm = N/m]", "WallSprings", stiffness, &stiffness, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-damping_ratio", "Dashpot as a fraction of critical damping 2 sqrt(m k_w)", "WallSprings", damping_ratio,
                              &damping_ratio, NULL));
  PetscOptionsEnd();
  PetscCheck(stiffness >= 0 && std::isfinite(stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -wall_stiffness = %g: a stiffness must be finite and >= 0",
             (double)stiffness);
  PetscCheck(damping_ratio >= 0 && std::isfinite(damping_ratio), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -wall_damping_ratio = %g: must be finite and >= 0",
             (double)damping_ratio);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WallSprings::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  gamma_.resize(P.springs.size());
  for (size_t s = 0; s < P.springs.size(); s++) {
    const Spring &b = P.springs[s];
    PetscCheck(b.rest_length > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Spring %zu (%" PetscInt_FMT ", %" PetscInt_FMT ") has rest length %g: must be > 0", s, b.i, b.j, (double)b.rest_length);
    /* The seed writes gamma_c = 2 sqrt(m_i k_w) with m_i the wall particle mass; for unequal end
       masses we use their mean. */
    const PetscReal m = 0.5 * (P.mass[b.i] + P.mass[b.j]);
    gamma_[s]         = damping_ratio * 2.0 * std::sqrt(m * stiffness);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Force on i: [k (r - l0) + gamma (e . v_ij)] e with e = (x_j - x_i)/r, v_ij = v_j - v_i. The seed's
   eq 16 prints the opposite overall sign (it pushes a stretched spring apart); see docs/model.md. */
namespace {
/* PERIODIC: end j at an image (RVEs); DAMPED: some dashpot (the velocity pass is skipped otherwise);
   ROUND: the shares rounded to the input's grain (a run with reproducible sums: no test per share
   in the others, this loop being most of a chain's step) */
template <bool VIRIAL, bool PERIODIC, bool DAMPED, bool ROUND>
void Kernel(const ForceInput &in, PetscReal k, const PetscReal *gamma_, PetscReal *f, PetscReal *virial, size_t first = 0)
{
  const PetscReal  *x = in.x, *v = in.v;
  const auto       &S     = in.P->springs;
  const ForceGrain &grain = in.Grain();
  PetscReal         w[4]  = {0, 0, 0, 0};
  for (size_t s = first, ns = in.P->OwnedSprings(); s < ns; s++) { /* this rank's springs (particles.h), from `first` */
    const PetscInt i = S[s].i, j = S[s].j;
    PetscReal      dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
    if (PERIODIC) {
      const PetscReal *sx = in.images->x[S[s].image];
      dx += sx[0], dy += sx[1];
    }
    const SpringAxial a  = SpringAxialAt(dx, dy, k, S[s].rest_length);
    const PetscReal   ex = a.ex, ey = a.ey;
    PetscReal         mag = a.mag;
    if (DAMPED) {
      PetscReal dvx = v[2 * j] - v[2 * i], dvy = v[2 * j + 1] - v[2 * i + 1];
      if (PERIODIC) {
        const PetscReal *sv = in.images->v[S[s].image];
        dvx += sv[0], dvy += sv[1];
      }
      const PetscReal md = SpringDashpotAt(a, gamma_[s], dvx, dvy);
      mag += md;
      if (in.f_dashpot) { /* the dashpot's part apart (the energy balance observes) */
        PetscReal *g = in.f_dashpot;
        g[2 * i] += md * ex, g[2 * i + 1] += md * ey;
        g[2 * j] -= md * ex, g[2 * j + 1] -= md * ey;
      }
    }
    PetscReal fx = mag * ex, fy = mag * ey;
    if (ROUND) grain(fx, fy);
    f[2 * i] += fx;
    f[2 * i + 1] += fy;
    f[2 * j] -= fx;
    f[2 * j + 1] -= fy;
    if (VIRIAL) { /* -(f_i x_i + f_j x_j) = f_i (x) (x_j - x_i) */
      w[0] += fx * dx;
      w[1] += fx * dy;
      w[2] += fy * dx;
      w[3] += fy * dy;
    }
  }
  if (VIRIAL)
    for (int c = 0; c < 4; c++) virial[c] += w[c];
}

template <bool VIRIAL, bool PERIODIC, bool DAMPED>
void KernelRounded(const ForceInput &in, PetscReal k, const PetscReal *gamma, PetscReal *f, PetscReal *virial)
{
  if (in.Grain().On()) Kernel<VIRIAL, PERIODIC, DAMPED, true>(in, k, gamma, f, virial);
  else Kernel<VIRIAL, PERIODIC, DAMPED, false>(in, k, gamma, f, virial);
}

template <bool VIRIAL>
void KernelFor(const ForceInput &in, PetscReal k, const std::vector<PetscReal> &gamma, bool damped, PetscReal *f, PetscReal *virial)
{
  if (in.images->periodic)
    damped ? KernelRounded<VIRIAL, true, true>(in, k, gamma.data(), f, virial) : KernelRounded<VIRIAL, true, false>(in, k, gamma.data(), f, virial);
  else damped ? KernelRounded<VIRIAL, false, true>(in, k, gamma.data(), f, virial) : KernelRounded<VIRIAL, false, false>(in, k, gamma.data(), f, virial);
}
} // namespace

void SpringForces(const ForceInput &in, PetscReal k, const std::vector<PetscReal> &gamma, bool damped, PetscReal *f, PetscReal *virial,
                  const SpringOrder *order, std::vector<PetscReal> *scratch)
{
  if (order && order->in_order && order->springs == in.P->OwnedSprings() && !virial && !in.images->periodic && !in.Grain().On()) {
    SpringForcesInOrder(in, *order, k, gamma.data(), damped, f, *scratch);
    /* the springs after the ordered ones (an open chain's, whose first node is not the next): one by
       one, after them, as the kernel sums them */
    if (order->rest.size() < order->springs) {
      if (damped) Kernel<false, false, true, false>(in, k, gamma.data(), f, NULL, order->rest.size());
      else Kernel<false, false, false, false>(in, k, gamma.data(), f, NULL, order->rest.size());
    }
  } else if (virial) KernelFor<true>(in, k, gamma, damped, f, virial);
  else KernelFor<false>(in, k, gamma, damped, f, NULL);
}

std::vector<PetscReal> SpringAxialForces(const ForceInput &in, PetscReal k, const std::vector<PetscReal> &gamma, bool damped)
{
  const auto            &S = in.P->springs;
  std::vector<PetscReal> t(S.size());
  for (size_t s = 0; s < S.size(); s++) {
    const PetscInt   i = S[s].i, j = S[s].j;
    const PetscReal *sx = in.images->x[S[s].image], *sv = in.images->v[S[s].image];
    const PetscReal  dx = in.x[2 * j] + sx[0] - in.x[2 * i], dy = in.x[2 * j + 1] + sx[1] - in.x[2 * i + 1], r = std::sqrt(dx * dx + dy * dy);
    t[s] = k * (r - S[s].rest_length);
    if (damped) t[s] += gamma[s] * ((in.v[2 * j] + sv[0] - in.v[2 * i]) * dx + (in.v[2 * j + 1] + sv[1] - in.v[2 * i + 1]) * dy) / r;
  }
  return t;
}

PetscReal SpringEnergy(const ForceInput &in, PetscReal k)
{
  PetscReal E = 0;
  for (size_t q = 0, ns = in.P->OwnedSprings(); q < ns; q++) {
    const Spring    &s  = in.P->springs[q];
    const PetscReal *sx = in.images->x[s.image];
    const PetscReal  dx = in.x[2 * s.j] + sx[0] - in.x[2 * s.i], dy = in.x[2 * s.j + 1] + sx[1] - in.x[2 * s.i + 1];
    const PetscReal  e = std::sqrt(dx * dx + dy * dy) - s.rest_length;
    E += 0.5 * k * e * e;
  }
  return E;
}

PetscErrorCode WallSprings::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  SpringForces(in, stiffness, gamma_, damping_ratio > 0, f, virial);
  PetscCall(PetscLogFlops(30.0 * in.P->springs.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WallSprings::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  *E   = SpringEnergy(in, stiffness);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Gershgorin bounds on the spring block of M^{-1} K and M^{-1} C: per particle,
   sum over its springs of k (1/m_i + 1/sqrt(m_i m_j)), same with gamma. An explicit step is
   stable for dt < 2 / (c/2 + sqrt(c^2/4 + w^2)), the largest |eigenvalue| of x'' + c x' + w^2 x. */
PetscErrorCode WallSprings::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscCall(SpringTimeStepLimit(*in.P, stiffness, gamma_, "wall springs", limits));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SpringTimeStepLimit(const ParticleSet &P, PetscReal stiffness, const std::vector<PetscReal> &gamma_, const char *label,
                                   std::vector<TimeStepLimit> &limits)
{
  std::vector<PetscReal> w2(P.n, 0.0), c(P.n, 0.0);
  PetscFunctionBeginUser;
  for (size_t s = 0; s < P.springs.size(); s++) {
    const PetscInt  i = P.springs[s].i, j = P.springs[s].j;
    const PetscReal mij = std::sqrt(P.mass[i] * P.mass[j]);
    w2[i] += stiffness * (1 / P.mass[i] + 1 / mij);
    w2[j] += stiffness * (1 / P.mass[j] + 1 / mij);
    c[i] += gamma_[s] * (1 / P.mass[i] + 1 / mij);
    c[j] += gamma_[s] * (1 / P.mass[j] + 1 / mij);
  }
  PetscReal lam = 0, wmax = 0, cmax = 0;
  for (PetscInt i = 0; i < P.n; i++) {
    const PetscReal l = 0.5 * c[i] + std::sqrt(0.25 * c[i] * c[i] + w2[i]);
    if (l > lam) {
      lam  = l;
      wmax = std::sqrt(w2[i]);
      cmax = c[i];
    }
  }
  if (lam > 0) {
    char why[256];
    PetscCall(PetscSNPrintf(why, sizeof why, "%s: omega_max <= %.4g /µs, dashpot rate <= %.4g /µs (Gershgorin)", label, (double)wmax, (double)cmax));
    limits.push_back({2.0 / lam, why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WallSprings::OutputFields(const ForceInput &in, std::vector<TermField> &fields)
{
  PetscFunctionBeginUser;
  fields.push_back({TermField::BAR, "axial_force", "µN (tension > 0)", SpringAxialForces(in, stiffness, gamma_, damping_ratio > 0)});
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode WallSprings::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "springs: k_w = %g µN/µm, damping ratio %g (gamma = %g ng/µs for the first spring)\n", (double)stiffness,
                                   (double)damping_ratio, gamma_.empty() ? 0.0 : (double)gamma_[0]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
