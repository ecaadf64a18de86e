#include <turgor/core/geometry.h>
#include <turgor/particles/polygon_couplings.h>
#include <algorithm>
#include <cmath>

namespace turgor {

CellBox BoxOf(const std::vector<PetscInt> &nodes, const PetscReal *x)
{
  CellBox b;
  for (PetscInt i : nodes)
    for (int d = 0; d < 2; d++) b.lo[d] = std::min(b.lo[d], x[2 * i + d]), b.hi[d] = std::max(b.hi[d], x[2 * i + d]);
  return b;
}

PetscReal BoxGap(const CellBox &a, const CellBox &b, const PetscReal shift[2])
{
  PetscReal g2 = 0;
  for (int d = 0; d < 2; d++) {
    const PetscReal g = std::max((PetscReal)0, std::max(a.lo[d] - (b.hi[d] + shift[d]), (b.lo[d] + shift[d]) - a.hi[d]));
    g2 += g * g;
  }
  return std::sqrt(g2);
}

void PolygonCouplings(const ParticleSet &P, const PetscReal *x, PetscReal reach, const std::function<PetscInt(PetscInt)> &owner,
                      std::vector<std::set<PetscInt>> &adj)
{
  const size_t         C = P.OwnedPolygons(), L = P.polygons.size();
  const PetscReal      zero[2] = {0, 0};
  std::vector<CellBox> box(L);
  adj.assign(P.NumOwned(), {});
  for (size_t c = 0; c < L; c++) box[c] = BoxOf(P.polygons[c].nodes, x);
  /* the cells sorted by their boxes' left edges: a cell's partners are the ones whose left edge is
     below its right edge + reach, found by a bisection (O(L log L + pairs) instead of all L^2 pairs) */
  std::vector<size_t> by_lo(L);
  for (size_t c = 0; c < L; c++) by_lo[c] = c;
  std::sort(by_lo.begin(), by_lo.end(), [&](size_t a, size_t b) { return box[a].lo[0] < box[b].lo[0]; });
  PetscReal widest = 0;
  for (size_t c = 0; c < L; c++) widest = std::max(widest, box[c].hi[0] - box[c].lo[0]);
  for (size_t c = 0; c < C; c++) {
    const std::vector<PetscInt> &nodes = P.polygons[c].nodes;
    for (PetscInt i : nodes) adj[i].insert(nodes.begin(), nodes.end());
    const PetscReal from = box[c].lo[0] - reach - widest, to = box[c].hi[0] + reach;
    auto            first = std::lower_bound(by_lo.begin(), by_lo.end(), from, [&](size_t e, PetscReal v) { return box[e].lo[0] < v; });
    for (auto it = first; it != by_lo.end() && box[*it].lo[0] <= to; ++it) {
      const size_t e = *it;
      if (e == c || BoxGap(box[c], box[e], zero) > reach) continue;
      for (PetscInt s : P.polygons[e].bars) {
        const Spring &b = P.springs[s];
        for (PetscInt p : nodes)
          if (PointSegmentDistance2(&x[2 * p], &x[2 * b.i], &x[2 * b.j]) <= reach * reach)
            for (PetscInt q : {owner(b.i), owner(b.j)}) adj[p].insert(q), adj[q].insert(p);
      }
    }
  }
}

} // namespace turgor
