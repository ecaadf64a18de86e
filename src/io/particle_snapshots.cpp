#include <turgor/io/particle_snapshots.h>
#include <turgor/io/xdmf.h>
#include <turgor/core/geometry.h>
#include <algorithm>
#include <cmath>
#include <petscdmswarm.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>

namespace turgor {

/* This rank's slab of an ordered integer table (w per row) as an HDF5 integer dataset (an IS:
   PetscInt, NumberType="Int" in the XDMF; ISView makes it rows x w, rows x 1 for w = 1). */
static PetscErrorCode WriteIntegers(MPI_Comm comm, PetscViewer viewer, const char *name, const std::vector<PetscInt> &slab, int w)
{
  IS is;
  PetscFunctionBeginUser;
  PetscCall(ISCreateGeneral(comm, (PetscInt)slab.size(), slab.data(), PETSC_COPY_VALUES, &is));
  if (w > 1) PetscCall(ISSetBlockSize(is, w));
  PetscCall(PetscObjectSetName((PetscObject)is, name));
  PetscCall(ISView(is, viewer));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The ordered ids of a table (64 bits: a glue bond's PairKey) as the dataset `path` (rows), each
   rank its slab; collective. */
static PetscErrorCode WriteIds(MPI_Comm comm, PetscViewer viewer, const std::string &path, const KeyOrder &order)
{
  hid_t fid;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(viewer, &fid));
  hsize_t dims[1] = {(hsize_t)order.Count()}, start[1] = {(hsize_t)order.SlabStart()}, count[1] = {(hsize_t)order.SlabRows()};
  hid_t   space = H5Screate_simple(1, dims, NULL), mem = H5Screate_simple(1, count, NULL);
  hid_t   d = H5Dcreate2(fid, path.c_str(), H5T_NATIVE_UINT64, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  PetscCheck(d >= 0, comm, PETSC_ERR_FILE_WRITE, "Snapshots: cannot create the dataset %s", path.c_str());
  if (count[0] > 0) H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
  else {
    H5Sselect_none(space);
    H5Sselect_none(mem);
  }
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  const std::uint64_t none = 0; /* a rank with no rows still passes a buffer */
  herr_t              e    = dims[0] > 0 ? H5Dwrite(d, H5T_NATIVE_UINT64, mem, space, dxpl, count[0] > 0 ? order.SlabKeys().data() : &none) : 0;
  H5Pclose(dxpl);
  H5Sclose(mem);
  H5Sclose(space);
  H5Dclose(d);
  PetscCheck(e >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Snapshots: cannot write the dataset %s", path.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The slab's rows (vertex cells): row r of the file is particle id r. */
static std::vector<PetscInt> SlabRows(const KeyOrder &order)
{
  std::vector<PetscInt> rows((size_t)order.SlabRows());
  for (PetscInt r = 0; r < order.SlabRows(); r++) rows[r] = order.SlabStart() + r;
  return rows;
}

PetscErrorCode ParticleSnapshotWriter::Open(DM swarm, const ParticleSet &P, const PetscReal *x, const std::string &dir, const std::string &base)
{
  PetscInt n, ns = (PetscInt)P.OwnedSprings();
  PetscFunctionBeginUser;
  PetscCall(Close());
  PetscCall(PetscObjectGetComm((PetscObject)swarm, &comm_));
  dir_     = dir;
  h5name_  = base + ".h5";
  xmfpath_ = dir + "/" + base + ".xmf";
  times_.clear();
  segment_meta_.clear();
  PetscCall(DMSwarmGetLocalSize(swarm, &n));
  PetscCheck(n == P.NumOwned(), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Snapshots: the swarm holds %" PetscInt_FMT " particles, the tissue owns %" PetscInt_FMT, n,
             P.NumOwned());
  /* the particles by id: the file's row of a particle is its id (the connectivity names particles by id) */
  {
    std::vector<std::uint64_t> ids((size_t)n);
    for (PetscInt i = 0; i < n; i++) ids[i] = (std::uint64_t)P.gid[i];
    PetscCall(nodes_.SetUp(comm_, ids, "Snapshots: the particle ids"));
    PetscInt gap = 0;
    for (PetscInt r = 0; r < nodes_.SlabRows(); r++) gap |= nodes_.SlabKeys()[r] != (std::uint64_t)(nodes_.SlabStart() + r);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &gap, 1, MPIU_INT, MPI_MAX, comm_));
    PetscCheck(!gap, comm_, PETSC_ERR_ARG_WRONG, "Snapshots: the particle ids are not 0 .. %" PetscInt_FMT " - 1", nodes_.Count());
  }
  PetscCall(PetscViewerHDF5Open(comm_, (dir + "/" + h5name_).c_str(), FILE_MODE_WRITE, &viewer_));
  PetscCall(DMSwarmGetSize(swarm, &n_global_));
  PetscCallMPI(MPI_Allreduce(&ns, &n_springs_, 1, MPIU_INT, MPI_SUM, comm_));
  bars_local_ = P.OwnedSprings();

  /* static data */
  PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
  {
    PetscInt             *kind, *cell, bs;
    PetscDataType         type;
    std::vector<PetscInt> slab, fixed(P.fixed.begin(), P.fixed.begin() + n);
    PetscCall(DMSwarmGetField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(nodes_.Order(kind, 1, slab));
    PetscCall(DMSwarmRestoreField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(WriteIntegers(comm_, viewer_, "kind", slab, 1));
    PetscCall(DMSwarmGetField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(nodes_.Order(cell, 1, slab));
    PetscCall(DMSwarmRestoreField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(WriteIntegers(comm_, viewer_, "cell", slab, 1));
    PetscCall(nodes_.Order(fixed.data(), 1, slab));
    PetscCall(WriteIntegers(comm_, viewer_, "fixed", slab, 1));
    /* the Polyvertex connectivity: one vertex cell per particle (without it Xdmf3 builds no cells),
       and the particles' ids (the same numbers: row = id) */
    slab = SlabRows(nodes_);
    PetscCall(WriteIntegers(comm_, viewer_, "vertices", slab, 1));
    PetscCall(WriteIntegers(comm_, viewer_, "particle_id", slab, 1));
    /* spring connectivity by particle id, as an (ns x 2) integer dataset in bar-id order */
    std::vector<std::uint64_t> bar_ids((size_t)ns);
    std::vector<PetscInt>      conn(2 * ns);
    for (PetscInt s = 0; s < ns; s++) {
      bar_ids[s]      = (std::uint64_t)P.SpringGid((size_t)s);
      conn[2 * s]     = P.gid[P.springs[s].i];
      conn[2 * s + 1] = P.gid[P.springs[s].j];
    }
    PetscCall(bars_order_.SetUp(comm_, bar_ids, "Snapshots: the bar ids"));
    PetscCall(bars_order_.Order(conn.data(), 2, slab));
    PetscCall(WriteIntegers(comm_, viewer_, "springs", slab, 2));
    slab.resize((size_t)bars_order_.SlabRows());
    for (PetscInt r = 0; r < bars_order_.SlabRows(); r++) slab[r] = (PetscInt)bars_order_.SlabKeys()[r];
    PetscCall(WriteIntegers(comm_, viewer_, "bar_id", slab, 1));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  /* polygonal tissues: the closed cells as Polygon (all the same size) or Mixed topology, by cell id */
  polys_.clear();
  area0_.clear();
  bars_.clear();
  cells_order_.Reset();
  n_polys_ = mixed_size_ = nodes_per_poly_ = 0;
  PetscInt     any                         = P.polygons.empty() ? 0 : 1;
  const size_t npoly                       = P.OwnedPolygons();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_INT, MPI_MAX, comm_));
  if (!any) PetscFunctionReturn(PETSC_SUCCESS);
  std::vector<std::uint64_t> ids;
  for (size_t c = 0; c < npoly; c++)
    if (!P.polygons[c].open) {
      polys_.push_back(P.polygons[c].nodes);
      area0_.push_back(PolygonArea(P.polygons[c].nodes, x));
      ids.push_back((std::uint64_t)P.PolygonGid(c));
    }
  bars_.assign(P.springs.begin(), P.springs.begin() + bars_local_);
  PetscInt np = (PetscInt)polys_.size(), lo = PETSC_MAX_INT, hi = 0, size = 0;
  for (auto &c : polys_) lo = PetscMin(lo, (PetscInt)c.size()), hi = PetscMax(hi, (PetscInt)c.size()), size += 2 + (PetscInt)c.size();
  PetscCallMPI(MPI_Allreduce(&np, &n_polys_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPIU_INT, MPI_MIN, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPIU_INT, MPI_MAX, comm_));
  PetscCallMPI(MPI_Allreduce(&size, &mixed_size_, 1, MPIU_INT, MPI_SUM, comm_));
  nodes_per_poly_ = lo == hi ? lo : 0;
  PetscCall(cells_order_.SetUp(comm_, ids, "Snapshots: the cell ids"));
  /* every cell's row of hi + 2 entries (Mixed: type code 3 and node count first), the nodes by id,
     ordered by cell id; then each row without its padding */
  const int             w = (int)hi + 2;
  std::vector<PetscInt> rows((size_t)w * polys_.size(), -1), slab, conn;
  for (size_t c = 0; c < polys_.size(); c++) {
    PetscInt *row = rows.data() + (size_t)w * c;
    row[0]        = 3; /* XDMF's Polygon type code in a Mixed topology */
    row[1]        = (PetscInt)polys_[c].size();
    for (size_t k = 0; k < polys_[c].size(); k++) row[2 + k] = P.gid[polys_[c][k]];
  }
  PetscCall(cells_order_.Order(rows.data(), w, slab));
  for (PetscInt r = 0; r < cells_order_.SlabRows(); r++) {
    const PetscInt *row = slab.data() + (size_t)w * r;
    conn.insert(conn.end(), row + (nodes_per_poly_ ? 2 : 0), row + 2 + row[1]);
  }
  PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
  PetscCall(WriteIntegers(comm_, viewer_, "polygons", conn, (int)nodes_per_poly_)); /* (n x k), as the XDMF says */
  slab.resize((size_t)cells_order_.SlabRows());
  for (PetscInt r = 0; r < cells_order_.SlabRows(); r++) slab[r] = (PetscInt)cells_order_.SlabKeys()[r]; /* the tissue's cell number */
  PetscCall(WriteIntegers(comm_, viewer_, "cell_id", slab, 1));
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A dataset of this snapshot: `components` values per item of `order`, written in id order, a
   2-vector with z = 0 (ParaView's filters take 3-component vectors). */
PetscErrorCode ParticleSnapshotWriter::WriteOrdered(KeyOrder &order, const std::string &name, const PetscReal *values, int components)
{
  Vec                    v;
  PetscScalar           *a;
  std::vector<PetscReal> slab;
  PetscFunctionBeginUser;
  PetscCall(order.Order(values, components, slab));
  const PetscInt out = components == 2 ? 3 : components, n = order.SlabRows();
  if (out == components) /* the slab itself (no copy) */
    PetscCall(VecCreateMPIWithArray(comm_, out, out * n, PETSC_DETERMINE, slab.empty() ? nullptr : slab.data(), &v));
  else {
    PetscCall(VecCreateMPI(comm_, out * n, PETSC_DETERMINE, &v));
    if (out > 1) PetscCall(VecSetBlockSize(v, out));
    PetscCall(VecGetArray(v, &a));
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt d = 0; d < out; d++) a[out * i + d] = d < components ? slab[components * i + d] : 0.0;
    PetscCall(VecRestoreArray(v, &a));
  }
  PetscCall(PetscObjectSetName((PetscObject)v, name.c_str()));
  PetscCall(VecView(v, viewer_));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Per snapshot: A/A0 of every closed cell, the callers' cell fields and every bar's strain. */
PetscErrorCode ParticleSnapshotWriter::WritePolygonFields(const PetscReal *x, const std::vector<Field> &cell_fields)
{
  PetscFunctionBeginUser;
  const PetscInt         np = (PetscInt)polys_.size(), nb = (PetscInt)bars_.size();
  std::vector<PetscReal> ratio(np), strain(nb);
  for (PetscInt c = 0; c < np; c++) ratio[c] = PolygonArea(polys_[c], x) / area0_[c];
  for (PetscInt b = 0; b < nb; b++)
    strain[b] = std::hypot(x[2 * bars_[b].j] - x[2 * bars_[b].i], x[2 * bars_[b].j + 1] - x[2 * bars_[b].i + 1]) / bars_[b].rest_length - 1;
  PetscCall(WriteOrdered(cells_order_, "area_ratio", ratio.data(), 1));
  PetscCall(WriteOrdered(bars_order_, "bar_strain", strain.data(), 1));
  field_names_.clear();
  field_units_.clear();
  for (const Field &f : cell_fields) {
    PetscCheck((PetscInt)f.Size() == np, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Cell field %s has %zu values for %" PetscInt_FMT " closed cells", f.name.c_str(),
               f.Size(), np);
    PetscCall(WriteOrdered(cells_order_, f.name, f.Data(), 1));
    field_names_.push_back(f.name);
    field_units_.push_back(f.unit);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every rank must pass the same fields (each writes its share of every dataset): compared by a hash
   of their names, so that a rank that lacks one fails with a message instead of waiting. */
PetscErrorCode ParticleSnapshotWriter::CheckSameFields(const Fields &fields)
{
  std::uint64_t h   = 1469598103934665603ull;
  auto          mix = [&h](const std::string &s) {
    for (unsigned char c : s + '\n') h = (h ^ c) * 1099511628211ull;
  };
  PetscFunctionBeginUser;
  for (const auto *list : {&fields.nodes, &fields.cells, &fields.bars}) {
    for (const Field &f : *list) mix(f.name);
    mix("|");
  }
  for (const Segments &g : fields.segments) {
    mix(g.name);
    for (const Field &f : g.fields) mix(f.name);
  }
  std::uint64_t range[2] = {h, ~h};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, range, 2, MPI_UINT64_T, MPI_MAX, comm_));
  PetscCheck(range[0] == ~range[1], comm_, PETSC_ERR_ARG_WRONG,
             "Snapshots: the ranks pass different fields (every rank passes every field, with no values where it holds no items)");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticleSnapshotWriter::Write(DM swarm, PetscReal time, const PetscReal *x, const PetscReal *vel, const Fields &fields)
{
  char     group[64];
  PetscInt nlocal;
  PetscFunctionBeginUser;
  PetscCall(DMSwarmGetLocalSize(swarm, &nlocal));
  PetscCall(CheckSameFields(fields));
  node_meta_.clear();
  bar_meta_.clear();
  for (const Field &f : fields.nodes) {
    PetscCheck((f.components == 1 || f.components == 2) && (PetscInt)f.Size() == f.components * nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "Node field %s: %zu values for %" PetscInt_FMT " particles x %d components", f.name.c_str(), f.Size(), nlocal, f.components);
    node_meta_.push_back({f.name, f.unit, {}, f.components});
  }
  for (const Field &f : fields.bars) {
    PetscCheck(f.components == 1 && f.Size() == bars_local_, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Bar field %s: %zu values for %zu springs", f.name.c_str(),
               f.Size(), bars_local_);
    bar_meta_.push_back({f.name, f.unit, {}, 1});
  }
  PetscCheck(n_polys_ > 0 || fields.cells.empty(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Cell fields given for a tissue without closed polygonal cells");
  PetscCall(PetscSNPrintf(group, sizeof group, "/snapshot_%04d", (int)times_.size()));
  PetscCall(PetscViewerHDF5PushGroup(viewer_, group));
  /* Plain Vecs rather than DMSwarmCreateGlobalVectorFromField(): VecView of a swarm Vec forces its
     own group and time-stepping layout, and we want one self-describing group per snapshot. The
     positions stay (n x 2), an XY geometry; the velocity is written (n x 3) with z = 0, since
     ParaView's Xdmf3 readers keep a 2-component vector as 2 components and no filter takes it. */
  {
    std::vector<PetscReal> slab;
    Vec                    v;
    PetscCall(nodes_.Order(x, 2, slab));
    PetscCall(VecCreateMPIWithArray(comm_, 2, (PetscInt)slab.size(), PETSC_DETERMINE, slab.empty() ? nullptr : slab.data(), &v));
    PetscCall(PetscObjectSetName((PetscObject)v, "position"));
    PetscCall(VecView(v, viewer_));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(WriteOrdered(nodes_, "velocity", vel, 2));
  for (const Field &f : fields.nodes) PetscCall(WriteOrdered(nodes_, f.name, f.Data(), f.components));
  for (const Field &f : fields.bars) PetscCall(WriteOrdered(bars_order_, f.name, f.Data(), 1));
  for (const Segments &g : fields.segments) { /* end points (2 per segment, n x 2 as the geometry) in id order, then the fields */
    const size_t nloc = g.xy.size() / 4;
    PetscCheck(g.id.size() == nloc, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Segments %s: %zu ids for %zu segments", g.name.c_str(), g.id.size(), nloc);
    auto it = std::find_if(segment_meta_.begin(), segment_meta_.end(), [&](const SegmentsMeta &m) { return m.name == g.name; });
    if (it == segment_meta_.end()) { /* the first snapshot: their order, ids and static connectivity, point pairs 2k, 2k + 1 */
      SegmentsMeta m;
      m.name  = g.name;
      m.first = times_.size();
      m.ids   = g.id;
      m.order = std::make_unique<KeyOrder>();
      PetscCall(m.order->SetUp(comm_, m.ids, ("Snapshots: the ids of the segments " + g.name).c_str()));
      m.count = m.order->Count();
      std::vector<PetscInt> conn(2 * (size_t)m.order->SlabRows());
      for (size_t k = 0; k < conn.size(); k++) conn[k] = 2 * m.order->SlabStart() + (PetscInt)k;
      PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
      PetscCall(WriteIntegers(comm_, viewer_, (g.name + "_segments").c_str(), conn, 2));
      PetscCall(PetscViewerHDF5PopGroup(viewer_));
      PetscCall(WriteIds(comm_, viewer_, "/static/" + g.name + "_id", *m.order));
      segment_meta_.push_back(std::move(m));
      it = segment_meta_.end() - 1;
    }
    PetscInt changed = g.id != it->ids;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPIU_INT, MPI_MAX, comm_));
    PetscCheck(!changed, comm_, PETSC_ERR_ARG_WRONG, "Segments %s: not the segments of the first snapshot (their ids or their order on a rank changed)",
               g.name.c_str());
    it->fields.clear();
    { /* the end points: (2 n) x 3 with z = 0, an XYZ geometry */
      std::vector<PetscReal> slab;
      Vec                    v;
      PetscScalar           *a;
      PetscCall(it->order->Order(g.xy.data(), 4, slab));
      const PetscInt points = 2 * it->order->SlabRows();
      PetscCall(VecCreateMPI(comm_, 3 * points, PETSC_DETERMINE, &v));
      PetscCall(VecSetBlockSize(v, 3));
      PetscCall(PetscObjectSetName((PetscObject)v, (g.name + "_xy").c_str()));
      PetscCall(VecGetArray(v, &a));
      for (PetscInt p = 0; p < points; p++) a[3 * p] = slab[2 * p], a[3 * p + 1] = slab[2 * p + 1], a[3 * p + 2] = 0;
      PetscCall(VecRestoreArray(v, &a));
      PetscCall(VecView(v, viewer_));
      PetscCall(VecDestroy(&v));
    }
    for (const Field &f : g.fields) {
      PetscCheck(f.Size() == nloc, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Segment field %s: %zu values for %zu segments", f.name.c_str(), f.Size(), nloc);
      PetscCall(WriteOrdered(*it->order, g.name + "_" + f.name, f.Data(), 1));
      it->fields.push_back({f.name, f.unit, {}, 1});
    }
  }
  if (n_polys_ > 0) PetscCall(WritePolygonFields(x, fields.cells));
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
      if (grid == 1) PetscCall(xdmf.Attribute("bar_id", "Scalar", "Cell", "values", "the tissue's bar id", {XdmfDims(S, 1), true, "/static/bar_id"}));
      if (grid == 1)
        for (const Field &f : bar_meta_) PetscCall(xdmf.Attribute(f.name, "Scalar", "Cell", "unit", f.unit, snapshot(f.name, XdmfDims(S))));
      if (grid == 2) {
        PetscCall(xdmf.Attribute("cell_id", "Scalar", "Cell", "values", "the tissue's cell id", {XdmfDims(NP, 1), true, "/static/cell_id"}));
        PetscCall(xdmf.Attribute("area_ratio", "Scalar", "Cell", "unit", "1", snapshot("area_ratio", XdmfDims(NP))));
        for (size_t f = 0; f < field_names_.size(); f++)
          PetscCall(xdmf.Attribute(field_names_[f], "Scalar", "Cell", "unit", field_units_[f], snapshot(field_names_[f], XdmfDims(NP))));
        PetscCall(xdmf.EndGrid());
        continue;
      }
      if (grid == 1 && n_polys_ > 0) PetscCall(xdmf.Attribute("bar_strain", "Scalar", "Cell", "unit", "1 (l / l0 - 1)", snapshot("bar_strain", XdmfDims(S))));
      const char *ints[4][2] = {
        {"particle_id", "the tissue's particle id (the row in this file)"        },
        {"kind",        "0 wall, 1 fluid"                                        },
        {"cell",        "tissue cell of a fluid particle, -1 for a wall particle"},
        {"fixed",       "1 clamped (position and velocity held), 0 free"         }
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
