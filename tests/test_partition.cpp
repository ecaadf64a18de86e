static const char help[] = "METIS cell partition: the cell graph of a square grid and of a Voronoi tissue, edge cut against the bound of a "
                           "square split, balance, connected parts, reproducibility, refusals.\n"
                           "  -grid N            cells per side of the square grid (default 64)\n"
                           "  -parts P           parts (default 4)\n"
                           "  -voronoi_cells N   cells of the Voronoi tissue (default 400)\n";
#include "test_util.h"
#include <turgor/parallel/cell_partition.h>
#include <algorithm>

using namespace turgor;

static MetisOptions metis; /* -seed, -ncuts, -contig */

/* Every cell in a part, and every part one connected piece of the cell graph (BFS inside it). */
static PetscErrorCode CheckParts(const CellGraph &g, const CellPartition &p)
{
  const PetscInt        n = g.NumCells();
  std::vector<PetscInt> size((size_t)p.nparts, 0), pieces((size_t)p.nparts, 0);
  std::vector<char>     seen((size_t)n, 0);
  PetscFunctionBeginUser;
  TG_CHECK((PetscInt)p.part.size() == n, "%zu parts for %" PetscInt_FMT " cells", p.part.size(), n);
  for (PetscInt c = 0; c < n; c++) {
    TG_CHECK(p.part[c] >= 0 && p.part[c] < p.nparts, "cell %" PetscInt_FMT " in part %" PetscInt_FMT, c, p.part[c]);
    size[p.part[c]]++;
  }
  for (PetscInt q = 0; q < p.nparts; q++) TG_CHECK(size[q] > 0, "part %" PetscInt_FMT " is empty", q);
  for (PetscInt c0 = 0; c0 < n; c0++) {
    if (seen[c0]) continue;
    pieces[p.part[c0]]++;
    std::vector<PetscInt> stack = {c0};
    seen[c0]                    = 1;
    while (!stack.empty()) {
      const PetscInt c = stack.back();
      stack.pop_back();
      for (PetscInt k = g.graph.xadj[c]; k < g.graph.xadj[c + 1]; k++) {
        const PetscInt e = g.graph.adjncy[k];
        if (!seen[e] && p.part[e] == p.part[c]) {
          seen[e] = 1;
          stack.push_back(e);
        }
      }
    }
  }
  for (PetscInt q = 0; q < p.nparts; q++) TG_CHECK(pieces[q] == 1, "part %" PetscInt_FMT " is %" PetscInt_FMT " disconnected pieces", q, pieces[q]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The graph is symmetric with equal weights both ways and no self loops. */
static PetscErrorCode CheckSymmetric(const CellGraph &g)
{
  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < g.NumCells(); c++)
    for (PetscInt k = g.graph.xadj[c]; k < g.graph.xadj[c + 1]; k++) {
      const PetscInt e = g.graph.adjncy[k];
      TG_CHECK(e != c, "cell %" PetscInt_FMT " is its own neighbour", c);
      bool back = false;
      for (PetscInt l = g.graph.xadj[e]; l < g.graph.xadj[e + 1]; l++) back = back || (g.graph.adjncy[l] == c && g.graph.adjwgt[l] == g.graph.adjwgt[k]);
      TG_CHECK(back, "edge %" PetscInt_FMT " -> %" PetscInt_FMT " has no twin of the same weight", c, e);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void Report(const char *what, const CellGraph &g, const CellPartition &p)
{
  PetscInt lo = PETSC_MAX_INT, hi = 0;
  for (PetscInt m : p.part_particles) lo = std::min(lo, m), hi = std::max(hi, m);
  PetscCallVoid(PetscPrintf(PETSC_COMM_SELF,
                            "%s: %" PetscInt_FMT " cells, %" PetscInt_FMT " graph edges, %" PetscInt_FMT " parts: edge cut %" PetscInt_FMT
                            " walls (%.1f µm), particles per part %" PetscInt_FMT "..%" PetscInt_FMT ", imbalance %.4f, METIS %.2f ms\n",
                            what, g.NumCells(), (PetscInt)g.graph.adjncy.size() / 2, p.nparts, p.edge_cut, (double)p.edge_cut_length, lo, hi,
                            (double)p.imbalance, 1e3 * (double)p.metis_seconds));
}

/* (a) an N x N grid on P parts (P a square: the bound is a sqrt(P) x sqrt(P) split) */
static PetscErrorCode TestSquareGrid(PetscInt N, PetscInt P)
{
  SquareGridSpec spec;
  Tissue         T;
  CellGraph      g;
  CellPartition  p, p2;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = N;
  PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
  PetscCall(BuildCellGraph(PETSC_COMM_SELF, T, &g));
  PetscCall(CheckSymmetric(g));
  /* the grid's 4 neighbours: 2 N (N - 1) shared walls of one cell side each, every particle owned */
  TG_CHECK((PetscInt)g.graph.adjncy.size() == 4 * N * (N - 1), "%zu edge ends, expected %" PetscInt_FMT, g.graph.adjncy.size(), 4 * N * (N - 1));
  for (PetscReal l : g.wall_length) TG_CHECK_CLOSE(l, spec.cell_size, 1e-12, 0, "shared wall length = the cell size");
  TG_CHECK(g.unowned == 0, "%" PetscInt_FMT " particles in no cell", g.unowned);
  PetscInt total = 0;
  for (PetscInt m : g.particles) total += m;
  TG_CHECK(total == T.particles.n, "cells own %" PetscInt_FMT " of %" PetscInt_FMT " particles", total, T.particles.n);

  PetscCall(PartitionCells(PETSC_COMM_SELF, g, P, metis, "-parts", &p));
  char what[64];
  PetscCall(PetscSNPrintf(what, sizeof what, "square grid %" PetscInt_FMT " x %" PetscInt_FMT, N, N));
  Report(what, g, p);
  PetscCall(CheckParts(g, p));
  const PetscInt  k     = (PetscInt)std::lround(std::sqrt((double)P));
  const PetscReal bound = (PetscReal)(k - 1) * 2 * N; /* k - 1 cuts each way, N walls each */
  if (k * k == P) {
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  edge cut / bound of a %" PetscInt_FMT " x %" PetscInt_FMT " split (%g walls) = %.4f\n", k, k, (double)bound,
                          (double)(p.edge_cut / bound)));
    TG_CHECK(p.edge_cut <= 1.10 * bound, "edge cut %" PetscInt_FMT " walls, more than 10%% above the bound %g", p.edge_cut, (double)bound);
  }
  const PetscReal mean = (PetscReal)total / P;
  for (PetscInt q = 0; q < P; q++)
    TG_CHECK(std::fabs(p.part_particles[q] - mean) <= 0.05 * mean, "part %" PetscInt_FMT ": %" PetscInt_FMT " particles, mean %g", q, p.part_particles[q],
             (double)mean);
  /* the same seed gives the same parts */
  PetscCall(PartitionCells(PETSC_COMM_SELF, g, P, metis, "-parts", &p2));
  TG_CHECK(p2.part == p.part, "two partitions with the same seed differ");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (b) a Voronoi tissue on P parts */
static PetscErrorCode TestVoronoi(PetscInt cells, PetscInt P)
{
  VoronoiSpec       spec;
  PolygonTissueSpec poly;
  Tissue            T;
  CellGraph         g;
  CellPartition     p;
  PetscFunctionBeginUser;
  spec.cells  = cells;
  spec.box[2] = spec.box[3] = 25.0 * std::sqrt((double)cells); /* cells of 25 µm on average */
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T));
  PetscCall(BuildCellGraph(PETSC_COMM_SELF, T, &g));
  PetscCall(CheckSymmetric(g));
  /* a planar tiling: about 6 neighbours a cell inside, fewer on the boundary */
  const PetscReal degree = (PetscReal)g.graph.adjncy.size() / g.NumCells();
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "Voronoi %" PetscInt_FMT " cells: mean neighbours %.3f\n", cells, (double)degree));
  TG_CHECK(degree > 5 && degree < 6, "mean neighbours %g of a Voronoi tiling, expected 5..6", (double)degree);
  for (PetscInt c = 0; c < g.NumCells(); c++) TG_CHECK(g.graph.xadj[c + 1] > g.graph.xadj[c], "cell %" PetscInt_FMT " has no neighbour", c);
  TG_CHECK(g.unowned == 0, "%" PetscInt_FMT " particles in no cell", g.unowned);
  PetscCall(PartitionCells(PETSC_COMM_SELF, g, P, metis, "-parts", &p));
  char what[64];
  PetscCall(PetscSNPrintf(what, sizeof what, "Voronoi %" PetscInt_FMT " cells", cells));
  Report(what, g, p);
  PetscCall(CheckParts(g, p));
  TG_CHECK(p.imbalance < 1.05, "imbalance %g", (double)p.imbalance);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* one part (no METIS), and the refusals */
