/* Square-cell tissue generator. Wall particles sit on the lines of a (cells_x*s) x (cells_y*s)
   lattice of spacing cell_size/s (s = springs per side): every lattice point with at least one
   coordinate on a cell boundary. For 16 x 16 cells and s = 2 this gives 17^2 corners + 544 edge
   midpoints = 833 wall particles, as in the seed (TW 562, Fig. 2). */
#include <turgor/tissue.h>
#include <algorithm>
#include <cmath>
#include <limits>

namespace turgor {

PetscErrorCode GenerateSquareGridTissue(MPI_Comm comm, const TissueSpec &spec, Tissue *tissue)
{
  const PetscInt  nx = spec.cells_x, ny = spec.cells_y, s = spec.springs_per_side;
  const PetscInt  ax = nx * s + 1, ay = ny * s + 1; /* lattice points per direction */
  const PetscReal dl = spec.cell_size / (PetscReal)s;
  const PetscInt  k  = (PetscInt)std::lround(std::sqrt((double)spec.fluid_per_cell));
  const PetscReal mf = spec.FluidParticleMass();

  PetscFunctionBeginUser;
  PetscCheck(spec.fluid_per_cell == 0 || mf > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_particle_mass: fluid particle mass must be > 0 (got %g)", (double)mf);
  *tissue      = Tissue();
  ParticleSet &P = tissue->particles;
  std::vector<PetscInt> id((size_t)ax * ay, -1);
  auto on_wall = [&](PetscInt a, PetscInt b) { return a % s == 0 || b % s == 0; };

  /* wall particles, row by row */
  for (PetscInt b = 0; b < ay; b++)
    for (PetscInt a = 0; a < ax; a++) {
      if (!on_wall(a, b)) continue;
      id[b * ax + a] = P.n++;
      tissue->X.push_back(a * dl);
      tissue->X.push_back(b * dl);
      P.mass.push_back(spec.wall_mass);
      P.kind.push_back(KIND_WALL);
      P.cell.push_back(-1);
    }
  /* springs: along horizontal lines (b on a cell boundary) and vertical lines */
  for (PetscInt b = 0; b < ay; b += s)
    for (PetscInt a = 0; a + 1 < ax; a++) P.springs.push_back({id[b * ax + a], id[b * ax + a + 1], dl});
  for (PetscInt a = 0; a < ax; a += s)
    for (PetscInt b = 0; b + 1 < ay; b++) P.springs.push_back({id[b * ax + a], id[(b + 1) * ax + a], dl});

  /* cells: wall ring counter-clockwise from the lower-left corner, then the fluid lattice */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt        a0 = cx * s, b0 = cy * s, c = cy * nx + cx;
      std::vector<PetscInt> ring;
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[b0 * ax + a0 + t]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + t) * ax + a0 + s]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + s) * ax + a0 + s - t]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + s - t) * ax + a0]);
      tissue->cell_walls.push_back(ring);
      for (PetscInt j = 0; j < k; j++)
        for (PetscInt i = 0; i < k; i++) {
          P.n++;
          tissue->X.push_back((cx + (i + 0.5) / k) * spec.cell_size);
          tissue->X.push_back((cy + (j + 0.5) / k) * spec.cell_size);
          P.mass.push_back(mf);
          P.kind.push_back(KIND_FLUID);
          P.cell.push_back(c);
        }
    }
  P.n_owned = P.n;
  P.gid.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) P.gid[i] = i;
  P.fixed.assign(P.n, 0);
  tissue->hi[0] = nx * spec.cell_size;
  tissue->hi[1] = ny * spec.cell_size;
  PetscFunctionReturn(PETSC_SUCCESS);
}

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
    if (r2 < d2) { d2 = r2; best = i; }
  }
  return best;
}

PetscErrorCode Tissue::Clamp(MPI_Comm comm, const std::vector<std::string> &sides, const char *option)
{
  PetscFunctionBeginUser;
  const PetscReal tol = 1e-9 * (hi[0] - lo[0] + hi[1] - lo[1]);
  for (const std::string &side : sides) {
    if (side == "none") continue;
    PetscCheck(side == "left" || side == "right" || side == "bottom" || side == "top", comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option %s: unknown side '%s' (known: left, right, bottom, top, none)", option, side.c_str());
    for (PetscInt i = 0; i < particles.n; i++) {
      if (particles.kind[i] != KIND_WALL) continue;
      const PetscReal x = X[2 * i], y = X[2 * i + 1];
      const bool      hit = (side == "left" && x < lo[0] + tol) || (side == "right" && x > hi[0] - tol) || (side == "bottom" && y < lo[1] + tol) || (side == "top" && y > hi[1] - tol);
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
