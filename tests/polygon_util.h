#pragma once
/* Polygonal tissues built by hand for the polygon force tests and benchmark (the generators of
   src/tissue/ are separate): cells of nodes and bars in a Tissue, with ParticleSet::polygons,
   node_polygon and bar_radius filled as the generators fill them. */
#include <turgor/turgor.hpp>
#include <turgor/physics/force_model.h>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace turgor_test {

struct PolygonBuilder {
  turgor::Tissue                   T;
  std::vector<turgor::PolygonCell> cells;
  /* A cell through the points (closed cells counter-clockwise); bars join consecutive points (and
     the last to the first unless open), rest lengths from these positions. Returns its index. */
  PetscInt AddCell(const std::vector<std::array<PetscReal, 2>> &pts, bool open, PetscReal mass)
  {
    turgor::PolygonCell c;
    c.open = open;
    for (const auto &q : pts) c.nodes.push_back(T.AddParticle(q[0], q[1], mass, turgor::KIND_WALL));
    const size_t N = c.nodes.size();
    for (size_t k = 0; k + (open ? 1 : 0) < N && N > 1; k++) {
      c.bars.push_back((PetscInt)T.particles.springs.size());
      T.AddSpring(c.nodes[k], c.nodes[(k + 1) % N]);
    }
    cells.push_back(c);
    return (PetscInt)cells.size() - 1;
  }
  /* Regular N-gon of circumradius R centred at (cx, cy), counter-clockwise. */
  PetscInt AddRegular(PetscInt N, PetscReal R, PetscReal cx, PetscReal cy, PetscReal mass, PetscReal phase = 0)
  {
    std::vector<std::array<PetscReal, 2>> pts;
    for (PetscInt k = 0; k < N; k++) pts.push_back({cx + R * std::cos(phase + 2 * PETSC_PI * k / N), cy + R * std::sin(phase + 2 * PETSC_PI * k / N)});
    return AddCell(pts, false, mass);
  }
  turgor::Tissue &Finish(PetscReal bar_radius)
  {
    T.Finalize();
    turgor::ParticleSet &P = T.particles;
    P.polygons             = cells;
    P.node_polygon.assign(P.n, -1);
    for (size_t c = 0; c < cells.size(); c++)
      for (PetscInt i : cells[c].nodes) P.node_polygon[i] = (PetscInt)c;
    P.bar_radius = bar_radius;
    return T;
  }
};

/* nx x ny jittered hexagons on a triangular lattice of spacing D (flat sides facing the neighbours,
   shrunk by r so that neighbours are 2 r apart, nodes then pulled towards their centre by 0.05 (1 +
   rnd()) µm, rnd() in [-1, 1): the jitter is part of the reference geometry), node mass m.
   Benchmark and tests share it. */
template <class Random>
inline turgor::Tissue &HexagonTissue(PolygonBuilder &B, PetscInt nx, PetscInt ny, PetscReal D, PetscReal r, PetscReal m, Random &rnd)
{
  const PetscReal apo = 0.5 * D - r, R = apo / std::cos(PETSC_PI / 6);
  for (PetscInt j = 0; j < ny; j++)
    for (PetscInt i = 0; i < nx; i++) {
      std::vector<std::array<PetscReal, 2>> pts;
      const PetscReal                       cx = D * (i + 0.5 * (j % 2)), cy = D * std::sqrt(3.0) / 2 * j;
      for (int k = 0; k < 6; k++) {
        const PetscReal phi = PETSC_PI / 6 + PETSC_PI * k / 3;
        const PetscReal Rk  = R - 0.05 * (1 + rnd());
        pts.push_back({cx + Rk * std::cos(phi), cy + Rk * std::sin(phi)});
      }
      B.AddCell(pts, false, m);
    }
  return B.Finish(r);
}

/* A ForceModel with exactly these configured terms (no options read). */
inline PetscErrorCode MakeModel(const turgor::ParticleSet &P, std::vector<std::unique_ptr<turgor::ForceTerm>> terms, turgor::ForceModel &M,
                                PetscReal skin = 1.0)
{
  turgor::PhysicsSpec spec;
  PetscFunctionBeginUser;
  spec.names          = {};
  spec.neighbour_skin = skin;
  for (auto &t : terms) spec.Add(std::move(t));
  PetscCall(M.SetUp(spec, P));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor_test
