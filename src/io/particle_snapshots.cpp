#include <turgor/io/particle_snapshots.h>
#include <turgor/io/xdmf.h>
#include <turgor/core/geometry.h>
#include <algorithm>
#include <cmath>
#include <petscdmswarm.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>

namespace turgor {

/* Write a per-particle integer (or char) array, or the global particle numbers when data is NULL,
   as an HDF5 integer dataset (an IS: PetscInt, NumberType="Int" in the XDMF; ISView makes it n x 1). */
template <typename T>
static PetscErrorCode WriteIntegerField(MPI_Comm comm, PetscViewer viewer, const char *name, const T *data, PetscInt n, PetscInt start)
{
  IS                    is;
  std::vector<PetscInt> a(n);
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) a[i] = data ? (PetscInt)data[i] : start + i;
  PetscCall(ISCreateGeneral(comm, n, a.data(), PETSC_COPY_VALUES, &is));
  PetscCall(PetscObjectSetName((PetscObject)is, name));
  PetscCall(ISView(is, viewer));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A particle's row in the file: an owned one's is this rank's offset + its index; a distributed
   run's halo copy is another rank's row (ParticleSet::halo_index). */
static PetscInt FileIndex(const ParticleSet &P, PetscInt start, PetscInt i)
{
  return i < P.NumOwned() ? start + i : P.halo_index[i - P.NumOwned()];
}

PetscErrorCode ParticleSnapshotWriter::Open(DM swarm, const ParticleSet &P, const PetscReal *x, const std::string &dir, const std::string &base)
{
  PetscInt n, start = 0, ns = (PetscInt)P.OwnedSprings();
  PetscFunctionBeginUser;
  PetscCall(Close());
  PetscCall(PetscObjectGetComm((PetscObject)swarm, &comm_));
  dir_     = dir;
  h5name_  = base + ".h5";
  xmfpath_ = dir + "/" + base + ".xmf";
  times_.clear();
  PetscCall(DMSwarmGetLocalSize(swarm, &n));
  PetscCallMPI(MPI_Exscan(&n, &start, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCall(PetscViewerHDF5Open(comm_, (dir + "/" + h5name_).c_str(), FILE_MODE_WRITE, &viewer_));
  PetscCall(DMSwarmGetSize(swarm, &n_global_));
  PetscCallMPI(MPI_Allreduce(&ns, &n_springs_, 1, MPIU_INT, MPI_SUM, comm_));
  bars_local_ = P.OwnedSprings();

  /* static data */
  PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
  {
    PetscInt     *kind, *cell, bs;
    PetscDataType type;
    PetscCall(DMSwarmGetField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(WriteIntegerField(comm_, viewer_, "kind", kind, n, start));
    PetscCall(DMSwarmRestoreField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(DMSwarmGetField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(WriteIntegerField(comm_, viewer_, "cell", cell, n, start));
    PetscCall(DMSwarmRestoreField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(WriteIntegerField(comm_, viewer_, "fixed", P.fixed.data(), n, start));
    /* the Polyvertex connectivity: one vertex cell per particle (without it Xdmf3 builds no cells) */
    PetscCall(WriteIntegerField<PetscInt>(comm_, viewer_, "vertices", NULL, n, start));
    /* spring connectivity in global particle numbering, as an (ns x 2) integer dataset */
    std::vector<PetscInt> conn(2 * ns);
    for (PetscInt s = 0; s < ns; s++) {
      conn[2 * s]     = FileIndex(P, start, P.springs[s].i);
      conn[2 * s + 1] = FileIndex(P, start, P.springs[s].j);
    }
    IS is;
    PetscCall(ISCreateGeneral(comm_, 2 * ns, conn.data(), PETSC_COPY_VALUES, &is));
    PetscCall(ISSetBlockSize(is, 2));
    PetscCall(PetscObjectSetName((PetscObject)is, "springs"));
    PetscCall(ISView(is, viewer_));
    PetscCall(ISDestroy(&is));
  }
  /* polygonal tissues: the closed cells as Polygon (all the same size) or Mixed topology */
  polys_.clear();
  area0_.clear();
  bars_.clear();
  n_polys_ = mixed_size_ = nodes_per_poly_ = 0;
  PetscInt     any                         = P.polygons.empty() ? 0 : 1;
  const size_t npoly                       = P.OwnedPolygons();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_INT, MPI_MAX, comm_));
  if (any) {
    for (size_t c = 0; c < npoly; c++)
      if (!P.polygons[c].open) {
        polys_.push_back(P.polygons[c].nodes);
        area0_.push_back(PolygonArea(P.polygons[c].nodes, x));
      }
    bars_.assign(P.springs.begin(), P.springs.begin() + bars_local_);
    PetscInt np = (PetscInt)polys_.size(), lo = PETSC_MAX_INT, hi = 0, size = 0;
    for (auto &c : polys_) lo = PetscMin(lo, (PetscInt)c.size()), hi = PetscMax(hi, (PetscInt)c.size()), size += 2 + (PetscInt)c.size();
    PetscCallMPI(MPI_Allreduce(&np, &n_polys_, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPIU_INT, MPI_MIN, comm_));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPIU_INT, MPI_MAX, comm_));
    PetscCallMPI(MPI_Allreduce(&size, &mixed_size_, 1, MPIU_INT, MPI_SUM, comm_));
    nodes_per_poly_ = lo == hi ? lo : 0;
    std::vector<PetscInt> conn, ids;
    for (size_t c = 0; c < npoly; c++) {
      if (P.polygons[c].open) continue;
      if (!nodes_per_poly_) {
        conn.push_back(3); /* XDMF's Polygon type code in a Mixed topology */
        conn.push_back((PetscInt)P.polygons[c].nodes.size());
      }
      for (PetscInt i : P.polygons[c].nodes) conn.push_back(FileIndex(P, start, i));
      ids.push_back(P.polygon_gid.empty() ? (PetscInt)c : P.polygon_gid[c]); /* the tissue's cell number (a distributed run numbers per rank) */
    }
    PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
    IS is;
    PetscCall(ISCreateGeneral(comm_, (PetscInt)conn.size(), conn.data(), PETSC_COPY_VALUES, &is));
    if (nodes_per_poly_) PetscCall(ISSetBlockSize(is, nodes_per_poly_)); /* (n x k), as the XDMF says */
    PetscCall(PetscObjectSetName((PetscObject)is, "polygons"));
    PetscCall(ISView(is, viewer_));
    PetscCall(ISDestroy(&is));
    PetscCall(WriteIntegerField(comm_, viewer_, "cell_id", ids.data(), (PetscInt)ids.size(), 0));
    PetscCall(PetscViewerHDF5PopGroup(viewer_));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A distributed dataset of this snapshot: `components` values per item, a 2-vector written with z = 0
   (ParaView's filters take 3-component vectors). */
PetscErrorCode ParticleSnapshotWriter::WriteVector(const std::string &name, const std::vector<PetscReal> &values, int components)
{
  Vec          v;
  PetscScalar *a;
  PetscFunctionBeginUser;
  const PetscInt out = components == 2 ? 3 : components, n = (PetscInt)values.size() / components;
  PetscCall(VecCreateMPI(comm_, out * n, PETSC_DETERMINE, &v));
  if (out > 1) PetscCall(VecSetBlockSize(v, out));
  PetscCall(PetscObjectSetName((PetscObject)v, name.c_str()));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt d = 0; d < out; d++) a[out * i + d] = d < components ? values[components * i + d] : 0.0;
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecView(v, viewer_));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Per snapshot: A/A0 of every closed cell, the callers' cell fields and every bar's strain. */
PetscErrorCode ParticleSnapshotWriter::WritePolygonFields(const PetscReal *x, const std::vector<Field> &cell_fields)
{
  PetscFunctionBeginUser;
  const PetscInt                                              np = (PetscInt)polys_.size(), nb = (PetscInt)bars_.size();
  std::vector<std::pair<std::string, std::vector<PetscReal>>> fields;
  {
    std::vector<PetscReal> ratio(np), strain(nb);
    for (PetscInt c = 0; c < np; c++) ratio[c] = PolygonArea(polys_[c], x) / area0_[c];
    for (PetscInt b = 0; b < nb; b++)
      strain[b] = std::hypot(x[2 * bars_[b].j] - x[2 * bars_[b].i], x[2 * bars_[b].j + 1] - x[2 * bars_[b].i + 1]) / bars_[b].rest_length - 1;
    fields.push_back({"area_ratio", ratio});
    fields.push_back({"bar_strain", strain});
  }
  field_names_.clear();
  field_units_.clear();
  for (const Field &f : cell_fields) {
    PetscCheck((PetscInt)f.values.size() == np, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Cell field %s has %zu values for %" PetscInt_FMT " closed cells",
               f.name.c_str(), f.values.size(), np);
    fields.push_back({f.name, f.values});
    field_names_.push_back(f.name);
    field_units_.push_back(f.unit);
  }
  for (auto &f : fields) PetscCall(WriteVector(f.first, f.second, 1));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticleSnapshotWriter::Write(DM swarm, PetscReal time, const PetscReal *x, const PetscReal *vel, const Fields &fields)
{
  char     group[64];
  Vec      v;
  PetscInt nlocal;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(swarm, &nlocal));
  node_meta_.clear();
  bar_meta_.clear();
  for (const Field &f : fields.nodes) {
    PetscCheck((f.components == 1 || f.components == 2) && (PetscInt)f.values.size() == f.components * nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "Node field %s: %zu values for %" PetscInt_FMT " particles x %d components", f.name.c_str(), f.values.size(), nlocal, f.components);
    node_meta_.push_back({f.name, f.unit, {}, f.components});
  }
  for (const Field &f : fields.bars) {
    PetscCheck(f.components == 1 && f.values.size() == bars_local_, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Bar field %s: %zu values for %zu springs",
               f.name.c_str(), f.values.size(), bars_local_);
    bar_meta_.push_back({f.name, f.unit, {}, 1});
  }
  PetscCall(PetscSNPrintf(group, sizeof group, "/snapshot_%04d", (int)times_.size()));
  PetscCall(PetscViewerHDF5PushGroup(viewer_, group));
  /* Plain Vecs rather than DMSwarmCreateGlobalVectorFromField(): VecView of a swarm Vec forces its
     own group and time-stepping layout, and we want one self-describing group per snapshot. The
     positions stay (n x 2), an XY geometry; the velocity is written (n x 3) with z = 0, since
     ParaView's Xdmf3 readers keep a 2-component vector as 2 components and no filter takes it. */
  for (const char *field : {"position", "velocity"}) {
    const PetscReal *data = field[0] == 'v' ? vel : x;
    const PetscInt   bs = 2, out = field[0] == 'v' ? 3 : bs;
    PetscScalar     *a;
    PetscCall(VecCreateMPI(comm_, out * nlocal, PETSC_DETERMINE, &v));
    PetscCall(VecSetBlockSize(v, out));
    PetscCall(PetscObjectSetName((PetscObject)v, field));
    PetscCall(VecGetArray(v, &a));
    for (PetscInt i = 0; i < nlocal; i++)
      for (PetscInt d = 0; d < out; d++) a[out * i + d] = d < bs ? data[bs * i + d] : 0.0;
    PetscCall(VecRestoreArray(v, &a));
    PetscCall(VecView(v, viewer_));
    PetscCall(VecDestroy(&v));
  }
  for (const Field &f : fields.nodes) PetscCall(WriteVector(f.name, f.values, f.components));
  for (const Field &f : fields.bars) PetscCall(WriteVector(f.name, f.values, 1));
  for (const Segments &g : fields.segments) { /* end points (2 per segment, n x 2 as the geometry), then the fields */
    PetscInt nloc = (PetscInt)g.xy.size() / 4, ntot, start = 0;
    PetscCallMPI(MPI_Allreduce(&nloc, &ntot, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCallMPI(MPI_Exscan(&nloc, &start, 1, MPIU_INT, MPI_SUM, comm_));
    auto it = std::find_if(segment_meta_.begin(), segment_meta_.end(), [&](const SegmentsMeta &m) { return m.name == g.name; });
    if (it == segment_meta_.end()) { /* the first snapshot: the static connectivity, point pairs 2k, 2k + 1 */
      std::vector<PetscInt> conn(2 * nloc);
      for (PetscInt k = 0; k < 2 * nloc; k++) conn[k] = 2 * start + k;
      IS is;
      PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
      PetscCall(ISCreateGeneral(comm_, 2 * nloc, conn.data(), PETSC_COPY_VALUES, &is));
      PetscCall(ISSetBlockSize(is, 2));
      PetscCall(PetscObjectSetName((PetscObject)is, (g.name + "_segments").c_str()));
      PetscCall(ISView(is, viewer_));
      PetscCall(ISDestroy(&is));
      PetscCall(PetscViewerHDF5PopGroup(viewer_));
      SegmentsMeta m;
      m.name  = g.name;
      m.count = ntot;
      m.first = times_.size();
      segment_meta_.push_back(m);
      it = segment_meta_.end() - 1;
    }
    PetscCheck(it->count == ntot, comm_, PETSC_ERR_ARG_SIZ, "Segments %s: %" PetscInt_FMT " in this snapshot, %" PetscInt_FMT " in the first", g.name.c_str(),
               ntot, it->count);
    it->fields.clear();
    PetscCall(WriteVector(g.name + "_xy", g.xy, 2)); /* (2 n) x 3, z = 0: an XYZ geometry */
    for (const Field &f : g.fields) {
      PetscCheck((PetscInt)f.values.size() == nloc, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Segment field %s: %zu values for %" PetscInt_FMT " segments",
                 f.name.c_str(), f.values.size(), nloc);
      PetscCall(WriteVector(g.name + "_" + f.name, f.values, 1));
      it->fields.push_back({f.name, f.unit, {}, 1});
    }
  }
  if (n_polys_ > 0) PetscCall(WritePolygonFields(x, fields.cells));
  else PetscCheck(fields.cells.empty(), comm_, PETSC_ERR_ARG_WRONG, "Cell fields given for a tissue without polygonal cells");
  PetscCall(PetscViewerHDF5WriteAttribute(viewer_, group, "time", PETSC_REAL, &time));
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  {
    hid_t fid;
    PetscCall(PetscViewerHDF5GetFileId(viewer_, &fid));
    PetscCheck(H5Fflush(fid, H5F_SCOPE_GLOBAL) >= 0, comm_, PETSC_ERR_FILE_WRITE, "Cannot flush %s", h5name_.c_str());
  }
  times_.push_back(time);
  PetscCall(WriteXdmf());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The XDMF (2.0, read by ParaView's Xdmf3 readers and by its legacy XDMF reader): per snapshot a
   grid of the particles (a Polyvertex of one vertex cell per particle) and one of the wall springs
   (a Polyline of two-point cells) through the same points; polygonal tissues add the cells, and
   segment terms their segments (io/xdmf.h: the elements and their units). */
PetscErrorCode ParticleSnapshotWriter::WriteXdmf()
{
  XdmfWriter      xdmf;
  const long long N = n_global_, S = n_springs_, NP = n_polys_;
  PetscFunctionBeginUser;
  PetscCall(xdmf.Open(comm_, xmfpath_, h5name_, "length µm, time µs, mass ng; velocity µm/µs, force µN"));
  const char *grids[3] = {"particles", "walls", "cells"};
  for (int grid = 0; grid < (n_polys_ > 0 ? 3 : 2); grid++) {
    PetscCall(xdmf.BeginCollection(grids[grid]));
    for (size_t k = 0; k < times_.size(); k++) {
      auto snapshot = [k](const std::string &name, const std::string &dims) { return XdmfData{dims, false, XdmfSnapshotPath(k, name)}; };
      PetscCall(xdmf.BeginGrid(grids[grid], k, times_[k]));
      if (grid == 2 && nodes_per_poly_) PetscCall(xdmf.Topology("Polygon", NP, nodes_per_poly_, {XdmfDims(NP, nodes_per_poly_), true, "/static/polygons"}));
      else if (grid == 2) PetscCall(xdmf.Topology("Mixed", NP, 0, {XdmfDims(mixed_size_, 1), true, "/static/polygons"}));
      else if (grid) PetscCall(xdmf.Topology("Polyline", S, 2, {XdmfDims(S, 2), true, "/static/springs"}));
      else PetscCall(xdmf.Topology("Polyvertex", N, 1, {XdmfDims(N, 1), true, "/static/vertices"}));
      PetscCall(xdmf.Geometry("XY", "µm", snapshot("position", XdmfDims(N, 2))));
      PetscCall(xdmf.Attribute("velocity", "Vector", "Node", "unit", "µm/µs", snapshot("velocity", XdmfDims(N, 3))));
      if (grid < 2)
        for (const Field &f : node_meta_) /* a scalar is written (N), a vector (N x 3) */
          PetscCall(
            xdmf.Attribute(f.name, f.components == 2 ? "Vector" : "Scalar", "Node", "unit", f.unit, snapshot(f.name, XdmfDims(N, f.components == 2 ? 3 : 0))));
      if (grid == 1)
        for (const Field &f : bar_meta_) PetscCall(xdmf.Attribute(f.name, "Scalar", "Cell", "unit", f.unit, snapshot(f.name, XdmfDims(S))));
      if (grid == 2) {
        PetscCall(xdmf.Attribute("cell_id", "Scalar", "Cell", "values", "index in the tissue's polygons", {XdmfDims(NP, 1), true, "/static/cell_id"}));
        PetscCall(xdmf.Attribute("area_ratio", "Scalar", "Cell", "unit", "1", snapshot("area_ratio", XdmfDims(NP))));
        for (size_t f = 0; f < field_names_.size(); f++)
          PetscCall(xdmf.Attribute(field_names_[f], "Scalar", "Cell", "unit", field_units_[f], snapshot(field_names_[f], XdmfDims(NP))));
        PetscCall(xdmf.EndGrid());
        continue;
      }
      if (grid == 1 && n_polys_ > 0) PetscCall(xdmf.Attribute("bar_strain", "Scalar", "Cell", "unit", "1 (l / l0 - 1)", snapshot("bar_strain", XdmfDims(S))));
      const char *ints[3][2] = {
        {"kind",  "0 wall, 1 fluid"                                        },
        {"cell",  "tissue cell of a fluid particle, -1 for a wall particle"},
        {"fixed", "1 clamped (position and velocity held), 0 free"         }
      };
      for (const auto &a : ints) PetscCall(xdmf.Attribute(a[0], "Scalar", "Node", "values", a[1], {XdmfDims(N, 1), true, std::string("/static/") + a[0]}));
      PetscCall(xdmf.EndGrid());
    }
    PetscCall(xdmf.EndCollection());
  }
  for (const SegmentsMeta &m : segment_meta_) { /* line segments with their own end points (the glue bonds) */
    const long long M = m.count;
    PetscCall(xdmf.BeginCollection(m.name));
    for (size_t k = m.first; k < times_.size(); k++) {
      PetscCall(xdmf.BeginGrid(m.name, k, times_[k]));
      PetscCall(xdmf.Topology("Polyline", M, 2, {XdmfDims(M, 2), true, "/static/" + m.name + "_segments"}));
      PetscCall(xdmf.Geometry("XYZ", "µm", {XdmfDims(2 * M, 3), false, XdmfSnapshotPath(k, m.name + "_xy")}));
      for (const Field &f : m.fields)
        PetscCall(xdmf.Attribute(f.name, "Scalar", "Cell", "unit", f.unit, {XdmfDims(M), false, XdmfSnapshotPath(k, m.name + "_" + f.name)}));
      PetscCall(xdmf.EndGrid());
    }
    PetscCall(xdmf.EndCollection());
  }
  PetscCall(xdmf.Close());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticleSnapshotWriter::Close()
{
  PetscFunctionBeginUser;
  if (viewer_) PetscCall(PetscViewerDestroy(&viewer_));
  viewer_ = nullptr;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
