#include <turgor/coarse/coarse_fields.h>
#include <turgor/core/geometry.h>
#include <turgor/io/xdmf.h>
#include <turgor/parallel/rank_reductions.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>
#include <algorithm>

namespace turgor {

/* Signed area of a quadrilateral (shoelace over its four vertices in cell order) at the points
   x + u (x: 2 per vertex; u: 3 per vertex, or NULL). */
static PetscReal QuadArea(const PetscInt *cell, const std::vector<PetscReal> &x, const PetscReal *u)
{
  return PolygonSignedArea(4, [&](size_t k) {
    const PetscInt i = cell[k];
    return Point2{x[2 * i] + (u ? u[3 * i] : 0), x[2 * i + 1] + (u ? u[3 * i + 1] : 0)};
  });
}

/* One dataset of the snapshot: this rank's block of `a` (bs values an entry), the blocks in rank
   order, written collectively (VecView of an MPI Vec on the HDF5 viewer) */
PetscErrorCode CoarseFieldsWriter::WriteArray(const char *name, const std::vector<PetscReal> &a, PetscInt bs)
{
  Vec v;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPIWithArray(comm_, bs, (PetscInt)a.size(), PETSC_DECIDE, a.empty() ? nullptr : a.data(), &v));
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
  PetscInt           vs, ve, cs, ce, counts[2];
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
  std::vector<PetscInt> gid(g, g + (ve - vs)); /* global number of each local vertex, -(number + 1) where another rank owns it */
  PetscCall(ISRestoreIndices(gnum, &g));

  /* this rank's owned vertices, by global number: DMPlex numbers them consecutively, rank after
     rank, so the file's vertex array is the ranks' blocks in order */
  owned_.clear();
  for (PetscInt v = 0; v < ve - vs; v++)
    if (gid[v] >= 0) owned_.push_back(v);
  std::sort(owned_.begin(), owned_.end(), [&](PetscInt a, PetscInt b) { return gid[a] < gid[b]; });
  counts[0]         = (PetscInt)owned_.size();
  counts[1]         = ce - cs;
  PetscInt first[2] = {0, 0};
  PetscCallMPI(MPI_Exscan(counts, first, 2, MPIU_INT, MPI_SUM, comm_));
  if (rank_ == 0) first[0] = first[1] = 0;
  PetscInt scrambled = -1; /* the lowest rank whose owned vertices are not its block (every rank learns it) */
  for (size_t k = 0; k < owned_.size(); k++)
    if (gid[owned_[k]] != first[0] + (PetscInt)k) scrambled = rank_;
  if (scrambled < 0) scrambled = PETSC_MAX_INT;
  PetscCall(MinOverRanks(comm_, &scrambled));
  PetscCheck(scrambled == PETSC_MAX_INT, comm_, PETSC_ERR_PLIB,
             "coarse fields: rank %" PetscInt_FMT "'s owned vertices are not a consecutive block of the vertex numbering", scrambled);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm_));
  n_vertices_ = counts[0];
  n_cells_    = counts[1];

  /* the local vertices' coordinates (ghosts too: the density of an element reads all four); the
     elements: their four vertices, as local indices and as global numbers, counter-clockwise */
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetLocalSection(cdm, &csec));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &x));
  xy_.assign(2 * (ve - vs), 0);
  for (PetscInt v = vs; v < ve; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(csec, v, &off));
    xy_[2 * (v - vs)]     = PetscRealPart(x[off]);
    xy_[2 * (v - vs) + 1] = PetscRealPart(x[off + 1]);
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  cells_.clear();
  std::vector<PetscInt> conn;
  for (PetscInt c = cs; c < ce; c++) {
    PetscInt *cl = NULL, n;
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &n, &cl));
    for (PetscInt r = 0; r < n; r++)
      if (cl[2 * r] >= vs && cl[2 * r] < ve) {
        const PetscInt v = cl[2 * r] - vs;
        cells_.push_back(v);
        conn.push_back(gid[v] >= 0 ? gid[v] : -(gid[v] + 1));
      }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &n, &cl));
  }
  PetscInt not_quads = cells_.size() != 4 * (size_t)(ce - cs);
  PetscCall(MaxOverRanks(comm_, &not_quads));
  PetscCheck(!not_quads, comm_, PETSC_ERR_SUP, "coarse fields: the elements are not quadrilaterals");
  rho0_ = model.ReferenceDensity();
  area0_.resize(ce - cs);
  for (PetscInt c = 0; c < ce - cs; c++) area0_[c] = QuadArea(&cells_[4 * c], xy_, NULL);

  PetscCall(PetscViewerHDF5Open(comm_, (dir + "/" + h5name_).c_str(), FILE_MODE_WRITE, &viewer_));
  PetscCall(PetscViewerHDF5PushGroup(viewer_, "/mesh"));
  std::vector<PetscReal> own_xy(2 * owned_.size());
  for (size_t k = 0; k < owned_.size(); k++)
    for (int d = 0; d < 2; d++) own_xy[2 * k + d] = xy_[2 * owned_[k] + d];
  PetscCall(WriteArray("vertices", own_xy, 2));
  IS is;
  PetscCall(ISCreateGeneral(comm_, (PetscInt)conn.size(), conn.data(), PETSC_COPY_VALUES, &is));
  PetscCall(ISSetBlockSize(is, 4));
  PetscCall(PetscObjectSetName((PetscObject)is, "cells"));
  PetscCall(ISView(is, viewer_));
  PetscCall(ISDestroy(&is));
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Components [offset, offset + 1] of every local vertex of a global vector V of the model's layout
   into `local` (2 a local vertex, ghosts too), and this rank's owned vertices' as 3 a vertex (z = 0)
   into `owned`; the clamped vertices get their boundary values (state) or 0 */
