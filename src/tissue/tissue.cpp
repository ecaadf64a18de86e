/* Tissue: building by hand, bounding box, clamps, polygon areas (any generator's tissue). */
#include <turgor/tissue/tissue.h>
#include <algorithm>
#include <cmath>
#include <limits>

namespace turgor {

PetscInt Tissue::AddParticle(PetscReal x, PetscReal y, PetscReal mass, ParticleKind kind, PetscInt cell)
{
  X.push_back(x);
  X.push_back(y);
  particles.mass.push_back(mass);
  particles.kind.push_back(kind);
  particles.cell.push_back(cell);
  return particles.n++;
}

void Tissue::Reserve(PetscInt n_particles, size_t n_springs)
{
  X.reserve(2 * (size_t)n_particles);
  particles.mass.reserve(n_particles);
  particles.kind.reserve(n_particles);
  particles.cell.reserve(n_particles);
  particles.springs.reserve(n_springs);
}

void Tissue::AddSpring(PetscInt i, PetscInt j)
{
  particles.springs.push_back({i, j, std::hypot(X[2 * j] - X[2 * i], X[2 * j + 1] - X[2 * i + 1])});
}

/* The straight joints of the walls, from the reference positions: at every wall point, the two
   incident spring ends whose directions are mutually the most opposite, and within 45° of opposite,
   continue one wall (Spring::joint). A square grid's edge midpoints join the two springs of a side;
   its corners join left with right and up with down (two walls cross), and join nothing where two
   walls meet at 90°. The repulsion counts each wall once (docs/model.md). */
static void FindWallJoints(ParticleSet &P, const std::vector<PetscReal> &X, const PetscReal period[2])
{
  const PetscReal                    straight = -0.70710678118654752; /* cos 135°: at most 45° from a straight line */
  const size_t                       ns       = P.springs.size();
  std::vector<PetscReal>             u(4 * ns, 0.0); /* outward unit direction of end 2 s + e, from its end point */
  std::vector<std::vector<PetscInt>> ends(P.n);      /* spring ends at each particle */
  for (size_t s = 0; s < ns; s++) {
    Spring         &sp = P.springs[s];
    const int       n1 = sp.image / 3 - 1, n2 = sp.image % 3 - 1; /* PeriodicImages::Index */
    const PetscReal dx = X[2 * sp.j] + n1 * period[0] - X[2 * sp.i], dy = X[2 * sp.j + 1] + n2 * period[1] - X[2 * sp.i + 1], L = std::hypot(dx, dy);
    sp.joint[0] = sp.joint[1] = -1;
    if (!(L > 0)) continue;
    u[4 * s + 0] = dx / L;
    u[4 * s + 1] = dy / L;
    u[4 * s + 2] = -dx / L;
    u[4 * s + 3] = -dy / L;
    ends[sp.i].push_back(2 * (PetscInt)s);
    ends[sp.j].push_back(2 * (PetscInt)s + 1);
  }
  auto most_opposite = [&](const std::vector<PetscInt> &at, PetscInt a) {
    PetscInt  best = -1;
    PetscReal c    = straight;
    for (PetscInt b : at) {
      const PetscReal cab = u[2 * a] * u[2 * b] + u[2 * a + 1] * u[2 * b + 1];
      if (b != a && cab < c) {
        c    = cab;
        best = b;
      }
    }
    return best;
  };
  for (PetscInt n = 0; n < P.n; n++)
    for (PetscInt a : ends[n]) {
      const PetscInt b = most_opposite(ends[n], a);
      if (b >= 0 && most_opposite(ends[n], b) == a) P.springs[a / 2].joint[a % 2] = b;
    }
}

void Tissue::Finalize()
{
  ParticleSet &P = particles;
  FindWallJoints(P, X, period);
  P.n_owned = -1; /* all */
  P.gid.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) P.gid[i] = i;
  P.fixed.assign(P.n, 0);
  UpdateBounds();
}

void Tissue::UpdateBounds()
{
  const PetscInt n = particles.n;
  for (int d = 0; d < 2; d++) {
    lo[d] = n ? X[d] : 0;
    hi[d] = n ? X[d] : 0;
    for (PetscInt i = 1; i < n; i++) {
      lo[d] = std::min(lo[d], X[2 * i + d]);
      hi[d] = std::max(hi[d], X[2 * i + d]);
    }
  }
}

PetscInt Tissue::ClosestWallParticle(PetscReal px, PetscReal py) const
{
  PetscInt  best = -1;
  PetscReal d2   = std::numeric_limits<PetscReal>::max();
  for (PetscInt i = 0; i < particles.n; i++) {
    if (particles.kind[i] != KIND_WALL) continue;
    const PetscReal dx = X[2 * i] - px, dy = X[2 * i + 1] - py, r2 = dx * dx + dy * dy;
    if (r2 < d2) {
      d2   = r2;
      best = i;
    }
  }
  return best;
}

PetscErrorCode Tissue::Clamp(MPI_Comm comm, const std::vector<std::string> &sides, const char *option)
{
  PetscFunctionBeginUser;
  const PetscReal tol = 1e-9 * (hi[0] - lo[0] + hi[1] - lo[1]);
  for (const std::string &side : sides) {
    if (side == "none") continue;
    PetscCheck(side == "left" || side == "right" || side == "bottom" || side == "top", comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
               "Option %s: unknown side '%s' (known: left, right, bottom, top, none)", option, side.c_str());
    for (PetscInt i = 0; i < particles.n; i++) {
      if (particles.kind[i] != KIND_WALL) continue;
      const PetscReal x = X[2 * i], y = X[2 * i + 1];
      const bool      hit = (side == "left" && x < lo[0] + tol) || (side == "right" && x > hi[0] - tol) || (side == "bottom" && y < lo[1] + tol) ||
                       (side == "top" && y > hi[1] - tol);
      if (hit) particles.fixed[i] = 1;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
