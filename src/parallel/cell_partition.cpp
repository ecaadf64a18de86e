#include <turgor/parallel/cell_partition.h>
#include <turgor/core/geometry.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace turgor {

static bool IsPolygonal(const Tissue &tissue)
{
  return !tissue.particles.polygons.empty();
}

static PetscInt CellCount(const Tissue &tissue)
{
  return IsPolygonal(tissue) ? (PetscInt)tissue.particles.polygons.size() : tissue.NumCells();
}

void OwnerCells(const Tissue &tissue, std::vector<PetscInt> *owner)
{
  const ParticleSet &P = tissue.particles;
  owner->assign((size_t)P.n, -1);
  if (!IsPolygonal(tissue)) /* shared wall particles: the lowest numbered cell (cells in increasing order) */
    for (PetscInt c = tissue.NumCells() - 1; c >= 0; c--)
      for (PetscInt i : tissue.cell_walls[c]) (*owner)[i] = c;
  for (PetscInt i = 0; i < P.n; i++) {
    if (!P.node_polygon.empty() && P.node_polygon[i] >= 0) (*owner)[i] = P.node_polygon[i];
    if (P.kind[i] == KIND_FLUID && P.cell[i] >= 0) { /* ParticleSet::cell is the whole tissue's number */
      if (tissue.cell_gid.empty()) (*owner)[i] = P.cell[i];
      else {
        auto it     = std::lower_bound(tissue.cell_gid.begin(), tissue.cell_gid.end(), P.cell[i]);
        (*owner)[i] = it != tissue.cell_gid.end() && *it == P.cell[i] ? (PetscInt)(it - tissue.cell_gid.begin()) : -1;
      }
    }
  }
}

/* Shared wall length between cells a < b. */
using PairLengths = std::map<std::pair<PetscInt, PetscInt>, PetscReal>;

/* Square grid: segments (consecutive ring points) that belong to two cells. */
static void SharedSegments(const Tissue &tissue, PairLengths *shared)
{
  std::unordered_map<long long, PetscInt> first; /* segment key -> first cell seen */
  const PetscInt                          n = tissue.particles.n;
  for (PetscInt c = 0; c < tissue.NumCells(); c++) {
    const std::vector<PetscInt> &ring = tissue.cell_walls[c];
    const size_t                 m    = ring.size();
    for (size_t k = 0; m > 1 && k < m; k++) {
      const PetscInt  i = ring[k], j = ring[(k + 1) % m];
      const long long key = (long long)std::min(i, j) * n + std::max(i, j);
      auto            it  = first.find(key);
      if (it == first.end()) {
        first.emplace(key, c);
        continue;
      }
      if (it->second == c) continue;
      const PetscReal dx = tissue.X[2 * i] - tissue.X[2 * j], dy = tissue.X[2 * i + 1] - tissue.X[2 * j + 1];
      (*shared)[{std::min(it->second, c), std::max(it->second, c)}] += std::sqrt(dx * dx + dy * dy);
    }
  }
}

/* Polygonal tissues: bars of different cells within 3 r of each other (see cell_partition.h). */
static void NearbyBars(const Tissue &tissue, PairLengths *shared)
{
  const ParticleSet &P       = tissue.particles;
  const PetscInt     samples = 4;
  struct Bar {
    PetscInt  cell;
    PetscReal a[2], b[2], length;
  };
  std::vector<Bar> bars;
  PetscReal        total = 0;
  for (PetscInt c = 0; c < (PetscInt)P.polygons.size(); c++)
    for (PetscInt s : P.polygons[c].bars) {
      const Spring &sp = P.springs[s];
      Bar           bar{
        c, {tissue.X[2 * sp.i], tissue.X[2 * sp.i + 1]},
         {tissue.X[2 * sp.j], tissue.X[2 * sp.j + 1]},
         0
      };
      bar.length = std::hypot(bar.b[0] - bar.a[0], bar.b[1] - bar.a[1]);
      total += bar.length;
      bars.push_back(bar);
    }
  if (bars.empty()) return;
  const PetscReal mean = total / (PetscReal)bars.size();
  const PetscReal d    = P.bar_radius > 0 ? 3 * P.bar_radius : 1e-3 * mean;
  /* a grid of the bars' bounding boxes grown by d, cells of about a bar's length (at most ~4 grid
     cells per bar overall) */
  const PetscReal lx = tissue.hi[0] - tissue.lo[0] + 2 * d, ly = tissue.hi[1] - tissue.lo[1] + 2 * d;
  PetscReal       h = std::max(mean, d);
  while ((lx / h + 1) * (ly / h + 1) > 4.0 * (PetscReal)bars.size() + 16) h *= 1.5;
  const PetscInt                     gx = (PetscInt)(lx / h) + 1, gy = (PetscInt)(ly / h) + 1;
  std::vector<std::vector<PetscInt>> grid((size_t)gx * gy);
  auto                               ix = [&](PetscReal x) { return std::min(gx - 1, std::max((PetscInt)0, (PetscInt)((x - tissue.lo[0] + d) / h))); };
  auto                               iy = [&](PetscReal y) { return std::min(gy - 1, std::max((PetscInt)0, (PetscInt)((y - tissue.lo[1] + d) / h))); };
  for (PetscInt k = 0; k < (PetscInt)bars.size(); k++) {
    const Bar &B = bars[k];
    for (PetscInt y = iy(std::min(B.a[1], B.b[1]) - d); y <= iy(std::max(B.a[1], B.b[1]) + d); y++)
      for (PetscInt x = ix(std::min(B.a[0], B.b[0]) - d); x <= ix(std::max(B.a[0], B.b[0]) + d); x++) grid[(size_t)y * gx + x].push_back(k);
  }
  std::map<std::pair<PetscInt, PetscInt>, PetscReal> oneway; /* (this cell, other cell) -> this cell's bar length near the other */
  std::vector<PetscInt>                              near;
  for (const Bar &A : bars)
    for (PetscInt s = 0; s < samples; s++) {
      const PetscReal t = (s + 0.5) / samples, p[2] = {A.a[0] + t * (A.b[0] - A.a[0]), A.a[1] + t * (A.b[1] - A.a[1])};
      near.clear();
      for (PetscInt k : grid[(size_t)iy(p[1]) * gx + ix(p[0])]) { /* every bar within d of p is in p's grid cell */
        const Bar &B = bars[k];
        if (B.cell == A.cell || std::find(near.begin(), near.end(), B.cell) != near.end()) continue;
        if (std::sqrt(PointSegmentDistance2(p, B.a, B.b)) <= d) near.push_back(B.cell);
      }
      for (PetscInt c : near) oneway[{A.cell, c}] += A.length / samples;
    }
  for (const auto &kv : oneway) (*shared)[{std::min(kv.first.first, kv.first.second), std::max(kv.first.first, kv.first.second)}] += 0.5 * kv.second;
}