PetscErrorCode CoarseFieldsWriter::VertexVector(CoarseModel &model, Vec V, PetscInt offset, bool boundary_values, std::vector<PetscReal> *local,
                                                std::vector<PetscReal> &owned)
{
  DM                 dm  = model.GetDM();
  Vec                loc = boundary_values ? Uloc_ : Vloc_;
  PetscSection       ls;
  PetscInt           vs, ve;
  const PetscScalar *u;
  PetscFunctionBeginUser;
  if (boundary_values) PetscCall(model.GlobalToLocal(V, loc));
  else { /* the constrained entries stay 0 */ PetscCall(VecZeroEntries(loc));
    PetscCall(DMGlobalToLocal(dm, V, INSERT_VALUES, loc));
  }
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  PetscCall(VecGetArrayRead(loc, &u));
  std::vector<PetscReal> all(2 * (ve - vs));
  for (PetscInt v = vs; v < ve; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ls, v, &off));
    for (int d = 0; d < 2; d++) all[2 * (v - vs) + d] = PetscRealPart(u[off + offset + d]);
  }
  PetscCall(VecRestoreArrayRead(loc, &u));
  owned.assign(3 * owned_.size(), 0);
  for (size_t k = 0; k < owned_.size(); k++)
    for (int d = 0; d < 2; d++) owned[3 * k + d] = all[2 * owned_[k] + d];
  if (local) local->swap(all);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseFieldsWriter::Write(CoarseModel &model, Vec U, PetscReal time, const std::vector<Vec> &vectors)
{
  std::vector<PetscReal>              disp_local, disp, vel;
  std::vector<std::vector<PetscReal>> extra(extra_.size());
  PetscFunctionBeginUser;
  PetscCheck(vectors.size() == extra_.size(), comm_, PETSC_ERR_ARG_SIZ, "CoarseFieldsWriter::Write: %zu vertex vectors for %zu added fields", vectors.size(),
             extra_.size());
  /* vectors with z = 0 (ParaView's Xdmf3 readers keep 2-component vectors as such, and Warp By
     Vector takes only 3) */
  PetscCall(VertexVector(model, U, 0, true, &disp_local, disp));
  PetscCall(VertexVector(model, U, 2, true, nullptr, vel));
  for (size_t k = 0; k < extra_.size(); k++) PetscCall(VertexVector(model, vectors[k], 0, false, nullptr, extra[k]));
  /* this rank's elements: the stress as a 3 x 3 tensor (row-major, the z row and column 0: the
     model is 2D) beside its three components; the density of the element, its mass over its current
     area: rho0 A0 / A (rho dv = rho0 dV, as in the mass matrix) */
  const std::vector<PetscReal> &stress = model.CellStress();
  const PetscInt                nc     = (PetscInt)area0_.size();
  PetscCheck((PetscInt)stress.size() == 3 * nc, PETSC_COMM_SELF, PETSC_ERR_PLIB, "coarse fields: %zu stress values for %" PetscInt_FMT " elements",
             stress.size(), nc);
  std::vector<PetscReal> sigma(9 * nc, 0), sxx(nc), syy(nc), sxy(nc), rho(nc), u3(3 * disp_local.size() / 2, 0);
  for (size_t v = 0; v < disp_local.size() / 2; v++) u3[3 * v] = disp_local[2 * v], u3[3 * v + 1] = disp_local[2 * v + 1];
  for (PetscInt c = 0; c < nc; c++) {
    sxx[c]           = stress[3 * c];
    syy[c]           = stress[3 * c + 1];
    sxy[c]           = stress[3 * c + 2];
    sigma[9 * c]     = sxx[c];
    sigma[9 * c + 1] = sxy[c];
    sigma[9 * c + 3] = sxy[c];
    sigma[9 * c + 4] = syy[c];
    rho[c]           = rho0_ * area0_[c] / QuadArea(&cells_[4 * c], xy_, u3.data());
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
  if (acoustic_) PetscCall(WriteArray("acoustic_min_det", model.CellAcoustic(), 1));
  for (size_t k = 0; k < extra_.size(); k++) PetscCall(WriteArray(extra_[k].name.c_str(), extra[k], 3));
  PetscCall(PetscViewerHDF5WriteAttribute(viewer_, group, "time", PETSC_REAL, &time));
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  hid_t fid;
  PetscCall(PetscViewerHDF5GetFileId(viewer_, &fid));
  PetscInt flush_failed = H5Fflush(fid, H5F_SCOPE_GLOBAL) < 0;
  PetscCall(MaxOverRanks(comm_, &flush_failed)); /* every rank stops, not only the one that saw it */
  PetscCheck(!flush_failed, comm_, PETSC_ERR_FILE_WRITE, "Cannot flush %s", h5name_.c_str());
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
