#pragma once
/* Particle snapshots for ParaView: one HDF5 file (PetscViewerHDF5) with a group per snapshot
   (position n x 2, velocity n x 3 with z = 0) and /static (kind, cell, fixed as integers, the
   vertex and spring connectivity), and an XDMF file describing a temporal collection of two grids,
   the particles (Polyvertex, one vertex cell per particle, with velocity, kind, cell, fixed) and
   the wall springs (Polyline through the same positions), with units. The XDMF file is rewritten
   after every snapshot, so a run that stops early stays readable. */
#include <turgor/particles/particles.h>
#include <petscdm.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace turgor {

class ParticleSnapshotWriter {
public:
  /* `swarm` holds fields "position" and "velocity" (bs 2) and "kind", "cell" (int); `P` gives the
     springs and fixed flags of the local particles (local indices). Files: dir/base.h5, dir/base.xmf. */
  PetscErrorCode Open(DM swarm, const ParticleSet &P, const std::string &dir, const std::string &base);
  PetscErrorCode Write(DM swarm, PetscReal time);
  PetscErrorCode Close();
  ~ParticleSnapshotWriter() { PetscCallVoid(Close()); }
  PetscInt Count() const { return (PetscInt)times_.size(); }

private:
  PetscErrorCode WriteXdmf();

  MPI_Comm               comm_   = MPI_COMM_NULL;
  PetscViewer            viewer_ = nullptr;
  std::string            dir_, h5name_, xmfpath_;
  PetscInt               n_global_ = 0, n_springs_ = 0;
  std::vector<PetscReal> times_;
};

} // namespace turgor
