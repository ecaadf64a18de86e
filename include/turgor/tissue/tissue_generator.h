#pragma once
/* Tissue generators: each builds a Tissue from its own options (prefix tissue_), chosen by
   -tissue_type. A new generator is one file (a class derived from TissueGenerator) plus one line
   in src/app/register_all.cpp: TissueGeneratorRegister("name", CreateInstance<TissueGenerator, G>). */
#include <turgor/core/parameters.h>
#include <turgor/core/registry.h>
#include <turgor/tissue/tissue.h>
#include <petscviewer.h>
#include <memory>
#include <string>

namespace turgor {

class TissueGenerator {
public:
  virtual ~TissueGenerator()       = default;
  virtual const char *Name() const = 0;
  /* params: where the options read are recorded as the run's physics parameters (may be NULL) */
  virtual PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) = 0;
  virtual PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const        = 0;
  /* Particles and springs the tissue will have, computed in floating point before anything is
     allocated (memory estimates; counts beyond PetscInt). */
  virtual PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const = 0;
  /* The options and values that set the size, for messages ("-tissue_cells_x 4 ..."). */
  virtual std::string    SizeOptions() const            = 0;
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;

  /* Distributed set-up without the whole tissue on any rank (-fine_partitioner ranges). A generator
     that orders its cells in space (a range of places in the order is a compact part) and can build
     a part of its tissue alone returns its number of cells here (-1: it cannot; ranges are refused,
     for the reason PartsRefused() gives). */
  virtual PetscInt    NumCellsOfParts() const { return -1; }
  virtual std::string PartsRefused() const { return "numbers its cells in no spatial order (a range of them is no compact part)"; }
  /* Collective, before CellPlace and GeneratePart: what the parts need that depends on the whole
     tissue (a Voronoi tissue's seeds after the Lloyd steps, each cell's node count). */
  virtual PetscErrorCode PrepareParts(MPI_Comm comm) { return PETSC_SUCCESS; }
  /* The place of cell `gid` in the space order (the square grid: its row-major number). */
  virtual PetscInt CellPlace(PetscInt gid) const { return gid; }
  /* The cells at places [c0, c1) of the space order, every cell within `distance` µm of them and
     one layer of cells more, so that each particle of a cell within `distance` has all its springs
     here: their particles, springs and cells as in the whole tissue (in its order, with its numbers
     in ParticleSet::gid, spring_gid (polygon_gid) and Tissue::cell_gid, and its bounding box),
     joints found as Tissue::Finalize finds them. Not collective. */
  virtual PetscErrorCode GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const
  {
    return PetscError(comm, __LINE__, PETSC_FUNCTION_NAME, __FILE__, PETSC_ERR_SUP, PETSC_ERROR_INITIAL, "tissue generator %s cannot build a part", Name());
  }
};

using TissueGeneratorCreator = Registry<TissueGenerator>::Creator;
PetscErrorCode TissueGeneratorRegister(const char name[], TissueGeneratorCreator create);
PetscErrorCode TissueGeneratorCreate(MPI_Comm comm, const std::string &name, std::unique_ptr<TissueGenerator> *generator);

/* The tissue of a fine run: -tissue_type (API default: square_grid) and that generator's options. */
class TissueSpec {
public:
  std::string type = "square_grid";

  PetscErrorCode   SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
  PetscErrorCode   Generate(MPI_Comm comm, Tissue *tissue) const;
  TissueGenerator *Generator() const { return generator_.get(); }

private:
  std::unique_ptr<TissueGenerator> generator_;
};

} // namespace turgor
