#include <turgor/coarse/coarse_snapshot_reader.h>
#include <turgor/core/errors.h>
#include <turgor/io/output.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace turgor {

namespace {

/* Rank 0 reads: the reference vertex coordinates (2 per vertex), the chosen snapshot's displacement
   (3 per vertex), its time, and the list of times (for messages); *problem says what is wrong. */
PetscErrorCode ReadOnRankZero(const CoarseSnapshotRequest &req, std::vector<PetscReal> &xy, std::vector<PetscReal> &disp, PetscReal *found,
                              std::string *problem)
{
  PetscBool   exists, has;
  PetscViewer v;
  char        buf[512];
  PetscFunctionBeginUser;
  PetscCall(PetscTestFile(req.path.c_str(), 'r', &exists));
  if (!exists) {
    *problem = "no such file (or not readable)";
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (H5Fis_hdf5(req.path.c_str()) <= 0) {
    *problem = "not an HDF5 file (a coarse.h5 of -mode fe2 or fe2_static is)";
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, req.path.c_str(), FILE_MODE_READ, &v));
  PetscCall(PetscViewerHDF5HasDataset(v, "/mesh/vertices", &has));
  if (!has) {
    *problem = "not a coarse snapshot file of turgor (no /mesh/vertices)";
    PetscCall(PetscViewerDestroy(&v));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  {
    Vec                X;
    const PetscScalar *a;
    PetscInt           n;
    PetscCall(VecCreate(PETSC_COMM_SELF, &X));
    PetscCall(PetscObjectSetName((PetscObject)X, "vertices"));
    PetscCall(PetscViewerHDF5PushGroup(v, "/mesh"));
    PetscCall(VecLoad(X, v));
    PetscCall(PetscViewerHDF5PopGroup(v));
    PetscCall(VecGetLocalSize(X, &n));
    PetscCall(VecGetArrayRead(X, &a));
    xy.assign(a, a + n);
    PetscCall(VecRestoreArrayRead(X, &a));
    PetscCall(VecDestroy(&X));
  }
  /* the snapshots and their times */
  std::vector<PetscReal> times;
  for (int k = 0;; k++) {
    PetscReal t;
    PetscCall(PetscSNPrintf(buf, sizeof buf, "/snapshot_%04d", k));
    PetscCall(PetscViewerHDF5HasGroup(v, buf, &has));
    if (!has) break;
    PetscCall(PetscViewerHDF5ReadAttribute(v, buf, "time", PETSC_REAL, NULL, &t));
    times.push_back(t);
  }
  if (times.empty()) {
    *problem = "the file holds no snapshot";
    PetscCall(PetscViewerDestroy(&v));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscInt  pick  = (PetscInt)times.size() - 1;
  PetscReal scale = 0;
  for (PetscReal t : times) scale = PetscMax(scale, PetscAbsReal(t));
  if (req.has_time) {
    pick = -1;
    for (size_t k = 0; k < times.size() && pick < 0; k++)
      if (PetscAbsReal(times[k] - req.time) <= 1e-6 * PetscMax(scale, 1e-12)) pick = (PetscInt)k;
    if (pick < 0) {
      PetscCall(PetscSNPrintf(buf, sizeof buf, "%s = %g: no snapshot at this time in %s (%zu snapshots at times %g", req.time_option, (double)req.time,
                              req.path.c_str(), times.size(), (double)times[0]));
      std::string msg = buf;
      for (size_t k = 1; k < times.size() && k < 12; k++) {
        PetscCall(PetscSNPrintf(buf, sizeof buf, ", %g", (double)times[k]));
        msg += buf;
      }
      *problem = msg + (times.size() > 12 ? ", ...)" : ")");
      PetscCall(PetscViewerDestroy(&v));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  *found = times[pick];
  {
    Vec                D;
    const PetscScalar *a;
    PetscInt           n;
    PetscCall(PetscSNPrintf(buf, sizeof buf, "/snapshot_%04d", (int)pick));
    PetscCall(VecCreate(PETSC_COMM_SELF, &D));
    PetscCall(PetscObjectSetName((PetscObject)D, "displacement"));
    PetscCall(PetscViewerHDF5PushGroup(v, buf));
    PetscCall(PetscViewerHDF5HasDataset(v, "displacement", &has));
    if (has) PetscCall(VecLoad(D, v));
    PetscCall(PetscViewerHDF5PopGroup(v));
    if (has) {
      PetscCall(VecGetLocalSize(D, &n));
      PetscCall(VecGetArrayRead(D, &a));
      disp.assign(a, a + n);
      PetscCall(VecRestoreArrayRead(D, &a));
    }
    PetscCall(VecDestroy(&D));
    if (!has || disp.size() != 3 * (xy.size() / 2)) {
      PetscCall(PetscSNPrintf(buf, sizeof buf, "the snapshot at t = %g has no displacement of its mesh", (double)*found));
      *problem = buf;
    }
    for (size_t k = 0; k < disp.size() && problem->empty(); k++)
      if (!std::isfinite(disp[k])) {
        PetscCall(PetscSNPrintf(buf, sizeof buf, "the displacement of the snapshot at t = %g is not finite (at its vertex %zu)", (double)*found, k / 3));
        *problem = buf;
      }
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BroadcastReals(MPI_Comm comm, std::vector<PetscReal> &a)
{
  PetscInt n = (PetscInt)a.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  a.resize(n);
  PetscCallMPI(MPI_Bcast(a.data(), (PetscMPIInt)n, MPIU_REAL, 0, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode ReadCoarseSnapshot(CoarseModel &model, const CoarseSnapshotRequest &req, Vec U, PetscReal *time_found)
{
  MPI_Comm               comm = PetscObjectComm((PetscObject)U);
  PetscMPIInt            rank;
  std::vector<PetscReal> xy, disp;
  std::string            problem;
  PetscReal              found = 0;
  PetscFunctionBeginUser;
  /* a snapshot stores the vertices' displacement: a Q2 state also has nodes at the edge midpoints
     and cell centres, which interpolating the vertices would not reproduce */
  PetscCheck(model.NodesPerElement() == 4, comm, PETSC_ERR_ARG_INCOMP,
             "Option %s = %s: a coarse.h5 snapshot holds the displacement at the vertices only, which does not determine a state of -coarse_element %s "
             "(nodes also at the edge midpoints and cell centres); analyse snapshots with -coarse_element q1",
             req.file_option, req.path.c_str(), model.ElementName());
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) PetscCall(ReadOnRankZero(req, xy, disp, &found, &problem));
  PetscCall(BroadcastString(comm, &problem));
  PetscCheck(problem.empty() || problem.rfind(req.time_option, 0) != 0, comm, PETSC_ERR_ARG_WRONG, "Option %s", problem.c_str());
  PetscCheck(problem.empty(), comm, PETSC_ERR_FILE_READ, "Option %s = %s: %s", req.file_option, req.path.c_str(), problem.c_str());
  PetscCall(BroadcastReals(comm, xy));
  PetscCall(BroadcastReals(comm, disp));
  PetscCallMPI(MPI_Bcast(&found, 1, MPIU_REAL, 0, comm));

  /* the model's vertices among the file's, by reference coordinates: the file's sorted by x, each
     model vertex looked up in the x window of the tolerance */
  DM        dm = model.GetDM();
  PetscInt  vs, ve, nfile = (PetscInt)xy.size() / 2, nmodel = 0;
  PetscReal lo[2], hi[2];
  PetscCall(DMGetBoundingBox(dm, lo, hi));
  const PetscReal       tol = 1e-9 * std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  std::vector<PetscInt> order(nfile);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) { return xy[2 * a] < xy[2 * b]; });
  {
    IS              gnum;
    const PetscInt *g;
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
    PetscCall(DMPlexGetVertexNumbering(dm, &gnum));
    PetscCall(ISGetIndices(gnum, &g));
    for (PetscInt v = vs; v < ve; v++) nmodel = PetscMax(nmodel, g[v - vs] >= 0 ? g[v - vs] + 1 : -g[v - vs]);
    PetscCall(ISRestoreIndices(gnum, &g));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nmodel, 1, MPIU_INT, MPI_MAX, comm));
  }
  PetscCheck(nmodel == nfile, comm, PETSC_ERR_ARG_INCOMP,
             "Option %s = %s: a snapshot of another mesh (%" PetscInt_FMT " vertices; this run's mesh has %" PetscInt_FMT ")", req.file_option,
             req.path.c_str(), nfile, nmodel);
  std::string missing;
  PetscCall(model.NodeState(
    U,
    [&](const PetscReal X[2], PetscReal state[4]) {
      auto it = std::lower_bound(order.begin(), order.end(), X[0] - tol, [&](PetscInt a, PetscReal val) { return xy[2 * a] < val; });
      for (; it != order.end() && xy[2 * *it] <= X[0] + tol; ++it)
        if (PetscAbsReal(xy[2 * *it + 1] - X[1]) <= tol) {
          state[0] = disp[3 * *it];
          state[1] = disp[3 * *it + 1];
          return true;
        }
      return false;
    },
    &missing));
  PetscCheck(missing.empty(), comm, PETSC_ERR_ARG_INCOMP,
             "Option %s = %s: a snapshot of another mesh (this run's vertex at %s is not among the file's vertices)", req.file_option, req.path.c_str(),
             missing.c_str());
  *time_found = found;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
