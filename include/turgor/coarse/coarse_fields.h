#pragma once
/* Coarse fields for ParaView: one HDF5 file with the quadrilateral mesh (vertices, cells) and a
   group per snapshot (displacement and velocity at the vertices, 3 components with z = 0; per
   element the Cauchy stress as a 3 x 3 tensor and as stress_xx, stress_yy, stress_xy, and the
   density), and an XDMF file describing the temporal collection, with units. The mesh is small:
   rank 0 gathers and writes (PetscViewerHDF5 on PETSC_COMM_SELF); the XDMF is rewritten after
   every snapshot. */
#include <turgor/coarse/coarse_model.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace turgor {

class CoarseFieldsWriter {
public:
  PetscErrorCode Open(CoarseModel &model, const std::string &dir, const std::string &base);
  /* U global state; the stresses of the model's last material evaluation (call after one at U). */
  PetscErrorCode Write(CoarseModel &model, Vec U, PetscReal time);
  PetscErrorCode Close();
  ~CoarseFieldsWriter() { PetscCallVoid(Close()); }
  PetscInt Count() const { return (PetscInt)times_.size(); }

private:
  PetscErrorCode WriteXdmf();
  PetscErrorCode WriteArray(const char *name, const std::vector<PetscReal> &a, PetscInt bs);

  MPI_Comm               comm_   = MPI_COMM_NULL;
  PetscMPIInt            rank_   = 0;
  PetscViewer            viewer_ = nullptr;
  std::string            h5name_, xmfpath_;
  PetscInt               n_vertices_ = 0, n_cells_ = 0;
  std::vector<PetscInt>  vertex_gid_; /* per local vertex: global number, < 0 if not owned */
  std::vector<PetscReal> times_;
  Vec                    Uloc_ = nullptr;
  PetscReal              rho0_ = 0;   /* the model's reference density */
  std::vector<PetscReal> xy_, area0_; /* rank 0: reference vertex coordinates, element areas */
  std::vector<PetscInt>  cells_;      /* rank 0: the four vertices of each element */
};

} // namespace turgor
