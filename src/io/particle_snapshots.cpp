#include <turgor/io/particle_snapshots.h>
#include <petscdmswarm.h>
#include <petscviewerhdf5.h>
#include <hdf5.h>

namespace turgor {

/* Copy an integer (or char) per-particle array into a named Vec and write it. */
template <typename T>
static PetscErrorCode WriteIntegerField(MPI_Comm comm, PetscViewer viewer, const char *name, const T *data, PetscInt n)
{
  Vec          v;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm, n, PETSC_DETERMINE, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = 0; i < n; i++) a[i] = (PetscScalar)data[i];
  PetscCall(VecRestoreArray(v, &a));
  PetscCall(VecView(v, viewer));
  PetscCall(VecDestroy(&v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticleSnapshotWriter::Open(DM swarm, const ParticleSet &P, const std::string &dir, const std::string &base)
{
  PetscInt n, start = 0, ns = (PetscInt)P.springs.size();
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

  /* static data */
  PetscCall(PetscViewerHDF5PushGroup(viewer_, "/static"));
  {
    PetscInt     *kind, *cell, bs;
    PetscDataType type;
    PetscCall(DMSwarmGetField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(WriteIntegerField(comm_, viewer_, "kind", kind, n));
    PetscCall(DMSwarmRestoreField(swarm, "kind", &bs, &type, (void **)&kind));
    PetscCall(DMSwarmGetField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(WriteIntegerField(comm_, viewer_, "cell", cell, n));
    PetscCall(DMSwarmRestoreField(swarm, "cell", &bs, &type, (void **)&cell));
    PetscCall(WriteIntegerField(comm_, viewer_, "fixed", P.fixed.data(), n));
    /* spring connectivity in global particle numbering, as an (ns x 2) integer dataset */
    std::vector<PetscInt> conn(2 * ns);
    for (PetscInt s = 0; s < ns; s++) {
      conn[2 * s]     = start + P.springs[s].i;
      conn[2 * s + 1] = start + P.springs[s].j;
    }
    IS is;
    PetscCall(ISCreateGeneral(comm_, 2 * ns, conn.data(), PETSC_COPY_VALUES, &is));
    PetscCall(ISSetBlockSize(is, 2));
    PetscCall(PetscObjectSetName((PetscObject)is, "springs"));
    PetscCall(ISView(is, viewer_));
    PetscCall(ISDestroy(&is));
  }
  PetscCall(PetscViewerHDF5PopGroup(viewer_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ParticleSnapshotWriter::Write(DM swarm, PetscReal time)
{
  char group[64];
  Vec  v;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(group, sizeof group, "/snapshot_%04d", (int)times_.size()));
  PetscCall(PetscViewerHDF5PushGroup(viewer_, group));
  /* Plain Vecs rather than DMSwarmCreateGlobalVectorFromField(): VecView of a swarm Vec forces its
     own group and time-stepping layout, and we want one self-describing group per snapshot. */
  for (const char *field : {"position", "velocity"}) {
    PetscInt      n, bs;
    PetscDataType type;
    PetscReal    *data;
    PetscScalar  *a;
    PetscCall(DMSwarmGetLocalSize(swarm, &n));
    PetscCall(DMSwarmGetField(swarm, field, &bs, &type, (void **)&data));
    PetscCall(VecCreateMPI(comm_, bs * n, PETSC_DETERMINE, &v));
    PetscCall(VecSetBlockSize(v, bs));
    PetscCall(PetscObjectSetName((PetscObject)v, field));
    PetscCall(VecGetArray(v, &a));
    for (PetscInt k = 0; k < bs * n; k++) a[k] = data[k];
    PetscCall(VecRestoreArray(v, &a));
    PetscCall(DMSwarmRestoreField(swarm, field, &bs, &type, (void **)&data));
    PetscCall(VecView(v, viewer_));
    PetscCall(VecDestroy(&v));
  }
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

PetscErrorCode ParticleSnapshotWriter::WriteXdmf()
{
  FILE *fp;
  PetscFunctionBeginUser;
  const long long N = n_global_, S = n_springs_;
  const char     *h5 = h5name_.c_str();
  PetscCall(PetscFOpen(comm_, xmfpath_.c_str(), "w", &fp));
  PetscCall(PetscFPrintf(comm_, fp, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n"));
  for (int grid = 0; grid < 2; grid++) {
    PetscCall(PetscFPrintf(comm_, fp, "  <Grid Name=\"%s\" GridType=\"Collection\" CollectionType=\"Temporal\">\n", grid ? "walls" : "particles"));
    for (size_t k = 0; k < times_.size(); k++) {
      PetscCall(PetscFPrintf(comm_, fp, "   <Grid Name=\"%s_%04zu\" GridType=\"Uniform\">\n    <Time Value=\"%.17g\"/>\n", grid ? "walls" : "particles", k,
                             (double)times_[k]));
      if (grid)
        PetscCall(PetscFPrintf(comm_, fp,
                               "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"%lld\" NodesPerElement=\"2\">\n     <DataItem Dimensions=\"%lld 2\" "
                               "NumberType=\"Int\" Precision=\"%d\" Format=\"HDF\">%s:/static/springs</DataItem>\n    </Topology>\n",
                               S, S, (int)sizeof(PetscInt), h5));
      else PetscCall(PetscFPrintf(comm_, fp, "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%lld\" NodesPerElement=\"1\"/>\n", N));
      PetscCall(PetscFPrintf(comm_, fp,
                             "    <Geometry GeometryType=\"XY\">\n     <DataItem Dimensions=\"%lld 2\" NumberType=\"Float\" Precision=\"8\" "
                             "Format=\"HDF\">%s:/snapshot_%04zu/position</DataItem>\n    </Geometry>\n",
                             N, h5, k));
      PetscCall(PetscFPrintf(comm_, fp,
                             "    <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n     <DataItem Dimensions=\"%lld 2\" "
                             "NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">%s:/snapshot_%04zu/velocity</DataItem>\n    </Attribute>\n",
                             N, h5, k));
      for (const char *a : {"kind", "cell", "fixed"})
        PetscCall(PetscFPrintf(comm_, fp,
                               "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Node\">\n     <DataItem Dimensions=\"%lld\" NumberType=\"Float\" "
                               "Precision=\"8\" Format=\"HDF\">%s:/static/%s</DataItem>\n    </Attribute>\n",
                               a, N, h5, a));
      PetscCall(PetscFPrintf(comm_, fp, "   </Grid>\n"));
    }
    PetscCall(PetscFPrintf(comm_, fp, "  </Grid>\n"));
  }
  PetscCall(PetscFPrintf(comm_, fp, " </Domain>\n</Xdmf>\n"));
  PetscCall(PetscFClose(comm_, fp));
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
