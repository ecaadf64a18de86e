#include <turgor/parallel/tissue_distribution.h>
#include <turgor/parallel/cell_partition.h>
#include <algorithm>
#include <cmath>
#include <map>

namespace turgor {

namespace {
struct Box {
  PetscReal lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
  void      Add(const PetscReal *p)
  {
    for (int d = 0; d < 2; d++) lo[d] = std::min(lo[d], p[d]), hi[d] = std::max(hi[d], p[d]);
  }
};

PetscReal BoxDistance(const Box &a, const Box &b)
{
  const PetscReal dx = std::max((PetscReal)0, std::max(a.lo[0] - b.hi[0], b.lo[0] - a.hi[0]));
  const PetscReal dy = std::max((PetscReal)0, std::max(a.lo[1] - b.hi[1], b.lo[1] - a.hi[1]));
  return std::sqrt(dx * dx + dy * dy);
}

/* For every target box the distance to the nearest query box, or `cap` where none is nearer: the
   query boxes grown by cap in a uniform grid of about their size (a plate spans many bins). */
void NearestDistances(const std::vector<Box> &query, const std::vector<Box> &target, PetscReal cap, std::vector<PetscReal> *dist)
{
  dist->assign(target.size(), cap);
  if (query.empty() || target.empty()) return;
  Box       all;
  PetscReal extent = 0;
  for (const Box &q : query) {
    all.Add(q.lo), all.Add(q.hi);
    extent += (q.hi[0] - q.lo[0]) + (q.hi[1] - q.lo[1]);
  }
  for (int d = 0; d < 2; d++) all.lo[d] -= cap, all.hi[d] += cap;
  PetscReal h = std::max({extent / (2 * query.size()), cap, (PetscReal)1e-9 * (all.hi[0] - all.lo[0] + all.hi[1] - all.lo[1] + 1)});
  while (((all.hi[0] - all.lo[0]) / h + 1) * ((all.hi[1] - all.lo[1]) / h + 1) > 4.0 * query.size() + 64) h *= 1.5;
  const PetscInt                     gx = (PetscInt)((all.hi[0] - all.lo[0]) / h) + 1, gy = (PetscInt)((all.hi[1] - all.lo[1]) / h) + 1;
  std::vector<std::vector<PetscInt>> bins((size_t)gx * gy);
  auto                               ix = [&](PetscReal x) { return std::min(gx - 1, std::max((PetscInt)0, (PetscInt)std::floor((x - all.lo[0]) / h))); };
  auto                               iy = [&](PetscReal y) { return std::min(gy - 1, std::max((PetscInt)0, (PetscInt)std::floor((y - all.lo[1]) / h))); };
  for (size_t k = 0; k < query.size(); k++)
    for (PetscInt y = iy(query[k].lo[1] - cap); y <= iy(query[k].hi[1] + cap); y++)
      for (PetscInt x = ix(query[k].lo[0] - cap); x <= ix(query[k].hi[0] + cap); x++) bins[(size_t)y * gx + x].push_back((PetscInt)k);
  for (size_t t = 0; t < target.size(); t++) {
    const Box &T = target[t];
    if (T.hi[0] < all.lo[0] || T.lo[0] > all.hi[0] || T.hi[1] < all.lo[1] || T.lo[1] > all.hi[1]) continue;
    PetscReal best = cap;
    for (PetscInt y = iy(T.lo[1]); y <= iy(T.hi[1]); y++)
      for (PetscInt x = ix(T.lo[0]); x <= ix(T.hi[0]); x++)
        for (PetscInt k : bins[(size_t)y * gx + x]) best = std::min(best, BoxDistance(query[k], T));
    (*dist)[t] = best;
  }
}
/* Messages of one tag on comm, all in flight at once: to_data[i] to rank to[i], from_data[i] (sized
   by the caller) from rank from[i]. */
template <class T>
PetscErrorCode ExchangeKnown(MPI_Comm comm, PetscMPIInt tag, MPI_Datatype type, const std::vector<PetscMPIInt> &to, std::vector<std::vector<T>> &to_data,
                             const std::vector<PetscMPIInt> &from, std::vector<std::vector<T>> &from_data)
{
  std::vector<MPI_Request> req(from.size() + to.size());
  PetscFunctionBeginUser;
  for (size_t i = 0; i < from.size(); i++) PetscCallMPI(MPI_Irecv(from_data[i].data(), (PetscMPIInt)from_data[i].size(), type, from[i], tag, comm, &req[i]));
  for (size_t i = 0; i < to.size(); i++)
    PetscCallMPI(MPI_Isend(to_data[i].data(), (PetscMPIInt)to_data[i].size(), type, to[i], tag, comm, &req[from.size() + i]));
  PetscCallMPI(MPI_Waitall((PetscMPIInt)req.size(), req.data(), MPI_STATUSES_IGNORE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The same where a rank does not know who sends to it: PetscCommBuildTwoSided finds its senders
   and their counts (neighbours only, no all-to-all of every rank's counts). */
template <class T>
PetscErrorCode ExchangeFound(MPI_Comm comm, PetscMPIInt tag, MPI_Datatype type, const std::vector<PetscMPIInt> &to, std::vector<std::vector<T>> &to_data,
                             std::vector<PetscMPIInt> *from, std::vector<std::vector<T>> *from_data)
{
  std::vector<PetscMPIInt> counts;
  PetscMPIInt              n_from, *from_ranks = nullptr, *from_counts = nullptr;
  PetscFunctionBeginUser;
  for (const std::vector<T> &d : to_data) counts.push_back((PetscMPIInt)d.size());
  PetscCall(PetscCommBuildTwoSided(comm, 1, MPI_INT, (PetscMPIInt)to.size(), to.data(), counts.data(), &n_from, &from_ranks, &from_counts));
  from->assign(from_ranks, from_ranks + n_from);
  from_data->assign(n_from, {});
  for (PetscMPIInt i = 0; i < n_from; i++) (*from_data)[i].resize(from_counts[i]);
  PetscCall(PetscFree(from_ranks));
  PetscCall(PetscFree(from_counts));
  PetscCall(ExchangeKnown(comm, tag, type, to, to_data, *from, *from_data));
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

TissueDistribution::~TissueDistribution()
{
  PetscCallVoid(PetscSFDestroy(&sf_));
  if (comm_tag_ != MPI_COMM_NULL) PetscCallVoid(PetscCommDestroy(&comm_tag_));
}

PetscErrorCode TissueDistribution::SetUp(MPI_Comm comm, const Tissue &global, const std::vector<PetscInt> &cell_rank, PetscReal reach, PetscReal margin,
                                         Tissue *local, std::vector<PetscInt> *local_of_out)
{
  const ParticleSet &G = global.particles;
  const PetscInt     N = G.n;
  PetscMPIInt        size, rank;
  PetscFunctionBeginUser;
  comm_ = comm;
  if (comm_tag_ != MPI_COMM_NULL) PetscCall(PetscCommDestroy(&comm_tag_));
  PetscCall(PetscCommDuplicate(comm, &comm_tag_, &tag_)); /* the full checks' messages: PETSc's inner communicator, a tag of their own */
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCheck(global.period[0] == 0 && global.period[1] == 0, comm, PETSC_ERR_SUP, "A periodic tissue cannot be distributed over ranks (run it on one rank)");
  PetscCheck((PetscInt)cell_rank.size() == global.NumCells(), comm, PETSC_ERR_ARG_SIZ, "cell_rank has %zu entries for %" PetscInt_FMT " cells",
             cell_rank.size(), global.NumCells());
  const bool part = !global.cell_gid.empty(); /* a part of the tissue (its numbers: ParticleSet::gid, spring_gid, Tissue::cell_gid) */
  reach_          = reach;
  margin_         = margin;
  PetscCall(PetscLogEventRegister("TgHaloExchange", PETSC_OBJECT_CLASSID, &ev_exchange_));
  PetscCall(PetscLogEventRegister("TgHaloCheck", PETSC_OBJECT_CLASSID, &ev_check_));

  /* the cells: the tissue's, then one pseudo-cell for every particle in no cell (rank 0's) */
  std::vector<PetscInt> owner_cell, owner_rank(N);
  OwnerCells(global, &owner_cell);
  std::vector<std::vector<PetscInt>> rings(global.cell_walls.begin(), global.cell_walls.end());
  std::vector<PetscInt>              crank(cell_rank.begin(), cell_rank.end());
  for (PetscInt i = 0; i < N; i++)
    if (owner_cell[i] < 0) {
      PetscCheck(!part, PETSC_COMM_SELF, PETSC_ERR_PLIB, "particle %" PetscInt_FMT " of a part of the tissue is in no cell", G.gid[i]);
      owner_cell[i] = (PetscInt)rings.size();
      rings.push_back({i});
      crank.push_back(0);
    }
  n_cells_ = (PetscInt)rings.size();
  for (PetscInt i = 0; i < N; i++) owner_rank[i] = crank[owner_cell[i]];

  /* the ranks' blocks (global order within a rank) */
  n_owned_ = 0;
  for (PetscInt g = 0; g < N; g++) n_owned_ += owner_rank[g] == rank;
  start_ = 0;
  PetscCallMPI(MPI_Exscan(&n_owned_, &start_, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) start_ = 0; /* MPI_Exscan leaves rank 0's undefined */

  /* the halo cells: another rank's cells within reach + margin of this rank's (reference boxes, of
     the rings and fluid) */
  std::vector<Box>      box(n_cells_), mine;
  std::vector<PetscInt> owned; /* this rank's cells (indices here) */
  owned_cells_.clear();
  for (PetscInt i = 0; i < N; i++) box[owner_cell[i]].Add(&global.X[2 * i]);
  for (PetscInt c = 0; c < n_cells_; c++) {
    for (PetscInt i : rings[c]) box[c].Add(&global.X[2 * i]);
    if (crank[c] == rank) owned.push_back(c), owned_cells_.push_back(global.CellGid(c)), mine.push_back(box[c]);
  }
  std::vector<PetscReal> dist;
  NearestDistances(mine, box, reach + margin + 1, &dist);
  std::vector<char> local_cell(n_cells_, 0);
  local_cells_.clear();
  for (PetscInt c = 0; c < n_cells_; c++) {
    local_cell[c] = crank[c] == rank || dist[c] <= reach + margin;
    if (local_cell[c]) local_cells_.push_back(global.CellGid(c));
  }
  n_local_cells_ = (PetscInt)local_cells_.size();
  std::sort(local_cells_.begin(), local_cells_.end());

  /* local particles: owned, then the other ranks' wall particles of the local cells */
  std::vector<PetscInt> &local_of = *local_of_out, order; /* the set-up's only (the caller's) */
  local_of.assign(N, -1);
  for (PetscInt g = 0; g < N; g++)
    if (owner_rank[g] == rank) local_of[g] = (PetscInt)order.size(), order.push_back(g);
  {
    std::vector<PetscInt> halo;
    for (PetscInt c = 0; c < n_cells_; c++)
      if (local_cell[c])
        for (PetscInt i : rings[c])
          if (owner_rank[i] != rank && G.kind[i] != KIND_FLUID) halo.push_back(i);
    std::sort(halo.begin(), halo.end());
    halo.erase(std::unique(halo.begin(), halo.end()), halo.end());
    for (PetscInt g : halo) local_of[g] = (PetscInt)order.size(), order.push_back(g);
    n_halo_ = (PetscInt)halo.size();
  }
  const PetscInt n = (PetscInt)order.size();

  /* this rank's tissue */
  Tissue       T;
  ParticleSet &P = T.particles;
  P.n            = n;
  P.n_owned      = n_owned_;
  P.bar_radius   = G.bar_radius;
  P.mass.resize(n), P.kind.resize(n), P.cell.resize(n), P.gid.resize(n), P.fixed.resize(n);
  T.X.resize(2 * n);
  if (!global.V.empty()) T.V.resize(2 * n);
  for (PetscInt l = 0; l < n; l++) {
    const PetscInt g = order[l];
    P.mass[l] = G.mass[g], P.kind[l] = G.kind[g], P.cell[l] = G.cell[g], P.gid[l] = G.gid[g], P.fixed[l] = G.fixed[g];
    for (int d = 0; d < 2; d++) {
      T.X[2 * l + d] = global.X[2 * g + d];
      if (!global.V.empty()) T.V[2 * l + d] = global.V[2 * g + d];
    }
  }
  /* springs with both ends here; this rank's (end i owned) first (counted first: no growth slack) */
  std::vector<PetscInt> spring_of(G.springs.size(), -1);
  {
    size_t count = 0;
    for (const Spring &s : G.springs) count += local_of[s.i] >= 0 && local_of[s.j] >= 0;
    P.springs.reserve(count);
    P.spring_gid.reserve(count);
  }
  for (int pass = 0; pass < 2; pass++)
    for (size_t s = 0; s < G.springs.size(); s++) {
      const PetscInt i = local_of[G.springs[s].i], j = local_of[G.springs[s].j];
      if (i < 0 || j < 0 || (i < n_owned_) != (pass == 0)) continue;
      spring_of[s] = (PetscInt)P.springs.size();
      P.spring_gid.push_back(G.SpringGid(s));
      Spring sp = G.springs[s];
      sp.i = i, sp.j = j;
      P.springs.push_back(sp);
    }
  P.n_springs_owned = 0;
  for (const Spring &s : P.springs) P.n_springs_owned += s.i < n_owned_;
  for (Spring &s : P.springs)
    for (int e = 0; e < 2; e++)
      if (s.joint[e] >= 0) s.joint[e] = spring_of[s.joint[e] / 2] >= 0 ? 2 * spring_of[s.joint[e] / 2] + s.joint[e] % 2 : -1;
  /* polygons of the local cells, this rank's first; the cell rings of this rank's cells */
  if (!G.polygons.empty()) {
    std::vector<PetscInt> polygon_of(G.polygons.size(), -1);
    for (int pass = 0; pass < 2; pass++)
      for (size_t c = 0; c < G.polygons.size(); c++) {
        if (!local_cell[c] || (crank[c] == rank) != (pass == 0)) continue;
        PolygonCell C = G.polygons[c];
        for (PetscInt &i : C.nodes) i = local_of[i];
        for (PetscInt &s : C.bars) s = spring_of[s];
        PetscCheck(std::find(C.nodes.begin(), C.nodes.end(), -1) == C.nodes.end() && std::find(C.bars.begin(), C.bars.end(), -1) == C.bars.end(),
                   PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %zu is not whole on rank %d", c, rank);
        polygon_of[c] = (PetscInt)P.polygons.size();
        P.polygons.push_back(C);
        P.polygon_gid.push_back(G.PolygonGid(c));
        if (pass == 0) P.n_polygons_owned = (PetscInt)P.polygons.size();
      }
    if (P.n_polygons_owned < 0) P.n_polygons_owned = 0;
    P.node_polygon.assign(n, -1);
    for (PetscInt l = 0; l < n; l++)
      if (G.node_polygon[order[l]] >= 0) P.node_polygon[l] = polygon_of[G.node_polygon[order[l]]];
    for (const auto &nc : global.named_cells)
      if (polygon_of[nc.second] >= 0) T.named_cells.push_back({nc.first, polygon_of[nc.second]});
  }
  /* this rank's cells: their rings, and every particle that makes their boxes (rings and fluid) */
  ring_start_.assign(1, 0);
  ring_.clear();
  {
    std::vector<std::vector<PetscInt>> fluid(n_cells_);
    for (PetscInt i = 0; i < N; i++)
      if (G.kind[i] == KIND_FLUID && crank[owner_cell[i]] == rank) fluid[owner_cell[i]].push_back(local_of[i]);
    size_t total = 0;
    for (PetscInt c : owned) total += rings[c].size() + fluid[c].size();
    ring_.reserve(total);
    for (PetscInt c : owned) {
      std::vector<PetscInt> ring;
      for (PetscInt i : rings[c]) ring.push_back(local_of[i]);
      ring_.insert(ring_.end(), ring.begin(), ring.end());
      ring_.insert(ring_.end(), fluid[c].begin(), fluid[c].end());
      ring_start_.push_back((PetscInt)ring_.size());
      if (c < global.NumCells()) T.cell_walls.push_back(std::move(ring));
    }
  }
  for (int d = 0; d < 2; d++) T.lo[d] = global.lo[d], T.hi[d] = global.hi[d];
  for (PetscInt l = 1; l < n_owned_; l++)
    PetscCheck(P.gid[l - 1] < P.gid[l], PETSC_COMM_SELF, PETSC_ERR_PLIB, "the owned particles are not in increasing global order");

  /* the exchange pattern: halo components <- their owners'; a halo particle's place in its owner's
     block is asked of the owner (no rank knows every rank's particles) */
  std::vector<PetscSFNode> remote(2 * n_halo_);
  {
    std::vector<PetscMPIInt>           to_ranks;
    std::vector<std::vector<PetscInt>> asked, answer_of; /* per rank asked: the global ids, then their places */
    std::vector<std::vector<PetscInt>> slot;             /* ... and the halo slots they fill */
    std::map<PetscMPIInt, size_t>      index_of;
    for (PetscInt k = 0; k < n_halo_; k++) {
      const PetscInt g     = order[n_owned_ + k];
      auto           added = index_of.emplace((PetscMPIInt)owner_rank[g], to_ranks.size());
      if (added.second) {
        to_ranks.push_back((PetscMPIInt)owner_rank[g]);
        asked.emplace_back();
        slot.emplace_back();
      }
      asked[added.first->second].push_back(G.gid[g]);
      slot[added.first->second].push_back(k);
    }
    std::vector<PetscMPIInt>           from_ranks;
    std::vector<std::vector<PetscInt>> questions;
    PetscMPIInt                        tag_answer;
    PetscCall(ExchangeFound(comm_tag_, tag_, MPIU_INT, to_ranks, asked, &from_ranks, &questions));
    PetscErrorCode missing = PETSC_SUCCESS;
    for (std::vector<PetscInt> &q : questions)
      for (PetscInt &g : q) { /* the answer replaces the question */
        auto it = std::lower_bound(P.gid.begin(), P.gid.begin() + n_owned_, g);
        if (it == P.gid.begin() + n_owned_ || *it != g) missing = PETSC_ERR_PLIB;
        g = (PetscInt)(it - P.gid.begin());
      }
    for (const auto &a : asked) answer_of.emplace_back(a.size());
    PetscCall(PetscCommGetNewTag(comm_tag_, &tag_answer));
    PetscCall(ExchangeKnown(comm_tag_, tag_answer, MPIU_INT, from_ranks, questions, to_ranks, answer_of));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &missing, 1, MPI_INT, MPI_MAX, comm));
    PetscCheck(!missing, comm, PETSC_ERR_PLIB, "a rank was asked for a halo particle it does not own");
    for (size_t i = 0; i < to_ranks.size(); i++)
      for (size_t j = 0; j < slot[i].size(); j++)
        for (int d = 0; d < 2; d++) remote[2 * slot[i][j] + d] = {to_ranks[i], 2 * answer_of[i][j] + d};
  }
  *local = std::move(T);
  PetscCall(PetscSFDestroy(&sf_));
  PetscCall(PetscSFCreate(comm, &sf_));
  PetscCall(PetscSFSetGraph(sf_, 2 * n_owned_, 2 * n_halo_, NULL, PETSC_OWN_POINTER, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(sf_));
  box_check_.clear();
  checked_     = false;
  full_checks_ = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissueDistribution::Gather(const std::vector<PetscReal *> &arrays) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_exchange_, 0, 0, 0, 0));
  for (PetscReal *a : arrays) PetscCall(PetscSFBcastBegin(sf_, MPIU_REAL, a, a + 2 * n_owned_, MPI_REPLACE));
  for (PetscReal *a : arrays) PetscCall(PetscSFBcastEnd(sf_, MPIU_REAL, a, a + 2 * n_owned_, MPI_REPLACE));
  bytes_ += 2.0 * arrays.size() * n_halo_ * sizeof(PetscReal);
  PetscCall(PetscLogEventEnd(ev_exchange_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissueDistribution::Return(PetscReal *f) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_exchange_, 0, 0, 0, 0));
  PetscCall(PetscSFReduceBegin(sf_, MPIU_REAL, f + 2 * n_owned_, f, MPIU_SUM));
  PetscCall(PetscSFReduceEnd(sf_, MPIU_REAL, f + 2 * n_owned_, f, MPIU_SUM));
  bytes_ += 2.0 * n_halo_ * sizeof(PetscReal);
  PetscCall(PetscLogEventEnd(ev_exchange_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissueDistribution::Check(const PetscReal *x)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_check_, 0, 0, 0, 0));
  /* this rank's cells' boxes now; cheap: has any box edge moved half the slack since the last full
     check? (two boxes come closer by at most the sum of their edges' moves) */
  std::vector<PetscReal> &now   = box_now_; /* kept: this runs every evaluation */
  PetscReal               shift = 0;
  now.resize(4 * owned_cells_.size());
  for (size_t k = 0; k < owned_cells_.size(); k++) {
    Box b;
    for (PetscInt r = ring_start_[k]; r < ring_start_[k + 1]; r++) b.Add(&x[2 * ring_[r]]);
    const PetscReal e[4] = {b.lo[0], b.lo[1], b.hi[0], b.hi[1]};
    for (int q = 0; q < 4; q++) {
      now[4 * k + q] = e[q];
      if (checked_) shift = std::max(shift, std::fabs(e[q] - box_check_[4 * k + q]));
    }
  }
  if (checked_) {
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &shift, 1, MPIU_REAL, MPIU_MAX, comm_));
    if (2 * std::sqrt(2.0) * shift < slack_) {
      PetscCall(PetscLogEventEnd(ev_check_, 0, 0, 0, 0));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(PetscInfo(NULL, "halo full check %d: box shift %g, slack %g\n", (int)full_checks_, (double)shift, (double)slack_));
  full_checks_++;
  /* The cells' current boxes, from their owners to the ranks near them only. Every rank's region
     (the box of its cells grown by reach + margin: 4 numbers a rank) is gathered; a cell's box goes
     to the ranks whose region it meets, over the pairs PetscCommBuildTwoSided finds. A cell that
     meets no region of a rank is farther than reach + margin from all of that rank's cells, where
     the distance below is capped anyway: the slack is the same as from every cell's box. */
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::vector<Box> own(owned_cells_.size());
  Box              region;
  for (size_t k = 0; k < owned_cells_.size(); k++) {
    own[k].lo[0] = now[4 * k], own[k].lo[1] = now[4 * k + 1], own[k].hi[0] = now[4 * k + 2], own[k].hi[1] = now[4 * k + 3];
    region.Add(own[k].lo), region.Add(own[k].hi);
  }
  const PetscReal grow = reach_ + margin_;
  if (!owned_cells_.empty())
    for (int d = 0; d < 2; d++) region.lo[d] -= grow, region.hi[d] += grow;
  std::vector<PetscReal> regions(4 * (size_t)size);
  const PetscReal        mine[4] = {region.lo[0], region.lo[1], region.hi[0], region.hi[1]};
  PetscCallMPI(MPI_Allgather(mine, 4, MPIU_REAL, regions.data(), 4, MPIU_REAL, comm_));
  std::vector<PetscMPIInt>            to_ranks;
  std::vector<std::vector<PetscReal>> to_data;
  for (PetscMPIInt q = 0; q < size; q++) {
    if (q == rank) continue;
    const PetscReal       *R = &regions[4 * (size_t)q];
    std::vector<PetscReal> send;
    for (size_t k = 0; k < own.size(); k++)
      if (!(own[k].hi[0] < R[0] || own[k].lo[0] > R[2] || own[k].hi[1] < R[1] || own[k].lo[1] > R[3]))
        send.insert(send.end(), {(PetscReal)owned_cells_[k], own[k].lo[0], own[k].lo[1], own[k].hi[0], own[k].hi[1]});
    if (send.empty()) continue;
    to_ranks.push_back(q);
    to_data.push_back(std::move(send));
  }
  std::vector<PetscMPIInt>            from_ranks;
  std::vector<std::vector<PetscReal>> from_data;
  PetscCall(ExchangeFound(comm_tag_, tag_, MPIU_REAL, to_ranks, to_data, &from_ranks, &from_data));
  std::vector<Box> near;
  check_bytes_ += sizeof(PetscReal) * (4.0 * size);
  for (const std::vector<PetscReal> &v : from_data) {
    check_bytes_ += sizeof(PetscReal) * (double)v.size();
    for (size_t k = 0; k + 5 <= v.size(); k += 5) {
      const PetscInt c = (PetscInt)v[k];
      if (std::binary_search(local_cells_.begin(), local_cells_.end(), c)) continue; /* in the halo already */
      Box b;
      b.lo[0] = v[k + 1], b.lo[1] = v[k + 2], b.hi[0] = v[k + 3], b.hi[1] = v[k + 4];
      near.push_back(b);
    }
  }
  std::vector<PetscReal> dist;
  NearestDistances(own, near, reach_ + margin_, &dist);
  PetscReal slack = margin_;
  for (PetscReal d : dist) slack = std::min(slack, d - reach_);
  PetscCallMPI(MPI_Allreduce(&slack, &slack_, 1, MPIU_REAL, MPIU_MIN, comm_));
  PetscCheck(slack_ >= 0, comm_, PETSC_ERR_NOT_CONVERGED,
             "A cell came within %g µm (the interactions' reach) of a rank's cells without being in its halo: the halo set up at the start "
             "(reach + -fine_halo_margin %g µm) no longer covers this deformation; rerun with a larger -fine_halo_margin",
             (double)reach_, (double)margin_);
  box_check_.swap(box_now_);
  checked_ = true;
  PetscCall(PetscLogEventEnd(ev_check_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
