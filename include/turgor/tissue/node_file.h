#pragma once
/* -tissue_type node_file: polygonal cells read from a node file in the format of the L-hyphen code:
   one node per line "x y cellId", a cell's nodes listed together, in order around its polygon.
   Blank lines and lines starting with '#' are skipped. */
#include <turgor/tissue/polygon_tissue.h>
#include <string>

namespace turgor {

/* Options -tissue_node_file PATH, -tissue_length_scale s, -tissue_open_cells id,id,... (prefix tissue_). */
struct NodeFileSpec {
  std::string           path;
  PetscReal             length_scale = 1; /* file coordinates x s = µm */
  std::vector<PetscInt> open_cells;       /* cell ids (as in the file) that are open chains */

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
};

/* Read spec.path: cell ids must run in steps of one from the first (each cell's nodes together),
   closed cells need >= 3 nodes (open ones >= 2), no zero-length bar, no self-intersecting polygon;
   a clockwise closed cell is reversed (its first node stays first). Errors name the file and line. */
PetscErrorCode GenerateNodeFileTissue(MPI_Comm comm, const NodeFileSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue);
/* Write the tissue's polygons as a node file (cell ids from 0, coordinates to 17 digits, so that
   reading it back with -tissue_length_scale 1 gives the same tissue bit for bit). */
PetscErrorCode WriteNodeFile(MPI_Comm comm, const std::string &path, const Tissue &tissue);

class NodeFileGenerator : public PolygonGenerator<NodeFileSpec> {
public:
  const char    *Name() const override { return "node_file"; }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GenerateNodeFileTissue(comm, spec, poly, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
};

} // namespace turgor
