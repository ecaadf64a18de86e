/* Square-cell tissue generator. Wall particles sit on the lines of a (cells_x*s) x (cells_y*s)
   lattice of spacing cell_size/s (s = springs per side): every lattice point with at least one
   coordinate on a cell boundary. For 16 x 16 cells and s = 2 this gives 17^2 corners + 544 edge
   midpoints = 833 wall particles, as in the seed (TW 562, Fig. 2). */
#include <turgor/tissue/tissue.h>
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
  *tissue = Tissue();
  Tissue               &T = *tissue;
  std::vector<PetscInt> id((size_t)ax * ay, -1);
  auto wall = [&](PetscInt a, PetscInt b) { id[b * ax + a] = T.AddParticle(a * dl, b * dl, spec.wall_mass, KIND_WALL); };
  auto spring = [&](PetscInt a, PetscInt b, PetscInt a2, PetscInt b2) { T.particles.springs.push_back({id[b * ax + a], id[b2 * ax + a2], dl}); };

  /* Particles and springs are numbered cell by cell (each cell owns the wall points of its bottom and
     left edges, then its fluid), so that neighbours in space are close in memory; the top row and
     right column of wall points come last. */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s, c = cy * nx + cx;
      for (PetscInt t = 0; t < s; t++) wall(a0 + t, b0);
      for (PetscInt t = 1; t < s; t++) wall(a0, b0 + t);
      for (PetscInt j = 0; j < k; j++)
        for (PetscInt i = 0; i < k; i++) T.AddParticle((cx + (i + 0.5) / k) * spec.cell_size, (cy + (j + 0.5) / k) * spec.cell_size, mf, KIND_FLUID, c);
    }
  for (PetscInt a = 0; a < ax; a++) wall(a, ay - 1);
  for (PetscInt b = 0; b + 1 < ay; b++)
    if (id[b * ax + ax - 1] < 0) wall(ax - 1, b);

  /* springs: each cell's bottom and left edges, then the top and right boundaries */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s;
      for (PetscInt t = 0; t < s; t++) spring(a0 + t, b0, a0 + t + 1, b0);
      for (PetscInt t = 0; t < s; t++) spring(a0, b0 + t, a0, b0 + t + 1);
    }
  for (PetscInt a = 0; a + 1 < ax; a++) spring(a, ay - 1, a + 1, ay - 1);
  for (PetscInt b = 0; b + 1 < ay; b++) spring(ax - 1, b, ax - 1, b + 1);

  /* cells: wall ring counter-clockwise from the lower-left corner */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt        a0 = cx * s, b0 = cy * s;
      std::vector<PetscInt> ring;
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[b0 * ax + a0 + t]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + t) * ax + a0 + s]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + s) * ax + a0 + s - t]);
      for (PetscInt t = 0; t < s; t++) ring.push_back(id[(b0 + s - t) * ax + a0]);
      T.cell_walls.push_back(ring);
    }
  T.Finalize();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeneratePeriodicSquareGridTissue(MPI_Comm comm, const TissueSpec &spec, Tissue *tissue)
{
  const PetscInt  nx = spec.cells_x, ny = spec.cells_y, s = spec.springs_per_side;
  const PetscInt  ax = nx * s, ay = ny * s; /* unique lattice points per direction */
  const PetscReal dl = spec.cell_size / (PetscReal)s;
  const PetscInt  k  = (PetscInt)std::lround(std::sqrt((double)spec.fluid_per_cell));
  const PetscReal mf = spec.FluidParticleMass();

  PetscFunctionBeginUser;
  PetscCheck(spec.fluid_per_cell == 0 || mf > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_particle_mass: fluid particle mass must be > 0 (got %g)", (double)mf);
  *tissue = Tissue();
  Tissue               &T = *tissue;
  std::vector<PetscInt> id((size_t)ax * ay, -1);
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s, c = cy * nx + cx;
      for (PetscInt t = 0; t < s; t++) id[b0 * ax + a0 + t] = T.AddParticle((a0 + t) * dl, b0 * dl, spec.wall_mass, KIND_WALL);
      for (PetscInt t = 1; t < s; t++) id[(b0 + t) * ax + a0] = T.AddParticle(a0 * dl, (b0 + t) * dl, spec.wall_mass, KIND_WALL);
      for (PetscInt j = 0; j < k; j++)
        for (PetscInt i = 0; i < k; i++) T.AddParticle((cx + (i + 0.5) / k) * spec.cell_size, (cy + (j + 0.5) / k) * spec.cell_size, mf, KIND_FLUID, c);
    }
  /* springs to the next lattice point, wrapping to the image across the boundary */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s;
      for (PetscInt t = 0; t < s; t++) {
        const PetscInt a = a0 + t, a1 = (a + 1) % ax;
        T.particles.springs.push_back({id[b0 * ax + a], id[b0 * ax + a1], dl, PeriodicImages::Index(a + 1 == ax ? 1 : 0, 0)});
      }
      for (PetscInt t = 0; t < s; t++) {
        const PetscInt b = b0 + t, b1 = (b + 1) % ay;
        T.particles.springs.push_back({id[b * ax + a0], id[b1 * ax + a0], dl, PeriodicImages::Index(0, b + 1 == ay ? 1 : 0)});
      }
    }
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt        a0 = cx * s, b0 = cy * s;
      /* lattice points of the ring, counter-clockwise; points past the period are images */
      std::vector<PetscInt> ring;
      std::vector<int>      img;
      auto                  add = [&](PetscInt a, PetscInt b) {
        ring.push_back(id[(b % ay) * ax + a % ax]);
        img.push_back(PeriodicImages::Index(a >= ax ? 1 : 0, b >= ay ? 1 : 0));
      };
      for (PetscInt t = 0; t < s; t++) add(a0 + t, b0);
      for (PetscInt t = 0; t < s; t++) add(a0 + s, b0 + t);
      for (PetscInt t = 0; t < s; t++) add(a0 + s - t, b0 + s);
      for (PetscInt t = 0; t < s; t++) add(a0, b0 + s - t);
      T.cell_wall_images.push_back(img);
      T.cell_walls.push_back(ring);
    }
  T.Finalize();
  T.period[0]           = nx * spec.cell_size;
  T.period[1]           = ny * spec.cell_size;
  T.particles.fixed[0] = 1; /* the corner at the origin: the four RVE corners are one particle */
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
