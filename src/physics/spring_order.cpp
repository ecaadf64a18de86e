#include <turgor/core/mask_select.h>
#include <turgor/core/vector_clones.h>
#include <turgor/physics/spring_order.h>
#include <turgor/physics/wall_springs.h>
#include <cmath>
#include <cstring>

/* Compiled with -fno-math-errno (CMakeLists.txt): sqrt's errno branch would keep the force loop from
   vectorising; nothing here reads errno. */
namespace turgor {

void SpringOrder::Build(const ParticleSet &P)
{
  const auto &S = P.springs;
  springs       = P.OwnedSprings();
  rest.clear(), interior.clear(), by_index.clear(), ends.clear();
  size_t ns = 0; /* the ordered springs: the longest run from the first */
  while (ns < springs && S[ns].i == S[0].i + (PetscInt)ns && S[ns].image == PeriodicImages::kSelf) ns++;
  in_order = ns >= 2;
  if (!in_order) return;
  i0 = S[0].i;
  rest.resize(ns);
  for (size_t s = 0; s < ns; s++) rest[s] = S[s].rest_length;
  /* node i_s takes -F_(s-1) then +F_s alone when spring s - 1 ends at it and no spring read by index
     does */
  std::vector<char> targeted(ns + 1, 0); /* by a spring whose far end is not the next node */
  for (size_t s = 0; s < ns; s++)
    if (S[s].j != S[s].i + 1 || s + 1 == ns) {
      by_index.push_back((PetscInt)s);
      if (S[s].j >= i0 && S[s].j < i0 + (PetscInt)ns) targeted[S[s].j - i0] = 1;
    }
  interior.assign(ns, 0);
  for (size_t s = 1; s < ns; s++) interior[s] = S[s - 1].j == S[s].i && !targeted[s] ? ~(std::uint64_t)0 : 0;
  auto inner = [&](PetscInt node) { return node > i0 && node < i0 + (PetscInt)ns && interior[node - i0]; };
  for (size_t s = 0; s < ns; s++) {
    if (!interior[s]) ends.push_back({S[s].i, (PetscInt)s, 1.0});
    if (!inner(S[s].j)) ends.push_back({S[s].j, (PetscInt)s, -1.0});
  }
}

namespace {
TURGOR_VECTOR_CLONES void NextDifferencesLoop(size_t n, const PetscReal *__restrict u, PetscReal *__restrict dx, PetscReal *__restrict dy)
{
  for (size_t s = 0; s < n; s++) dx[s] = u[2 * s + 2] - u[2 * s], dy[s] = u[2 * s + 3] - u[2 * s + 1];
}
} // namespace

void NextNodeDifferences(size_t n, const PetscReal *u, PetscReal *dx, PetscReal *dy)
{
  NextDifferencesLoop(n, u, dx, dy);
}

namespace {

/* The kernel's arithmetic (SpringAxialAt, SpringDashpotAt), spring by spring; KEEP: the dashpot's part too */
template <bool DAMPED, bool KEEP>
TURGOR_VECTOR_CLONES void ForceLoop(size_t n, PetscReal k, const PetscReal *__restrict rest, const PetscReal *__restrict gamma, const PetscReal *__restrict dx,
                                    const PetscReal *__restrict dy, const PetscReal *__restrict dvx, const PetscReal *__restrict dvy, PetscReal *__restrict fx,
                                    PetscReal *__restrict fy, PetscReal *__restrict gx, PetscReal *__restrict gy)
{
  for (size_t s = 0; s < n; s++) {
    const SpringAxial a   = SpringAxialAt(dx[s], dy[s], k, rest[s]);
    PetscReal         mag = a.mag;
    if (DAMPED) {
      const PetscReal md = SpringDashpotAt(a, gamma[s], dvx[s], dvy[s]);
      mag += md;
      if (KEEP) gx[s] = md * a.ex, gy[s] = md * a.ey;
    }
    fx[s] = mag * a.ex, fy[s] = mag * a.ey;
  }
}

/* fb[2 s] = (fb[2 s] - F_(s-1)) + F_s where interior[s] (fb = f + 2 i_0) */
TURGOR_VECTOR_CLONES void InteriorNodes(size_t n, const std::uint64_t *__restrict interior, const PetscReal *__restrict fx, const PetscReal *__restrict fy,
                                        PetscReal *__restrict fb)
{
  for (size_t s = 1; s < n; s++) {
    const PetscReal ox = fb[2 * s], oy = fb[2 * s + 1];
    fb[2 * s]     = MaskSelect(interior[s], ox - fx[s - 1] + fx[s], ox);
    fb[2 * s + 1] = MaskSelect(interior[s], oy - fy[s - 1] + fy[s], oy);
  }
}

void AddShares(const SpringOrder &O, const PetscReal *fx, const PetscReal *fy, PetscReal *f)
{
  InteriorNodes(O.rest.size(), O.interior.data(), fx, fy, f + 2 * O.i0);
  for (const SpringOrder::Share &E : O.ends) { /* f += F or f -= F: a sign of magnitude 1 changes no bit */
    f[2 * E.node] += E.sign * fx[E.s];
    f[2 * E.node + 1] += E.sign * fy[E.s];
  }
}
} // namespace

void SpringForcesInOrder(const ForceInput &in, const SpringOrder &O, PetscReal k, const PetscReal *gamma, bool damped, PetscReal *f,
                         std::vector<PetscReal> &scratch)
{
  const size_t     n = O.rest.size();
  const PetscReal *x = in.x, *v = in.v;
  const auto      &S = in.P->springs;
  scratch.resize(8 * n);
  PetscReal *dx = scratch.data(), *dy = dx + n, *dvx = dy + n, *dvy = dvx + n, *fx = dvy + n, *fy = fx + n, *gx = fy + n, *gy = gx + n;
  NextNodeDifferences(n - 1, x + 2 * O.i0, dx, dy); /* the last spring's far end may not exist: by index */
  if (damped) NextNodeDifferences(n - 1, v + 2 * O.i0, dvx, dvy);
  for (PetscInt s : O.by_index) {
    const PetscInt i = S[s].i, j = S[s].j;
    dx[s] = x[2 * j] - x[2 * i], dy[s] = x[2 * j + 1] - x[2 * i + 1];
    if (damped) dvx[s] = v[2 * j] - v[2 * i], dvy[s] = v[2 * j + 1] - v[2 * i + 1];
  }
  if (damped && in.f_dashpot) ForceLoop<true, true>(n, k, O.rest.data(), gamma, dx, dy, dvx, dvy, fx, fy, gx, gy);
  else if (damped) ForceLoop<true, false>(n, k, O.rest.data(), gamma, dx, dy, dvx, dvy, fx, fy, gx, gy);
  else ForceLoop<false, false>(n, k, O.rest.data(), gamma, dx, dy, dvx, dvy, fx, fy, gx, gy);
  if (damped && in.f_dashpot) AddShares(O, gx, gy, in.f_dashpot); /* the dashpot's part apart (the energy balance observes) */
  AddShares(O, fx, fy, f);
}

} // namespace turgor
