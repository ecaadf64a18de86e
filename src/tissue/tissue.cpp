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

void Tissue::AddSpring(PetscInt i, PetscInt j)
{
  particles.springs.push_back({i, j, std::hypot(X[2 * j] - X[2 * i], X[2 * j + 1] - X[2 * i + 1])});
}

void Tissue::Finalize()
{
  ParticleSet &P = particles;
  P.n_owned      = P.n;
  P.gid.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) P.gid[i] = i;
  P.fixed.assign(P.n, 0);
  for (int d = 0; d < 2; d++) {
    lo[d] = P.n ? X[d] : 0;
    hi[d] = P.n ? X[d] : 0;
    for (PetscInt i = 1; i < P.n; i++) {
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

PetscReal PolygonArea(const std::vector<PetscInt> &ring, const PetscReal *x)
{
  PetscReal a = 0;
  for (size_t t = 0; t < ring.size(); t++) {
    const PetscInt i = ring[t], j = ring[(t + 1) % ring.size()];
    a += x[2 * i] * x[2 * j + 1] - x[2 * j] * x[2 * i + 1];
  }
  return 0.5 * a;
}

} // namespace turgor
