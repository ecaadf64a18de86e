#include <turgor/coarse/coarse_fields.h>
#include <turgor/core/geometry.h>
#include <turgor/io/xdmf.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>

namespace turgor {

/* Gather variable-length blocks of doubles to rank 0 (MPI_Gatherv). */
static PetscErrorCode GatherToZero(MPI_Comm comm, const std::vector<PetscReal> &mine, std::vector<PetscReal> &all)
{
  PetscMPIInt size, rank, n = (PetscMPIInt)mine.size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm));
  if (rank == 0)
    for (int r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
  all.resize(rank == 0 ? displs[size - 1] + counts[size - 1] : 0);
  PetscCallMPI(MPI_Gatherv(mine.data(), n, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, 0, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Signed area of a quadrilateral (shoelace over its four vertices in cell order) at the points
   x + u (x: 2 per vertex; u: 3 per vertex, or NULL). */
static PetscReal QuadArea(const PetscInt *cell, const std::vector<PetscReal> &x, const PetscReal *u)
{
  return PolygonSignedArea(4, [&](size_t k) {
    const PetscInt i = cell[k];
    return Point2{x[2 * i] + (u ? u[3 * i] : 0), x[2 * i + 1] + (u ? u[3 * i + 1] : 0)};
  });
}

PetscErrorCode CoarseFieldsWriter::WriteArray(const char *name, const std::vector<PetscReal> &a, PetscInt bs)
{
  Vec v;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, (PetscInt)a.size(), a.data(), &v));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(VecView(v, viewer_));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseFieldsWriter::Open(CoarseModel &model, const std::string &dir, const std::string &base)
{
  DM                 dm = model.GetDM(), cdm;
  IS                 gnum;
  const PetscInt    *g;
  PetscInt           vs, ve, cs, ce, gmax = -1;
  Vec                coords;
  PetscSection       csec;
  const PetscScalar *x;
  PetscFunctionBeginUser;
  PetscCall(Close());
  PetscCall(PetscObjectGetComm((PetscObject)dm, &comm_));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  h5name_   = base + ".h5";
  xmfpath_  = dir + "/" + base + ".xmf";
  grid_     = base;
  acoustic_ = model.Spec().acoustic_field;
  times_.clear();
  PetscCall(DMCreateLocalVector(dm, &Uloc_));
  PetscCall(DMCreateLocalVector(dm, &Vloc_));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cs, &ce));
  PetscCall(DMPlexGetVertexNumbering(dm, &gnum));
  PetscCall(ISGetIndices(gnum, &g));
  vertex_gid_.assign(g, g + (ve - vs));
  PetscCall(ISRestoreIndices(gnum, &g));
  for (PetscInt k : vertex_gid_) gmax = PetscMax(gmax, k >= 0 ? k : -(k + 1));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &gmax, 1, MPIU_INT, MPI_MAX, comm_));
  n_vertices_ = gmax + 1;

  /* owned vertices: (gid, x, y); cells: the global numbers of their four vertices, counter-clockwise */
  std::vector<PetscReal> mine, all, conn, allconn;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt v = vs; v < ve; v++) {
    if (vertex_gid_[v - vs] < 0) continue;
    PetscInt off;
    PetscCall(PetscSectionGetOffset(csec, v, &off));
    mine.insert(mine.end(), {(PetscReal)vertex_gid_[v - vs], PetscRealPart(x[off]), PetscRealPart(x[off + 1])});
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  for (PetscInt c = cs; c < ce; c++) {
    PetscInt *cl = NULL, n;
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &n, &cl));
    for (PetscInt r = 0; r < n; r++)
      if (cl[2 * r] >= vs && cl[2 * r] < ve) {
        const PetscInt k = vertex_gid_[cl[2 * r] - vs];
        conn.push_back((PetscReal)(k >= 0 ? k : -(k + 1)));
      }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &n, &cl));
  }
  PetscCall(GatherToZero(comm_, mine, all));
  PetscCall(GatherToZero(comm_, conn, allconn));
  n_cells_ = (PetscInt)allconn.size() / 4;
  PetscCallMPI(MPI_Bcast(&n_cells_, 1, MPIU_INT, 0, comm_));
  rho0_ = model.ReferenceDensity();
  if (rank_ == 0) {
    xy_.assign(2 * n_vertices_, 0);
    for (size_t k = 0; k + 3 <= all.size(); k += 3) {
      const PetscInt id = (PetscInt)all[k];
      xy_[2 * id]       = all[k + 1];
      xy_[2 * id + 1]   = all[k + 2];
    }
    cells_.assign(allconn.begin(), allconn.end());
    area0_.resize(n_cells_);
    for (PetscInt c = 0; c < n_cells_; c++) area0_[c] = QuadArea(&cells_[4 * c], xy_, NULL);
    PetscCall(PetscViewerHDF5Open(PETSC_COMM_SELF, (dir + "/" + h5name_).c_str(), FILE_MODE_WRITE, &viewer_));
    PetscCall(PetscViewerHDF5PushGroup(viewer_, "/mesh"));
    PetscCall(WriteArray("vertices", xy_, 2));
    IS is;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)cells_.size(), cells_.data(), PETSC_COPY_VALUES, &is));
    PetscCall(ISSetBlockSize(is, 4));
    PetscCall(PetscObjectSetName((PetscObject)is, "cells"));
    PetscCall(ISView(is, viewer_));
    PetscCall(ISDestroy(&is));
    PetscCall(PetscViewerHDF5PopGroup(viewer_));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseFieldsWriter::GatherVertexVector(CoarseModel &model, Vec V, PetscInt offset, bool boundary_values, std::vector<PetscReal> &xyz)
{
  DM                     dm  = model.GetDM();
  Vec                    loc = boundary_values ? Uloc_ : Vloc_;
  PetscSection           ls;
  PetscInt               vs, ve;
  const PetscScalar     *u;
  std::vector<PetscReal> mine, all;
  PetscFunctionBeginUser;
  if (boundary_values) PetscCall(model.GlobalToLocal(V, loc));
  else { /* the constrained entries stay 0 */ PetscCall(VecZeroEntries(loc));
    PetscCall(DMGlobalToLocal(dm, V, INSERT_VALUES, loc));
  }
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(VecGetArrayRead(loc, &u));
  for (PetscInt v = vs; v < ve; v++) {
    if (vertex_gid_[v - vs] < 0) continue;
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ls, v, &off));
    mine.insert(mine.end(), {(PetscReal)vertex_gid_[v - vs], PetscRealPart(u[off + offset]), PetscRealPart(u[off + offset + 1])});
  }
  PetscCall(VecRestoreArrayRead(loc, &u));
  PetscCall(GatherToZero(comm_, mine, all));
  xyz.assign(rank_ == 0 ? 3 * n_vertices_ : 0, 0);
  for (size_t k = 0; k + 2 < all.size(); k += 3) {
    const PetscInt id = (PetscInt)all[k];
    for (int d = 0; d < 2; d++) xyz[3 * id + d] = all[k + 1 + d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseFieldsWriter::Write(CoarseModel &model, Vec U, PetscReal time, const std::vector<Vec> &vectors)
{
  std::vector<PetscReal>              disp, vel, stress, acoustic;
  std::vector<std::vector<PetscReal>> extra(extra_.size());
  PetscFunctionBeginUser;
  PetscCheck(vectors.size() == extra_.size(), comm_, PETSC_ERR_ARG_SIZ, "CoarseFieldsWriter::Write: %zu vertex vectors for %zu added fields", vectors.size(),
             extra_.size());
  /* vectors with z = 0 (ParaView's Xdmf3 readers keep 2-component vectors as such, and Warp By
     Vector takes only 3) */
  PetscCall(GatherVertexVector(model, U, 0, true, disp));
  PetscCall(GatherVertexVector(model, U, 2, true, vel));
  for (size_t k = 0; k < extra_.size(); k++) PetscCall(GatherVertexVector(model, vectors[k], 0, false, extra[k]));
  PetscCall(GatherToZero(comm_, model.CellStress(), stress));
  if (acoustic_) PetscCall(GatherToZero(comm_, model.CellAcoustic(), acoustic));
  if (rank_ == 0) {
    /* the stress as a 3 x 3 tensor (row-major, the z row and column 0: the model is 2D) beside its
       three components; the density of the element, its mass over its current area: rho0 A0 / A
       (rho dv = rho0 dV, as in the mass matrix) */
    std::vector<PetscReal> sigma(9 * n_cells_, 0), sxx(n_cells_), syy(n_cells_), sxy(n_cells_), rho(n_cells_);
    for (PetscInt c = 0; c < n_cells_; c++) {
      sxx[c]           = stress[3 * c];
      syy[c]           = stress[3 * c + 1];
      sxy[c]           = stress[3 * c + 2];
      sigma[9 * c]     = sxx[c];
      sigma[9 * c + 1] = sxy[c];
      sigma[9 * c + 3] = sxy[c];
      sigma[9 * c + 4] = syy[c];
      rho[c]           = rho0_ * area0_[c] / QuadArea(&cells_[4 * c], xy_, disp.data());
    }
    char group[64];
    PetscCall(PetscSNPrintf(group, sizeof group, "/snapshot_%04d", (int)times_.size()));
    PetscCall(PetscViewerHDF5PushGroup(viewer_, group));
    PetscCall(WriteArray("displacement", disp, 3));
    PetscCall(WriteArray("velocity", vel, 3));
    PetscCall(WriteArray("stress", sigma, 9));
    PetscCall(WriteArray("stress_xx", sxx, 1));
    PetscCall(WriteArray("stress_yy", syy, 1));
    PetscCall(WriteArray("stress_xy", sxy, 1));
    PetscCall(WriteArray("density", rho, 1));
    if (acoustic_) PetscCall(WriteArray("acoustic_min_det", acoustic, 1));
    for (size_t k = 0; k < extra_.size(); k++) PetscCall(WriteArray(extra_[k].name.c_str(), extra[k], 3));
    PetscCall(PetscViewerHDF5WriteAttribute(viewer_, group, "time", PETSC_REAL, &time));
    PetscCall(PetscViewerHDF5PopGroup(viewer_));
    hid_t fid;
    PetscCall(PetscViewerHDF5GetFileId(viewer_, &fid));
    PetscCheck(H5Fflush(fid, H5F_SCOPE_GLOBAL) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot flush %s", h5name_.c_str());
  }
  times_.push_back(time);
  PetscCall(WriteXdmf());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The XDMF (2.0, read by ParaView's Xdmf3 readers and by its legacy XDMF reader): per snapshot the
   quadrilaterals on the reference vertices with the vertex and element fields (io/xdmf.h). The
   stress is a 9-component Tensor, not a Tensor6: the two readers order a Tensor6's six values
   differently (the legacy reader as xx xy xz yy yz zz, the Xdmf3 readers pass them on as VTK's
   xx yy zz xy yz xz), a full tensor means the same to both. */
PetscErrorCode CoarseFieldsWriter::WriteXdmf()
{
  XdmfWriter      xdmf;
  const long long NV = n_vertices_, NC = n_cells_;
  struct Attribute {
    std::string name, type, center, unit;
    long long   n, ncomp;
  };
  std::vector<Attribute> attrs = {
    {"displacement", "Vector", "Node", "µm",      NV, 3},
    {"velocity",     "Vector", "Node", "µm/µs",  NV, 3},
    {"stress",       "Tensor", "Cell", "N/m",      NC, 9},
    {"stress_xx",    "Scalar", "Cell", "N/m",      NC, 1},
    {"stress_yy",    "Scalar", "Cell", "N/m",      NC, 1},
    {"stress_xy",    "Scalar", "Cell", "N/m",      NC, 1},
    {"density",      "Scalar", "Cell", "ng/µm²", NC, 1}
  };
  if (acoustic_) attrs.push_back({"acoustic_min_det", "Scalar", "Cell", "(N/m)²", NC, 1});
  for (const Field &f : extra_) attrs.push_back({f.name, "Vector", "Node", f.unit, NV, 3});
  PetscFunctionBeginUser;
  PetscCall(xdmf.Open(comm_, xmfpath_, h5name_, "length µm, time µs, mass ng; velocity µm/µs, force µN, 2D stress N/m, 2D density ng/µm²"));
  PetscCall(xdmf.BeginCollection(grid_));
  for (size_t k = 0; k < times_.size(); k++) {
    PetscCall(xdmf.BeginGrid(grid_, k, times_[k]));
    PetscCall(xdmf.Topology("Quadrilateral", NC, 0, {XdmfDims(NC, 4), true, "/mesh/cells"}));
    PetscCall(xdmf.Geometry("XY", "µm", {XdmfDims(NV, 2), false, "/mesh/vertices"}));
    for (const Attribute &a : attrs)
      PetscCall(xdmf.Attribute(a.name, a.type.c_str(), a.center.c_str(), "unit", a.unit,
                               {XdmfDims(a.n, a.ncomp > 1 ? a.ncomp : 0), false, XdmfSnapshotPath(k, a.name)}));
    PetscCall(xdmf.EndGrid());
  }
  PetscCall(xdmf.EndCollection());
  PetscCall(xdmf.Close());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseFieldsWriter::Close()
{
  PetscFunctionBeginUser;
  if (viewer_) PetscCall(PetscViewerDestroy(&viewer_));
  viewer_ = nullptr;
  PetscCall(VecDestroy(&Uloc_));
  PetscCall(VecDestroy(&Vloc_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
