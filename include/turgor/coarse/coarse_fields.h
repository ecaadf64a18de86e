#pragma once
/* Coarse fields for ParaView: one HDF5 file with the quadrilateral mesh (vertices, cells) and a
   group per snapshot (displacement and velocity at the vertices, 3 components with z = 0; per
   element the Cauchy stress as a 3 x 3 tensor and as stress_xx, stress_yy, stress_xy, and the
   density; acoustic_min_det when the model computes it, CoarseSpec::acoustic_field; and any further
   vertex vectors a caller adds, such as mode shapes), and an XDMF file describing the temporal
   collection, with units. Written collectively (PetscViewerHDF5 on the mesh's communicator): each
   rank writes its owned vertices (DMPlex numbers them rank after rank, so the file's vertex order is
   the global numbering) and its elements (in rank order), nothing is gathered to one rank; the XDMF
   (rank 0) is rewritten after every snapshot. */
#include <turgor/coarse/coarse_model.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace turgor {

class CoarseFieldsWriter {
public:
  /* Before Open: a further vertex vector in every snapshot, given to Write as a global vector of the
     model's layout whose displacement components it takes (3 components, z = 0; 0 on the clamped
     vertices). */
  void           AddVertexVector(const std::string &name, const std::string &unit) { extra_.push_back({name, unit}); }
  PetscErrorCode Open(CoarseModel &model, const std::string &dir, const std::string &base);
  /* U global state; the stresses (and acoustic field) of the model's last EvaluateCellStress at U;
     `vectors`: one per AddVertexVector, in that order. */
  PetscErrorCode Write(CoarseModel &model, Vec U, PetscReal time, const std::vector<Vec> &vectors = {});
  PetscErrorCode Close();
  ~CoarseFieldsWriter() { PetscCallVoid(Close()); }
  PetscInt Count() const { return (PetscInt)times_.size(); }

private:
  PetscErrorCode WriteXdmf();
  PetscErrorCode WriteArray(const char *name, const std::vector<PetscReal> &a, PetscInt bs);
  /* components [offset, offset + 1] of a global vector V of the model's layout: every local
     vertex's (2 each, into *local if given) and the owned vertices' (3 each, z = 0); the clamped
     vertices get their boundary values (state) or 0 */
  PetscErrorCode VertexVector(CoarseModel &model, Vec V, PetscInt offset, bool boundary_values, std::vector<PetscReal> *local, std::vector<PetscReal> &owned);

  struct Field {
    std::string name, unit;
  };
  std::vector<Field>     extra_;
  bool                   acoustic_ = false; /* the model's acoustic_min_det is written */
  std::string            grid_;             /* the collection's name: the file's base name */
  MPI_Comm               comm_   = MPI_COMM_NULL;
  PetscMPIInt            rank_   = 0;
  PetscViewer            viewer_ = nullptr;
  std::string            h5name_, xmfpath_;
  PetscInt               n_vertices_ = 0, n_cells_ = 0; /* over all ranks */
  std::vector<PetscInt>  owned_;                        /* this rank's owned vertices (local indices), by global number */
  std::vector<PetscReal> times_;
  Vec                    Uloc_ = nullptr, Vloc_ = nullptr;
  PetscReal              rho0_ = 0;   /* the model's reference density */
  std::vector<PetscReal> xy_, area0_; /* the local vertices' reference coordinates, this rank's elements' areas */
  std::vector<PetscInt>  cells_;      /* this rank's elements' four vertices (local indices) */
};

} // namespace turgor