static PetscErrorCode TestEdgeCases()
{
  SquareGridSpec spec;
  Tissue         T;
  CellGraph      g;
  CellPartition  p;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = 3;
  PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
  PetscCall(BuildCellGraph(PETSC_COMM_SELF, T, &g));
  PetscCall(PartitionCells(PETSC_COMM_SELF, g, 1, metis, "-parts", &p));
  TG_CHECK(p.edge_cut == 0 && p.imbalance == 1 && p.metis_seconds == 0, "one part: cut %" PetscInt_FMT ", imbalance %g", p.edge_cut, (double)p.imbalance);
  PetscCall(PartitionCells(PETSC_COMM_SELF, g, 9, metis, "-parts", &p)); /* as many parts as cells: allowed (METIS may leave a part empty) */
  for (PetscInt c = 0; c < 9; c++) TG_CHECK(p.part[c] >= 0 && p.part[c] < 9, "cell %" PetscInt_FMT " in part %" PetscInt_FMT, c, p.part[c]);
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  PetscErrorCode ierr0  = PartitionCells(PETSC_COMM_SELF, g, 0, metis, "-parts", &p);
  PetscErrorCode ierr10 = PartitionCells(PETSC_COMM_SELF, g, 10, metis, "-parts", &p);
  PetscCall(PetscPopErrorHandler());
  TG_CHECK(ierr0 == PETSC_ERR_ARG_OUTOFRANGE && ierr10 == PETSC_ERR_ARG_OUTOFRANGE, "0 and 10 parts of 9 cells must be refused (%d, %d)", (int)ierr0,
           (int)ierr10);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt grid = 64, parts = 4, vcells = 400;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-grid", &grid, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-parts", &parts, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-voronoi_cells", &vcells, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-seed", &metis.seed, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-ncuts", &metis.ncuts, NULL));
  {
    PetscBool contig = PETSC_TRUE;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-contig", &contig, NULL));
    metis.contiguous = contig;
  }
  PetscCall(TestEdgeCases());
  if (grid > 0) PetscCall(TestSquareGrid(grid, parts));
  if (vcells > 0) PetscCall(TestVoronoi(vcells, parts));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_partition: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