PetscErrorCode BuildCellGraph(MPI_Comm comm, const Tissue &tissue, CellGraph *g)
{
  const PetscInt ncells = CellCount(tissue);
  PairLengths    shared;
  PetscFunctionBeginUser;
  *g = CellGraph();
  PetscCheck(tissue.period[0] == 0 && tissue.period[1] == 0, comm, PETSC_ERR_SUP, "Cell partition: periodic tissues (RVEs) are not partitioned");
  if (IsPolygonal(tissue)) NearbyBars(tissue, &shared);
  else SharedSegments(tissue, &shared);

  /* vertex weights: the particles each cell owns */
  std::vector<PetscInt> owner;
  OwnerCells(tissue, &owner);
  g->particles.assign((size_t)ncells, 0);
  for (PetscInt o : owner) {
    if (o >= 0 && o < ncells) g->particles[o]++;
    else g->unowned++;
  }
  g->graph.vwgt.resize((size_t)ncells);
  for (PetscInt c = 0; c < ncells; c++) g->graph.vwgt[c] = std::max((PetscInt)1, g->particles[c]);

  /* edges both ways, weights in units of a hundredth of the mean shared length */
  PetscReal sum = 0;
  for (const auto &kv : shared) sum += kv.second;
  g->length_unit = shared.empty() ? 1 : sum / (PetscReal)shared.size() / 100;
  std::vector<std::vector<std::pair<PetscInt, PetscReal>>> adj((size_t)ncells);
  for (const auto &kv : shared) {
    adj[kv.first.first].push_back({kv.first.second, kv.second});
    adj[kv.first.second].push_back({kv.first.first, kv.second});
  }
  g->graph.xadj.assign(1, 0);
  for (PetscInt c = 0; c < ncells; c++) {
    std::sort(adj[c].begin(), adj[c].end());
    for (const auto &e : adj[c]) {
      g->graph.adjncy.push_back(e.first);
      g->graph.adjwgt.push_back(std::max((PetscInt)1, (PetscInt)std::lround(e.second / g->length_unit)));
      g->wall_length.push_back(e.second);
    }
    g->graph.xadj.push_back((PetscInt)g->graph.adjncy.size());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void PartitionStatistics(const CellGraph &g, CellPartition *p)
{
  const PetscInt n   = g.NumCells();
  p->edge_cut        = 0;
  p->edge_cut_length = 0;
  p->part_particles.assign((size_t)p->nparts, 0);
  for (PetscInt c = 0; c < n; c++) {
    p->part_particles[p->part[c]] += g.particles[c];
    for (PetscInt k = g.graph.xadj[c]; k < g.graph.xadj[c + 1]; k++)
      if (g.graph.adjncy[k] > c && p->part[g.graph.adjncy[k]] != p->part[c]) {
        p->edge_cut++;
        p->edge_cut_length += g.wall_length[k];
      }
  }
  PetscInt total = 0, most = 0;
  for (PetscInt m : p->part_particles) total += m, most = std::max(most, m);
  p->imbalance = total > 0 ? (PetscReal)most * p->nparts / (PetscReal)total : 1;
}

PetscErrorCode PartitionCells(MPI_Comm comm, const CellGraph &g, PetscInt nparts, const MetisOptions &opt, const char *option, CellPartition *p)
{
  PetscFunctionBeginUser;
  *p        = CellPartition();
  p->nparts = nparts;
  PetscCall(MetisPartGraphKway(comm, g.graph, nparts, opt, option, &p->part, &p->metis_objval, &p->metis_seconds));
  PartitionStatistics(g, p);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void ParticleParts(const Tissue &tissue, const CellPartition &partition, std::vector<PetscInt> *part)
{
  std::vector<PetscInt> owner;
  OwnerCells(tissue, &owner);
  part->assign(owner.size(), -1);
  for (size_t i = 0; i < owner.size(); i++)
    if (owner[i] >= 0 && owner[i] < (PetscInt)partition.part.size()) (*part)[i] = partition.part[owner[i]];
}

} // namespace turgor
