/* Square-cell tissue generator. Wall particles sit on the lines of a (cells_x*s) x (cells_y*s)
   lattice of spacing cell_size/s (s = springs per side): every lattice point with at least one
   coordinate on a cell boundary. For 16 x 16 cells and s = 2 this gives 17^2 corners + 544 edge
   midpoints = 833 wall particles, as in the seed (TW 562, Fig. 2). */
#include <turgor/tissue/square_grid.h>
#include <algorithm>
#include <cmath>

namespace turgor {

namespace {

/* What both grids take from the spec: nx x ny cells of s springs per side (lattice spacing dl),
   each with a k x k lattice of fluid particles of mass mf. */
struct GridLattice {
  PetscInt  nx, ny, s, k;
  PetscReal dl, mf;
};

PetscErrorCode GetGridLattice(MPI_Comm comm, const SquareGridSpec &spec, GridLattice *L)
{
  PetscFunctionBeginUser;
  L->nx = spec.cells_x;
  L->ny = spec.cells_y;
  L->s  = spec.springs_per_side;
  L->dl = spec.cell_size / (PetscReal)L->s;
  L->k  = (PetscInt)std::lround(std::sqrt((double)spec.fluid_per_cell));
  L->mf = spec.FluidParticleMass();
  PetscCheck(spec.fluid_per_cell == 0 || L->mf > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_fluid_particle_mass: fluid particle mass must be > 0 (got %g)", (double)L->mf);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The fluid of cell (cx, cy): its k x k lattice, row by row. */
void AddCellFluid(const SquareGridSpec &spec, const GridLattice &L, PetscInt cx, PetscInt cy, Tissue &T)
{
  for (PetscInt j = 0; j < L.k; j++)
    for (PetscInt i = 0; i < L.k; i++)
      T.AddParticle((cx + (i + 0.5) / L.k) * spec.cell_size, (cy + (j + 0.5) / L.k) * spec.cell_size, L.mf, KIND_FLUID, cy * L.nx + cx);
}

} // namespace

PetscErrorCode GenerateSquareGridTissue(MPI_Comm comm, const SquareGridSpec &spec, Tissue *tissue)
{
  GridLattice L;
  PetscFunctionBeginUser;
  PetscCall(GetGridLattice(comm, spec, &L));
  const PetscInt  nx = L.nx, ny = L.ny, s = L.s, k = L.k;
  const PetscInt  ax = nx * s + 1, ay = ny * s + 1; /* lattice points per direction */
  const PetscReal dl      = L.dl;
  *tissue                 = Tissue();
  Tissue               &T = *tissue;
  std::vector<PetscInt> id((size_t)ax * ay, -1);
  /* lattice points on a cell boundary, the fluid; each cell's bottom and left edges, then the top and right */
  T.Reserve(ax * ay - nx * ny * (s - 1) * (s - 1) + nx * ny * k * k, (size_t)nx * ny * 2 * s + (ax - 1) + (ay - 1));
  T.cell_walls.reserve(nx * ny);
  auto wall   = [&](PetscInt a, PetscInt b) { id[b * ax + a] = T.AddParticle(a * dl, b * dl, spec.wall_mass, KIND_WALL); };
  auto spring = [&](PetscInt a, PetscInt b, PetscInt a2, PetscInt b2) { T.particles.springs.push_back({id[b * ax + a], id[b2 * ax + a2], dl}); };

  /* Particles and springs are numbered cell by cell (each cell owns the wall points of its bottom and
     left edges, then its fluid), so that neighbours in space are close in memory; the top row and
     right column of wall points come last. */
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s;
      for (PetscInt t = 0; t < s; t++) wall(a0 + t, b0);
      for (PetscInt t = 1; t < s; t++) wall(a0, b0 + t);
      AddCellFluid(spec, L, cx, cy, T);
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

/* The numbers are GenerateSquareGridTissue's: particles cell by cell (bottom and left wall points,
   fluid), then the top row and the right column; springs cell by cell (bottom, left), then the top
   and the right boundary. A part emits them in that order, so that its numbering increases. */
PetscErrorCode GenerateSquareGridPart(MPI_Comm comm, const SquareGridSpec &spec, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part)
{
  GridLattice L;
  PetscFunctionBeginUser;
  PetscCall(GetGridLattice(comm, spec, &L));
  const PetscInt  nx = L.nx, ny = L.ny, s = L.s, k = L.k;
  const PetscInt  ax = nx * s + 1, ay = ny * s + 1, per_cell = 2 * s - 1 + k * k;
  const PetscInt  walls_base = nx * ny * per_cell, springs_base = nx * ny * 2 * s;
  const PetscReal dl = L.dl;
  PetscCheck(0 <= c0 && c0 <= c1 && c1 <= nx * ny, comm, PETSC_ERR_ARG_OUTOFRANGE, "cells [%" PetscInt_FMT ", %" PetscInt_FMT ") of a grid of %" PetscInt_FMT,
             c0, c1, nx * ny);
  PetscCheck(distance >= 0 && std::isfinite(distance), comm, PETSC_ERR_ARG_OUTOFRANGE, "a part's distance must be finite and >= 0 (got %g)", (double)distance);
  *part     = Tissue();
  Tissue &T = *part;
  if (c0 < c1) {
    /* rows within `distance`: a cell j rows away is (j - 1) cells away; two rows more against the
       rounding of the positions that the halo measures, and one for complete springs */
    const PetscInt        h  = (PetscInt)std::min((PetscReal)ny, std::floor(distance / spec.cell_size)) + 2;
    const PetscInt        r0 = std::max((PetscInt)0, c0 / nx - h - 1), r1 = std::min(ny - 1, (c1 - 1) / nx + h + 1);
    const PetscInt        b0 = r0 * s, b1 = (r1 + 1) * s; /* the lattice rows of the part's rings */
    std::vector<PetscInt> id((size_t)ax * (b1 - b0 + 1), -1), gid, sgid;
    auto                  at   = [&](PetscInt a, PetscInt b) -> PetscInt                    &{ return id[(size_t)(b - b0) * ax + a]; };
    auto                  wall = [&](PetscInt a, PetscInt b, PetscInt g) {
      at(a, b) = T.AddParticle(a * dl, b * dl, spec.wall_mass, KIND_WALL);
      gid.push_back(g);
    };
    auto spring = [&](PetscInt a, PetscInt b, PetscInt a2, PetscInt b2, PetscInt g) {
      T.particles.springs.push_back({at(a, b), at(a2, b2), dl});
      sgid.push_back(g);
    };
    const PetscInt rows = r1 - r0 + 1;
    T.Reserve(rows * nx * per_cell + nx * s + ax + (b1 - b0 + 1), (size_t)rows * nx * 2 * s + nx * s + ax + (b1 - b0));
    for (PetscInt cy = r0; cy <= r1; cy++)
      for (PetscInt cx = 0; cx < nx; cx++) {
        const PetscInt c = cy * nx + cx, a0 = cx * s, bb = cy * s;
        for (PetscInt t = 0; t < s; t++) wall(a0 + t, bb, c * per_cell + t);
        for (PetscInt t = 1; t < s; t++) wall(a0, bb + t, c * per_cell + s + t - 1);
        AddCellFluid(spec, L, cx, cy, T);
        for (PetscInt f = 0; f < k * k; f++) gid.push_back(c * per_cell + 2 * s - 1 + f);
      }
    if (r1 + 1 < ny) /* the top edge of the part: the next row's bottom wall points */
      for (PetscInt cx = 0; cx < nx; cx++)
        for (PetscInt t = 0; t < s; t++) wall(cx * s + t, b1, ((r1 + 1) * nx + cx) * per_cell + t);
    else
      for (PetscInt a = 0; a < ax; a++) wall(a, ay - 1, walls_base + a);
    for (PetscInt b = b0; b <= std::min(b1, ay - 2); b++) wall(ax - 1, b, walls_base + ax + b);

    for (PetscInt cy = r0; cy <= r1; cy++)
      for (PetscInt cx = 0; cx < nx; cx++) {
        const PetscInt c = cy * nx + cx, a0 = cx * s, bb = cy * s;
        for (PetscInt t = 0; t < s; t++) spring(a0 + t, bb, a0 + t + 1, bb, c * 2 * s + t);
        for (PetscInt t = 0; t < s; t++) spring(a0, bb + t, a0, bb + t + 1, c * 2 * s + s + t);
      }
    if (r1 + 1 < ny)
      for (PetscInt cx = 0; cx < nx; cx++)
        for (PetscInt t = 0; t < s; t++) spring(cx * s + t, b1, cx * s + t + 1, b1, ((r1 + 1) * nx + cx) * 2 * s + t);
    else
      for (PetscInt a = 0; a + 1 < ax; a++) spring(a, ay - 1, a + 1, ay - 1, springs_base + a);
    for (PetscInt b = b0; b < b1; b++) spring(ax - 1, b, ax - 1, b + 1, springs_base + ax - 1 + b);

    for (PetscInt cy = r0; cy <= r1; cy++)
      for (PetscInt cx = 0; cx < nx; cx++) {
        const PetscInt        a0 = cx * s, bb = cy * s;
        std::vector<PetscInt> ring;
        for (PetscInt t = 0; t < s; t++) ring.push_back(at(a0 + t, bb));
        for (PetscInt t = 0; t < s; t++) ring.push_back(at(a0 + s, bb + t));
        for (PetscInt t = 0; t < s; t++) ring.push_back(at(a0 + s - t, bb + s));
        for (PetscInt t = 0; t < s; t++) ring.push_back(at(a0, bb + s - t));
        T.cell_walls.push_back(ring);
        T.cell_gid.push_back(cy * nx + cx);
      }
    T.Finalize(); /* the joints: every spring of a particle within `distance` is here */
    T.particles.gid.swap(gid);
    T.particles.spring_gid.swap(sgid);
  }
  /* the whole grid's bounding box, as Tissue::UpdateBounds finds it */
  T.lo[0] = T.lo[1] = 0;
  T.hi[0]           = (ax - 1) * dl;
  T.hi[1]           = (ay - 1) * dl;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GeneratePeriodicSquareGridTissue(MPI_Comm comm, const SquareGridSpec &spec, Tissue *tissue)
{
  GridLattice L;
  PetscFunctionBeginUser;
  PetscCall(GetGridLattice(comm, spec, &L));
  const PetscInt  nx = L.nx, ny = L.ny, s = L.s;
  const PetscInt  ax = nx * s, ay = ny * s; /* unique lattice points per direction */
  const PetscReal dl      = L.dl;
  *tissue                 = Tissue();
  Tissue               &T = *tissue;
  std::vector<PetscInt> id((size_t)ax * ay, -1);
  for (PetscInt cy = 0; cy < ny; cy++)
    for (PetscInt cx = 0; cx < nx; cx++) {
      const PetscInt a0 = cx * s, b0 = cy * s;
      for (PetscInt t = 0; t < s; t++) id[b0 * ax + a0 + t] = T.AddParticle((a0 + t) * dl, b0 * dl, spec.wall_mass, KIND_WALL);
      for (PetscInt t = 1; t < s; t++) id[(b0 + t) * ax + a0] = T.AddParticle(a0 * dl, (b0 + t) * dl, spec.wall_mass, KIND_WALL);
      AddCellFluid(spec, L, cx, cy, T);
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
      const PetscInt a0 = cx * s, b0 = cy * s;
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
  T.period[0] = nx * spec.cell_size; /* before Finalize: the springs across the boundary join their images */
  T.period[1] = ny * spec.cell_size;
  T.Finalize();
  T.particles.fixed[0] = 1; /* the corner at the origin: the four RVE corners are one particle */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SquareGridSpec::SetFromOptions(MPI_Comm comm, bool layout, ParameterList *params)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_", "Tissue geometry (square cells with shared walls; units µm, ng)", "turgor");
  if (layout) {
    PetscCall(TurgorOptionsInt(params, "-cells_x", "Cells in x", "SquareGridSpec", cells_x, &cells_x, NULL));
    PetscCall(TurgorOptionsInt(params, "-cells_y", "Cells in y", "SquareGridSpec", cells_y, &cells_y, NULL));
  }
  PetscCall(TurgorOptionsReal(params, "-cell_size", "Cell side length [µm]", "SquareGridSpec", cell_size, &cell_size, NULL));
  PetscCall(TurgorOptionsInt(params, "-springs_per_side", "Wall springs along one cell side", "SquareGridSpec", springs_per_side, &springs_per_side, NULL));
  PetscCall(
    TurgorOptionsInt(params, "-fluid_per_cell", "SPH particles per cell (a square number k^2)", "SquareGridSpec", fluid_per_cell, &fluid_per_cell, NULL));
  PetscCall(TurgorOptionsReal(params, "-wall_particle_mass", "Wall (DEM) particle mass m_DEM [ng]", "SquareGridSpec", wall_mass, &wall_mass, NULL));
  PetscCall(
    TurgorOptionsReal(params, "-fluid_density", "2D fluid density = 3D density x thickness [ng/µm^2]", "SquareGridSpec", fluid_density, &fluid_density, NULL));
  PetscCall(TurgorOptionsReal(params, "-fluid_particle_mass", "SPH particle mass m_SPH [ng]; 0: fluid_density x cell area / fluid_per_cell", "SquareGridSpec",
                              fluid_mass, &fluid_mass, NULL));
  PetscOptionsEnd();

  PetscCheck(cells_x >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cells_x = %" PetscInt_FMT ": must be >= 1", cells_x);
  PetscCheck(cells_y >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cells_y = %" PetscInt_FMT ": must be >= 1", cells_y);
  PetscCheck(cell_size > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cell_size = %g: must be > 0", (double)cell_size);
  PetscCheck(springs_per_side >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_springs_per_side = %" PetscInt_FMT ": must be >= 1", springs_per_side);
  PetscInt k = (PetscInt)std::lround(std::sqrt((double)fluid_per_cell));
  PetscCheck(fluid_per_cell >= 0 && k * k == fluid_per_cell, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_fluid_per_cell = %" PetscInt_FMT ": must be a square number (k x k lattice per cell)", fluid_per_cell);
  PetscCheck(wall_mass > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_wall_particle_mass = %g: a particle mass must be > 0", (double)wall_mass);
  PetscCheck(fluid_density > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_fluid_density = %g: must be > 0", (double)fluid_density);
  PetscCheck(std::isfinite(fluid_mass) && fluid_mass >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_fluid_particle_mass = %g: a particle mass must be > 0 (or 0 to derive it from -tissue_fluid_density)", (double)fluid_mass);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal SquareGridSpec::FluidParticleMass() const
{
  if (fluid_mass > 0) return fluid_mass;
  if (fluid_per_cell == 0) return 0;
  return fluid_density * cell_size * cell_size / (PetscReal)fluid_per_cell;
}

void SquareGridSpec::Count(PetscReal nx, PetscReal ny, bool periodic, PetscReal *particles, PetscReal *springs) const
{
  const PetscReal s = (PetscReal)springs_per_side, ax = nx * s, ay = ny * s;
  /* lattice points on cell boundaries: every point of the (ax+1) x (ay+1) lattice on a grid line */
  const PetscReal walls = periodic ? nx * ny * (2 * s - 1) : (ax + 1) * (ny + 1) + (ay + 1) * (nx + 1) - (nx + 1) * (ny + 1);
  *particles            = walls + nx * ny * (PetscReal)fluid_per_cell;
  *springs              = periodic ? 2 * s * nx * ny : ax * (ny + 1) + ay * (nx + 1);
}

PetscErrorCode SquareGridGenerator::Estimate(PetscReal *particles, PetscReal *springs) const
{
  PetscFunctionBeginUser;
  spec.Count((PetscReal)spec.cells_x, (PetscReal)spec.cells_y, false, particles, springs);
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string SquareGridGenerator::SizeOptions() const
{
  return "-tissue_cells_x " + std::to_string((long long)spec.cells_x) + " -tissue_cells_y " + std::to_string((long long)spec.cells_y) +
         " -tissue_springs_per_side " + std::to_string((long long)spec.springs_per_side) + " -tissue_fluid_per_cell " +
         std::to_string((long long)spec.fluid_per_cell);
}

PetscErrorCode SquareGridGenerator::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "tissue square_grid: %" PetscInt_FMT " x %" PetscInt_FMT " cells of %g µm, %" PetscInt_FMT
                                   " springs per side, %" PetscInt_FMT " fluid particles per cell\n",
                                   spec.cells_x, spec.cells_y, (double)spec.cell_size, spec.springs_per_side, spec.fluid_per_cell));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
