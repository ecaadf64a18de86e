#pragma once
/* A part of a polygonal tissue (TissueGenerator::GeneratePart) checked against the whole tissue:
   test_tissue (every part, on one rank) and test_node_file_parts (each rank its own, after
   PrepareParts on all ranks). */
#include "test_util.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

/* The part of places [c0, c1) of G's space order (PrepareParts done) against the whole tissue W:
   every node, bar, joint and cell of the part as in W under its numbers, bit for bit; every cell
   whose ring's box comes within `distance` of a cell of the range is there; the CellPlace of every
   cell is a permutation. seen, seen_spring: W's nodes and bars met, marked. */
static inline PetscErrorCode CheckPolygonPart(const turgor::TissueGenerator &G, const turgor::Tissue &W, PetscInt c0, PetscInt c1, PetscReal distance,
                                              std::vector<char> *seen, std::vector<char> *seen_spring)
{
  using namespace turgor;
  const ParticleSet &PW = W.particles;
  const PetscInt     C = G.NumCellsOfParts(), r = c0;
  auto               box_of = [](const Tissue &T, const std::vector<PetscInt> &ring, PetscReal b[4]) {
    b[0] = b[1] = PETSC_MAX_REAL;
    b[2] = b[3] = -PETSC_MAX_REAL;
    for (PetscInt i : ring) {
      b[0] = std::min(b[0], T.X[2 * i]), b[1] = std::min(b[1], T.X[2 * i + 1]);
      b[2] = std::max(b[2], T.X[2 * i]), b[3] = std::max(b[3], T.X[2 * i + 1]);
    }
  };
  PetscFunctionBeginUser;
  TG_CHECK(W.NumCells() == C, "parts: %" PetscInt_FMT " cells, the whole tissue %" PetscInt_FMT, C, W.NumCells());
  std::vector<char> placed(C, 0);
  for (PetscInt c = 0; c < C; c++) {
    const PetscInt k = G.CellPlace(c);
    TG_CHECK(k >= 0 && k < C && !placed[k], "parts: cell %" PetscInt_FMT " at place %" PetscInt_FMT, c, k);
    placed[k] = 1;
  }
  std::vector<std::array<PetscReal, 4>> wbox(C);
  for (PetscInt c = 0; c < C; c++) box_of(W, W.cell_walls[c], wbox[c].data());
  Tissue T;
  PetscCall(G.GeneratePart(PETSC_COMM_SELF, c0, c1, distance, &T));
  const ParticleSet &P = T.particles;
  TG_CHECK(T.lo[0] == W.lo[0] && T.lo[1] == W.lo[1] && T.hi[0] == W.hi[0] && T.hi[1] == W.hi[1] && P.bar_radius == PW.bar_radius,
           "part at place %" PetscInt_FMT ": bounds", r);
  for (PetscInt i = 0; i < P.n; i++) {
    const PetscInt g = P.gid[i];
    TG_CHECK(g >= 0 && g < PW.n && (i == 0 || g > P.gid[i - 1]), "part at place %" PetscInt_FMT ": node %" PetscInt_FMT " numbered %" PetscInt_FMT, r, i, g);
    TG_CHECK(T.X[2 * i] == W.X[2 * g] && T.X[2 * i + 1] == W.X[2 * g + 1] && P.mass[i] == PW.mass[g] && P.kind[i] == PW.kind[g] &&
               T.CellGid(P.node_polygon[i]) == PW.node_polygon[g],
             "part at place %" PetscInt_FMT ": node %" PetscInt_FMT " differs", r, g);
    (*seen)[g] = 1;
  }
  TG_CHECK(P.polygon_gid == T.cell_gid && P.polygons.size() == T.cell_gid.size(), "part at place %" PetscInt_FMT ": polygons", r);
  for (PetscInt c = 0; c < T.NumCells(); c++) {
    const PetscInt g = T.CellGid(c);
    TG_CHECK(c == 0 || g > T.CellGid(c - 1), "part at place %" PetscInt_FMT ": cells not increasing", r);
    TG_CHECK(T.cell_walls[c].size() == W.cell_walls[g].size() && P.polygons[c].open == PW.polygons[g].open &&
               P.polygons[c].bars.size() == PW.polygons[g].bars.size(),
             "part at place %" PetscInt_FMT ": cell %" PetscInt_FMT, r, g);
    for (size_t k = 0; k < T.cell_walls[c].size(); k++)
      TG_CHECK(P.gid[T.cell_walls[c][k]] == W.cell_walls[g][k], "part at place %" PetscInt_FMT ": ring of cell %" PetscInt_FMT, r, g);
    for (size_t k = 0; k < P.polygons[c].bars.size(); k++)
      TG_CHECK(P.SpringGid((size_t)P.polygons[c].bars[k]) == PW.polygons[g].bars[k], "part at place %" PetscInt_FMT ": bars of cell %" PetscInt_FMT, r, g);
  }
  for (PetscInt c = 0; c < C; c++) { /* every cell near the range's (box gaps) is here */
    bool near = false;
    for (PetscInt o = 0; o < C && !near; o++) {
      if (G.CellPlace(o) < c0 || G.CellPlace(o) >= c1) continue;
      const PetscReal dx = std::max((PetscReal)0, std::max(wbox[c][0] - wbox[o][2], wbox[o][0] - wbox[c][2]));
      const PetscReal dy = std::max((PetscReal)0, std::max(wbox[c][1] - wbox[o][3], wbox[o][1] - wbox[c][3]));
      near               = std::hypot(dx, dy) <= distance;
    }
    if (near) TG_CHECK(std::binary_search(T.cell_gid.begin(), T.cell_gid.end(), c), "part at place %" PetscInt_FMT ": cell %" PetscInt_FMT " missing", r, c);
  }
  for (size_t q = 0; q < P.springs.size(); q++) {
    const Spring  &a = P.springs[q];
    const PetscInt g = P.spring_gid[q];
    TG_CHECK(g >= 0 && g < (PetscInt)PW.springs.size() && (q == 0 || g > P.spring_gid[q - 1]), "part at place %" PetscInt_FMT ": bar numbered %" PetscInt_FMT,
             r, g);
    const Spring &b = PW.springs[g];
    TG_CHECK(P.gid[a.i] == b.i && P.gid[a.j] == b.j && a.rest_length == b.rest_length, "part at place %" PetscInt_FMT ": bar %" PetscInt_FMT " differs", r, g);
    for (int e = 0; e < 2; e++) {
      const PetscInt j = a.joint[e] < 0 ? -1 : 2 * P.spring_gid[a.joint[e] / 2] + a.joint[e] % 2;
      TG_CHECK(j == b.joint[e], "part at place %" PetscInt_FMT ": joint %d of bar %" PetscInt_FMT, r, e, g);
    }
    (*seen_spring)[g] = 1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
