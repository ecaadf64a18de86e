#include <turgor/tissue/periodic_polygons.h>
#include <turgor/core/uniform_random.h>
#include <turgor/tissue/voronoi.h>
#include <cmath>

namespace turgor {

static const char *const kLatticeNames[] = {"voronoi", "square", "hexagonal"};

const char *PeriodicPolygonSpec::LatticeName() const
{
  return kLatticeNames[(int)lattice];
}

PetscErrorCode PeriodicPolygonSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscInt l = (PetscInt)lattice;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "prve_", "Periodic polygonal RVE (-material polygon_rve; µm)", "turgor");
  PetscCall(TurgorOptionsEList(params, "-lattice", "Cells: voronoi (random seeds), square or hexagonal (regular lattices, for verification)",
                               "PeriodicPolygonSpec", kLatticeNames, 3, kLatticeNames[l], &l, NULL));
  PetscCall(
    TurgorOptionsInt(params, "-cells", "Cells K in the periodic box (square: a square number; hexagonal: 4 m^2)", "PeriodicPolygonSpec", cells, &cells, NULL));
  PetscCall(TurgorOptionsReal(params, "-cell_size", "Square root of the mean cell area [µm]", "PeriodicPolygonSpec", cell_size, &cell_size, NULL));
  PetscCall(TurgorOptionsInt(params, "-seed", "Seed of the random Voronoi seeds", "PeriodicPolygonSpec", seed, &seed, NULL));
  PetscCall(
    TurgorOptionsInt(params, "-lloyd_steps", "Lloyd relaxations of the Voronoi seeds (periodic)", "PeriodicPolygonSpec", lloyd_steps, &lloyd_steps, NULL));
  PetscCall(PetscOptionsReal("-halo_margin",
                             "Distance [µm] beyond the interactions' reach within which periodic images of cells are kept (0: half the cell size)",
                             "PeriodicPolygonSpec", halo_margin, &halo_margin, NULL));
  PetscCall(TurgorOptionsReal(params, "-gap", "Gap [µm] between neighbouring cells' bar surfaces (a middle lamella; 0: touching at 2 r)", "PeriodicPolygonSpec",
                              gap, &gap, NULL));
  PetscOptionsEnd();
  lattice = (PeriodicLattice)l;
  PetscCheck(std::isfinite(gap) && gap >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -prve_gap = %g: must be finite and >= 0", (double)gap);
  PetscCheck(std::isfinite(halo_margin) && halo_margin >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -prve_halo_margin = %g: must be finite and >= 0",
             (double)halo_margin);
  if (halo_margin == 0) halo_margin = 0.5 * cell_size;
  PetscCheck(cells >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -prve_cells = %" PetscInt_FMT ": must be >= 1", cells);
  PetscCheck(lattice != PeriodicLattice::Voronoi || cells >= 2, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -prve_cells = %" PetscInt_FMT ": a Voronoi RVE needs at least 2 cells (one seed tiles the box with a single square cell glued to "
             "its own images: -prve_lattice square -prve_cells 1 is that lattice)",
             cells);
  const PetscInt m = (PetscInt)std::llround(std::sqrt((double)cells));
  PetscCheck(lattice != PeriodicLattice::Square || m * m == cells, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -prve_cells = %" PetscInt_FMT ": a square lattice needs a square number of cells (1, 4, 9, 16, ...)", cells);
  PetscCheck(lattice != PeriodicLattice::Hexagonal || (m * m == cells && m % 2 == 0), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -prve_cells = %" PetscInt_FMT ": a hexagonal lattice needs 4 m^2 cells (4, 16, 64, 256, ...): an even number of rows", cells);
  PetscCheck(std::isfinite(cell_size) && cell_size > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -prve_cell_size = %g: must be finite and > 0",
             (double)cell_size);
  PetscCheck(lloyd_steps >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -prve_lloyd_steps = %" PetscInt_FMT ": must be >= 0", lloyd_steps);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The power diagram of the seeds and their eight images in the box grown by a period on every
   side: the first K cells are the periodic cells (a cell is cut only by seeds within its own
   diameter, and every such seed, images included, is there). */
static PetscErrorCode PeriodicCells(const std::vector<Point2> &seeds, const PetscReal L[2], std::vector<PowerCell> *cells)
{
  std::vector<Point2> all(seeds);
  PetscFunctionBeginUser;
  for (int n1 = -1; n1 <= 1; n1++)
    for (int n2 = -1; n2 <= 1; n2++)
      if (n1 || n2)
        for (const Point2 &s : seeds) all.push_back({s[0] + n1 * L[0], s[1] + n2 * L[1]});
  const PetscReal box[4] = {-L[0], -L[1], 2 * L[0], 2 * L[1]};
  PetscCall(ComputePowerDiagram(box, all, {}, cells));
  cells->resize(seeds.size());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PeriodicPolygonRings(MPI_Comm comm, const PeriodicPolygonSpec &spec, PetscReal bar_radius, std::vector<PolygonRing> *rings, PetscReal period[2])
{
  const size_t        K = (size_t)spec.cells;
  const PetscInt      m = (PetscInt)std::llround(std::sqrt((double)spec.cells));
  const PetscReal     a = spec.cell_size;
  std::vector<Point2> seeds;
  PetscFunctionBeginUser;
  switch (spec.lattice) {
  case PeriodicLattice::Square:
    period[0] = period[1] = (PetscReal)m * a;
    for (PetscInt j = 0; j < m; j++)
      for (PetscInt i = 0; i < m; i++) seeds.push_back({((PetscReal)i + 0.5) * a, ((PetscReal)j + 0.5) * a});
    break;
  case PeriodicLattice::Hexagonal: { /* centre spacing d: a hexagon's area sqrt(3)/2 d^2 = a^2; rows sqrt(3)/2 d apart, odd rows shifted by d/2 */
    const PetscReal d = a * std::sqrt(2 / std::sqrt(3.0)), h = 0.5 * std::sqrt(3.0) * d;
    period[0] = (PetscReal)m * d;
    period[1] = (PetscReal)m * h;
    for (PetscInt j = 0; j < m; j++)
      for (PetscInt i = 0; i < m; i++) seeds.push_back({((PetscReal)i + 0.25 + 0.5 * (PetscReal)(j % 2)) * d, ((PetscReal)j + 0.5) * h});
    break;
  }
  case PeriodicLattice::Voronoi: {
    UniformRandom u(spec.seed);
    period[0] = period[1] = std::sqrt((PetscReal)K) * a;
    for (size_t k = 0; k < K; k++) {
      const PetscReal x = u(), y = u();
      seeds.push_back({x * period[0], y * period[1]});
    }
    break;
  }
  }
  std::vector<PowerCell> cells;
  for (PetscInt step = 0;; step++) {
    PetscCall(PeriodicCells(seeds, period, &cells));
    if (spec.lattice != PeriodicLattice::Voronoi || step == spec.lloyd_steps) break;
    for (size_t k = 0; k < K; k++) { /* Lloyd: the centroid, wrapped into the box */
      const Point2 c = RingCentroid(cells[k].v);
      for (int d = 0; d < 2; d++) seeds[k][d] = c[d] - period[d] * std::floor(c[d] / period[d]);
    }
  }
  rings->assign(K, PolygonRing());
  const PetscReal min_edge = std::max(bar_radius, 1e-9 * a);
  for (size_t k = 0; k < K; k++) {
    ShrinkPowerCell(cells[k], bar_radius + 0.5 * spec.gap, min_edge, &(*rings)[k].points);
    PetscCheck((*rings)[k].points.size() >= 3, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -tissue_bar_radius = %g: periodic cell %zu vanishes when shrunk by the bar radius (-prve_cell_size %g); use a smaller radius or larger "
               "cells",
               (double)bar_radius, k, (double)a);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
