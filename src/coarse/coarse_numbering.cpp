/* A numbering of the coarse mesh's unknowns and material points that does not depend on the ranks
   or the partition (restarts on another number of ranks): by position in the reference geometry.
   Debian's PETSc 3.18 DMPlex keeps no natural numbering unless a section exists before the mesh is
   distributed (ours is made after METIS's partition), so the positions are the rank-free key: a
   node's reference position and component for an unknown, a cell's centre for its points. */
#include <turgor/coarse/coarse_model.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace turgor {

/* Every rank's items keyed by (a, b, c), a and b rounded to `tol`: each item's position in the
   order of the keys over all ranks, in rank order of the items (every rank sorts the same gathered
   keys, so the order does not depend on the partition). Two items with one key are an error. */
static PetscErrorCode GeometricOrder(MPI_Comm comm, const std::vector<std::array<PetscReal, 3>> &keys, PetscReal tol, const char *what,
                                     std::vector<PetscInt> &order)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
  const PetscMPIInt        n = (PetscMPIInt)(3 * keys.size());
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  std::vector<PetscReal> all(displs[size]);
  PetscCallMPI(MPI_Allgatherv(keys.empty() ? nullptr : keys[0].data(), n, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, comm));
  const size_t                          N = all.size() / 3;
  std::vector<std::array<long long, 3>> key(N);
  std::vector<PetscInt>                 by_key(N);
  for (size_t i = 0; i < N; i++) {
    key[i]    = {std::llround(all[3 * i] / tol), std::llround(all[3 * i + 1] / tol), std::llround(all[3 * i + 2])};
    by_key[i] = (PetscInt)i;
  }
  std::sort(by_key.begin(), by_key.end(), [&](PetscInt i, PetscInt j) { return key[i] < key[j]; });
  order.assign(N, -1);
  for (size_t k = 0; k < N; k++) {
    PetscCheck(k == 0 || key[by_key[k]] != key[by_key[k - 1]], comm, PETSC_ERR_PLIB, "%s: two at (%g, %g): no rank-independent numbering", what,
               (double)all[3 * by_key[k]], (double)all[3 * by_key[k] + 1]);
    order[by_key[k]] = (PetscInt)k;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The mesh's extent, for the rounding of positions. */
static PetscErrorCode Extent(MPI_Comm comm, const std::vector<PetscReal> &Xref, PetscReal *extent)
{
  PetscReal lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
  PetscFunctionBeginUser;
  for (size_t i = 0; i < Xref.size(); i++) lo[i % 2] = std::min(lo[i % 2], Xref[i]), hi[i % 2] = std::max(hi[i % 2], Xref[i]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo, 2, MPIU_REAL, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi, 2, MPIU_REAL, MPI_MAX, comm));
  *extent = std::max(std::max(hi[0] - lo[0], hi[1] - lo[1]), (PetscReal)1e-300);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::RankFreeStateOrder(IS *order)
{
  PetscFunctionBeginUser;
  if (!rank_free_order_) PetscCall(ComputeRankFreeStateOrder(&rank_free_order_)); /* once: the mesh does not change */
  PetscCall(PetscObjectReference((PetscObject)rank_free_order_));
  *order = rank_free_order_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::ComputeRankFreeStateOrder(IS *order)
{
  Vec                   X[3];
  const PetscScalar    *x[3];
  PetscInt              n, rstart;
  PetscReal             extent;
  std::vector<PetscInt> all;
  std::string           missing;
  PetscFunctionBeginUser;
  PetscCall(Extent(comm_, Xref_, &extent));
  /* each unknown's node position (x, then y) and component, through NodeState */
  for (int k = 0; k < 3; k++) {
    PetscCall(DMCreateGlobalVector(dm_, &X[k]));
    PetscCall(NodeState(
      X[k],
      [k](const PetscReal P[2], PetscReal s[4]) {
        for (int d = 0; d < 4; d++) s[d] = k < 2 ? P[k] : (PetscReal)d;
        return true;
      },
      &missing));
  }
  PetscCall(VecGetLocalSize(X[0], &n));
  PetscCall(VecGetOwnershipRange(X[0], &rstart, NULL));
  std::vector<std::array<PetscReal, 3>> keys((size_t)n);
  for (int k = 0; k < 3; k++) PetscCall(VecGetArrayRead(X[k], &x[k]));
  for (PetscInt i = 0; i < n; i++) keys[i] = {PetscRealPart(x[1][i]), PetscRealPart(x[0][i]), PetscRealPart(x[2][i])}; /* row by row */
  for (int k = 0; k < 3; k++) {
    PetscCall(VecRestoreArrayRead(X[k], &x[k]));
    PetscCall(VecDestroy(&X[k]));
  }
  PetscCall(GeometricOrder(comm_, keys, 1e-9 * extent, "coarse unknowns", all));
  PetscCall(ISCreateGeneral(comm_, n, all.data() + rstart, PETSC_COPY_VALUES, order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::ComputeRankFreeCellIds()
{
  PetscReal                             extent;
  const PetscInt                        nc = c_end_ - c_start_;
  std::vector<std::array<PetscReal, 3>> keys((size_t)nc);
  std::vector<PetscInt>                 all;
  PetscInt                              offset = 0;
  PetscFunctionBeginUser;
  PetscCall(Extent(comm_, Xref_, &extent));
  for (PetscInt k = 0; k < nc; k++) {
    const PetscReal *X = &Xref_[8 * k];
    keys[k]            = {0.25 * (X[1] + X[3] + X[5] + X[7]), 0.25 * (X[0] + X[2] + X[4] + X[6]), 0};
  }
  PetscCall(GeometricOrder(comm_, keys, 1e-9 * extent, "coarse elements", all));
  PetscCallMPI(MPI_Exscan(&nc, &offset, 1, MPIU_INT, MPI_SUM, comm_));
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) offset = 0; /* MPI_Exscan leaves rank 0's undefined */
  cell_id_.assign(all.begin() + offset, all.begin() + offset + nc);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseModel::RankFreePointIds(std::vector<PetscInt> &global)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  if (!rank_free_ids_.empty()) { /* once: the mesh does not change */
    global = rank_free_ids_;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* every rank's cells' numbers, in rank order (the pool's order of the points) */
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
  const PetscMPIInt        n = (PetscMPIInt)cell_id_.size();
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  std::vector<PetscInt> cells(displs[size]);
  PetscCallMPI(MPI_Allgatherv(cell_id_.data(), n, MPIU_INT, cells.data(), counts.data(), displs.data(), MPIU_INT, comm_));
  /* the points in the pool's global order: the ranks' cells in turn, each cell's points in turn */
  global.resize(cells.size() * npts_);
  for (size_t c = 0; c < cells.size(); c++)
    for (PetscInt q = 0; q < npts_; q++) global[c * npts_ + q] = cells[c] * npts_ + q;
  rank_free_ids_ = global;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
