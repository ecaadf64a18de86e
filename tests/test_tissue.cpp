static const char help[] = "Tissue generator: particle and spring counts, cell polygons, clamps.\n";
#include "test_util.h"
#include "tissue_parts_util.h"
#include <turgor/tissue/node_file.h>
#include <turgor/tissue/voronoi.h>
#include <cstdio>
#include <algorithm>
#include <array>
#include <cmath>

using namespace turgor;

/* The parts of a polygonal tissue G (PrepareParts done) dealt in `parts` ranges of its space order,
   each against the whole tissue W (CheckPolygonPart); the parts cover W. */
static PetscErrorCode CheckPolygonParts(const TissueGenerator &G, const Tissue &W, PetscInt parts, PetscReal distance)
{
  const PetscInt    C = G.NumCellsOfParts();
  std::vector<char> seen(W.particles.n, 0), seen_spring(W.particles.springs.size(), 0);
  PetscFunctionBeginUser;
  for (PetscInt r = 0; r < parts; r++) PetscCall(CheckPolygonPart(G, W, r * C / parts, (r + 1) * C / parts, distance, &seen, &seen_spring));
  for (PetscInt g = 0; g < W.particles.n; g++) TG_CHECK(seen[g], "%" PetscInt_FMT " cells: node %" PetscInt_FMT " in no part", C, g);
  for (size_t g = 0; g < W.particles.springs.size(); g++) TG_CHECK(seen_spring[g], "%" PetscInt_FMT " cells: bar %zu in no part", C, g);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  {
    /* the seed's 16 x 16 tissue: 833 wall and 4096 SPH particles (TW 562 Fig. 2) */
    SquareGridSpec spec;
    Tissue         T;
    PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
    const ParticleSet &P = T.particles;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "16x16: %" PetscInt_FMT " wall, %" PetscInt_FMT " fluid, %zu springs\n", P.Count(KIND_WALL), P.Count(KIND_FLUID),
                          P.springs.size()));
    TG_CHECK(P.Count(KIND_WALL) == 833, "wall particles %" PetscInt_FMT, P.Count(KIND_WALL));
    TG_CHECK(P.Count(KIND_FLUID) == 4096, "fluid particles %" PetscInt_FMT, P.Count(KIND_FLUID));
    TG_CHECK(P.springs.size() == 1088, "springs %zu", P.springs.size());
    TG_CHECK(T.NumCells() == 256, "cells");
    /* every cell: 8 wall particles, area 625 µm², springs of rest length 12.5 µm */
    for (PetscInt c = 0; c < T.NumCells(); c++) {
      TG_CHECK(T.cell_walls[c].size() == 8, "cell %" PetscInt_FMT " ring", c);
      TG_CHECK_CLOSE(PolygonArea(T.cell_walls[c], T.X.data()), 625.0, 1e-12, 1.0, "cell area");
    }
    for (const Spring &s : P.springs) TG_CHECK_CLOSE(s.rest_length, 12.5, 1e-12, 1.0, "rest length");
    /* fluid mass from 2D density: 0.01 ng/µm² x 625 µm² / 16 */
    for (PetscInt i = 0; i < P.n; i++) TG_CHECK_CLOSE(P.mass[i], P.kind[i] == KIND_FLUID ? 0.390625 : 0.5, 1e-14, 1.0, "particle mass");
    /* each fluid particle lies inside its own cell */
    for (PetscInt i = 0; i < P.n; i++) {
      if (P.kind[i] != KIND_FLUID) continue;
      const PetscInt cx = P.cell[i] % 16, cy = P.cell[i] / 16;
      TG_CHECK(T.X[2 * i] > 25 * cx && T.X[2 * i] < 25 * (cx + 1) && T.X[2 * i + 1] > 25 * cy && T.X[2 * i + 1] < 25 * (cy + 1),
               "fluid particle %" PetscInt_FMT " outside its cell", i);
    }
    /* left clamp: the 33 wall particles at x = 0; the tip is the wall particle at (400, 200) */
    PetscCall(T.Clamp(PETSC_COMM_SELF, {"left"}, "-fine_clamp"));
    PetscInt nfixed = 0;
    for (char f : P.fixed) nfixed += f;
    TG_CHECK(nfixed == 33, "clamped %" PetscInt_FMT, nfixed);
    const PetscInt tip = T.ClosestWallParticle(400, 200);
    TG_CHECK(T.X[2 * tip] == 400 && T.X[2 * tip + 1] == 200, "tip particle");
  }
  {
    /* general counts: corners (nx+1)(ny+1) + (s-1) per wall segment */
    SquareGridSpec spec;
    spec.cells_x          = 5;
    spec.cells_y          = 3;
    spec.springs_per_side = 4;
    spec.fluid_per_cell   = 9;
    Tissue T;
    PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
    const PetscInt walls = 6 * 4 + 3 * (5 * 4 + 6 * 3);
    TG_CHECK(T.particles.Count(KIND_WALL) == walls, "5x3, s=4: %" PetscInt_FMT " wall particles, expected %" PetscInt_FMT, T.particles.Count(KIND_WALL), walls);
    TG_CHECK(T.particles.Count(KIND_FLUID) == 15 * 9, "5x3 fluid");
    TG_CHECK(T.particles.springs.size() == (size_t)(4 * (5 * 4 + 6 * 3)), "5x3 springs");
  }
  {
    /* Parts of a grid (distributed set-up): every particle, spring and cell as in the whole grid under
       the whole grid's numbers; every cell within the distance there, with the joints of its springs;
       the parts of a partition cover the whole grid */
    struct Case {
      PetscInt  nx, ny, s, k, parts;
      PetscReal distance;
    };
    const Case cases[] = {
      {5, 7, 2, 4, 3, 30.0},
      {4, 9, 3, 1, 4, 0.0 },
      {6, 5, 1, 9, 2, 60.0},
      {3, 4, 2, 0, 5, 10.0},
    };
    for (const Case &cs : cases) {
      SquareGridSpec spec;
      spec.cells_x          = cs.nx;
      spec.cells_y          = cs.ny;
      spec.springs_per_side = cs.s;
      spec.fluid_per_cell   = cs.k;
      Tissue W;
      PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &W));
      const ParticleSet    &PW = W.particles;
      const PetscInt        C  = cs.nx * cs.ny;
      std::vector<char>     seen(PW.n, 0), seen_spring(PW.springs.size(), 0);
      std::vector<PetscInt> wring; /* a whole cell's ring */
      for (PetscInt r = 0; r < cs.parts; r++) {
        const PetscInt c0 = r * C / cs.parts, c1 = (r + 1) * C / cs.parts;
        Tissue         T;
        PetscCall(GenerateSquareGridPart(PETSC_COMM_SELF, spec, c0, c1, cs.distance, &T));
        const ParticleSet &P = T.particles;
        TG_CHECK(T.lo[0] == W.lo[0] && T.lo[1] == W.lo[1] && T.hi[0] == W.hi[0] && T.hi[1] == W.hi[1], "part %" PetscInt_FMT ": bounds", r);
        for (PetscInt i = 0; i < P.n; i++) {
          const PetscInt g = P.gid[i];
          TG_CHECK(g >= 0 && g < PW.n && (i == 0 || g > P.gid[i - 1]), "part %" PetscInt_FMT ": particle %" PetscInt_FMT " numbered %" PetscInt_FMT, r, i, g);
          TG_CHECK(T.X[2 * i] == W.X[2 * g] && T.X[2 * i + 1] == W.X[2 * g + 1] && P.mass[i] == PW.mass[g] && P.kind[i] == PW.kind[g] &&
                     P.cell[i] == PW.cell[g],
                   "part %" PetscInt_FMT ": particle %" PetscInt_FMT " differs", r, g);
          seen[g] = 1;
        }
        /* the cells: [c0, c1) and all within the distance (boxes of the rings) */
        auto gap = [&](PetscInt a, PetscInt b) {
          const PetscInt ax = a % cs.nx, ay = a / cs.nx, bx = b % cs.nx, by = b / cs.nx;
          const PetscInt dx = std::max((PetscInt)0, std::abs(ax - bx) - 1), dy = std::max((PetscInt)0, std::abs(ay - by) - 1);
          return spec.cell_size * std::hypot((PetscReal)dx, (PetscReal)dy);
        };
        std::vector<char> near(C, 0);
        for (PetscInt c = 0; c < C; c++)
          for (PetscInt o = c0; o < c1 && !near[c]; o++) near[c] = gap(c, o) <= cs.distance;
        for (PetscInt c = 0; c < C; c++)
          if (near[c]) TG_CHECK(std::binary_search(T.cell_gid.begin(), T.cell_gid.end(), c), "part %" PetscInt_FMT ": cell %" PetscInt_FMT " missing", r, c);
        for (PetscInt c = 0; c < T.NumCells(); c++) {
          const PetscInt g = T.CellGid(c);
          TG_CHECK(c == 0 || g > T.CellGid(c - 1), "part %" PetscInt_FMT ": cells not increasing", r);
          TG_CHECK(T.cell_walls[c].size() == W.cell_walls[g].size(), "part %" PetscInt_FMT ": ring of cell %" PetscInt_FMT, r, g);
          for (size_t k = 0; k < T.cell_walls[c].size(); k++)
            TG_CHECK(P.gid[T.cell_walls[c][k]] == W.cell_walls[g][k], "part %" PetscInt_FMT ": ring of cell %" PetscInt_FMT, r, g);
        }
        /* springs; joints where both ends are on the ring of a cell within the distance */
        std::vector<char> on_near(P.n, 0);
        for (PetscInt c = 0; c < T.NumCells(); c++)
          if (near[T.CellGid(c)])
            for (PetscInt i : T.cell_walls[c]) on_near[i] = 1;
        for (size_t q = 0; q < P.springs.size(); q++) {
          const Spring  &a = P.springs[q];
          const PetscInt g = P.spring_gid[q];
          TG_CHECK(g >= 0 && g < (PetscInt)PW.springs.size() && (q == 0 || g > P.spring_gid[q - 1]), "part %" PetscInt_FMT ": spring numbered %" PetscInt_FMT,
                   r, g);
          const Spring &b = PW.springs[g];
          TG_CHECK(P.gid[a.i] == b.i && P.gid[a.j] == b.j && a.rest_length == b.rest_length, "part %" PetscInt_FMT ": spring %" PetscInt_FMT " differs", r, g);
          seen_spring[g] = 1;
          if (!on_near[a.i] || !on_near[a.j]) continue;
          for (int e = 0; e < 2; e++) {
            const PetscInt j = a.joint[e] < 0 ? -1 : 2 * P.spring_gid[a.joint[e] / 2] + a.joint[e] % 2;
            TG_CHECK(j == b.joint[e], "part %" PetscInt_FMT ": joint %d of spring %" PetscInt_FMT ": %" PetscInt_FMT " vs %" PetscInt_FMT, r, e, g, j,
                     b.joint[e]);
          }
        }
      }
      for (PetscInt g = 0; g < PW.n; g++) TG_CHECK(seen[g], "%" PetscInt_FMT " x %" PetscInt_FMT ": particle %" PetscInt_FMT " in no part", cs.nx, cs.ny, g);
      for (size_t g = 0; g < PW.springs.size(); g++) TG_CHECK(seen_spring[g], "%" PetscInt_FMT " x %" PetscInt_FMT ": spring %zu in no part", cs.nx, cs.ny, g);
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "parts of %" PetscInt_FMT " x %" PetscInt_FMT " (s %" PetscInt_FMT ", %" PetscInt_FMT " ranges, %g µm): as in the whole grid\n",
                            cs.nx, cs.ny, cs.s, cs.parts, (double)cs.distance));
    }
  }
  {
    /* Parts of a Voronoi tissue (distributed set-up): the Hilbert order of the seeds dealt in ranges,
       each part as in the whole tissue (CheckPolygonParts). Lloyd steps, Laguerre weights, a gap,
       subdivided and whole edges. */
    struct Case {
      PetscInt  cells, lloyd, parts;
      PetscReal size_cv, gap, bar_length, distance;
    };
    const Case cases[] = {
      {60, 2, 3, 0.0, 0.05, 3.0, 20.0},
      {40, 0, 5, 0.3, 0.0,  0.0, 0.0 },
      {25, 1, 4, 0.0, 0.0,  5.0, 60.0},
    };
    for (const Case &cs : cases) {
      VoronoiGenerator G;
      G.spec.cells       = cs.cells;
      G.spec.box[2]      = 200;
      G.spec.box[3]      = 150;
      G.spec.seed        = 3;
      G.spec.lloyd_steps = cs.lloyd;
      G.spec.size_cv     = cs.size_cv;
      G.spec.gap         = cs.gap;
      G.poly.bar_length  = cs.bar_length;
      Tissue W;
      PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, G.spec, G.poly, &W));
      PetscCall(G.PrepareParts(PETSC_COMM_SELF));
      PetscCall(CheckPolygonParts(G, W, cs.parts, cs.distance));
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "parts of a Voronoi tissue of %" PetscInt_FMT " cells (%" PetscInt_FMT " Lloyd steps, cv %g, %" PetscInt_FMT
                            " ranges, %g µm): as in the whole tissue\n",
                            cs.cells, cs.lloyd, (double)cs.size_cv, cs.parts, (double)cs.distance));
    }
  }
  {
    /* Parts of a node file (read by seeking to each cell): a 48-cell Voronoi tissue written with
       comments, blank lines, clockwise cells (reversed when read), ids from 7 and an open cell; each
       part as the whole file's tissue (CheckPolygonParts). The file is the fixture of the runs in
       parts on several ranks (tests/distributed.cmake). */
    VoronoiSpec       vs;
    PolygonTissueSpec vp;
    vs.cells       = 48;
    vs.box[2]      = 300;
    vs.box[3]      = 100;
    vs.lloyd_steps = 2;
    vs.gap         = 0.05;
    Tissue V;
    PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, vs, vp, &V));
    FILE *f = std::fopen("parts_tissue.nodes", "w");
    TG_CHECK(f, "cannot write parts_tissue.nodes");
    std::fprintf(f, "# 48 Voronoi cells in 300 x 100 µm (test_tissue): x y cellId\n");
    for (size_t c = 0; c < V.particles.polygons.size(); c++) {
      std::vector<PetscInt> ring = V.particles.polygons[c].nodes;
      if (c % 3 == 1) std::reverse(ring.begin() + 1, ring.end()); /* clockwise, from the same first node */
      if (c % 5 == 2) std::fprintf(f, "\n# cell %zu\n", c + 7);
      for (PetscInt i : ring) std::fprintf(f, "%.17g %.17g %zu\n", (double)V.X[2 * i], (double)V.X[2 * i + 1], c + 7);
    }
    TG_CHECK(std::fclose(f) == 0, "cannot write parts_tissue.nodes");
    for (PetscReal h : {0.0, 2.5}) {
      NodeFileGenerator G;
      G.spec.path       = "parts_tissue.nodes";
      G.spec.open_cells = {12};
      G.poly.bar_length = h;
      Tissue W;
      PetscCall(GenerateNodeFileTissue(PETSC_COMM_SELF, G.spec, G.poly, &W));
      TG_CHECK(G.NumCellsOfParts() == 0, "a node file's cells before PrepareParts");
      PetscCall(G.PrepareParts(PETSC_COMM_SELF));
      TG_CHECK(W.particles.polygons[5].open && G.NumCellsOfParts() == 48, "node file parts: 48 cells, cell 12 open");
      for (PetscInt parts : {2, 5}) PetscCall(CheckPolygonParts(G, W, parts, parts == 2 ? 0.0 : 15.0));
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "parts of a node file of 48 cells (bar length %g µm): as in the whole tissue\n", (double)h));
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_tissue: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
