#pragma once
/* -tissue_type node_file: polygonal cells read from a node file in the format of the L-hyphen code:
   one node per line "x y cellId", a cell's nodes listed together, in order around its polygon.
   Blank lines and lines starting with '#' are skipped. */
#include <turgor/tissue/polygon_tissue.h>
#include <array>
#include <cstdint>
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

/* The tissue in parts (TissueGenerator::GeneratePart): PrepareParts reads the file in byte ranges,
   one a rank (a cell belongs to the range where its first node's line starts, and is read on past
   the range's end to its last node), checks the range's cells as Generate does (the same errors,
   the first in the file named on every rank) and gathers an index of every cell to every rank: where
   it starts in the file, its nodes, its box (about 56 B a cell). The cells' space order is the
   Hilbert curve through their boxes' centres. A part is read from the file by seeking to each of its
   cells: the rank's range of the order and every cell whose box comes within the distance of them.
   A named pipe cannot be read twice: not in parts; nor plates or a -tissue_cut_box (their cells are
   numbered once the whole tissue is built). */
class NodeFileGenerator : public PolygonGenerator<NodeFileSpec> {
public:
  const char    *Name() const override { return "node_file"; }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GenerateNodeFileTissue(comm, spec, poly, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
  /* the cells (after PrepareParts; before it, 0 where the file can be read in parts) */
  PetscInt       NumCellsOfParts() const override;
  std::string    PartsRefused() const override;
  PetscErrorCode PrepareParts(MPI_Comm comm) override;
  PetscInt       CellPlace(PetscInt gid) const override { return place_[(size_t)gid]; }
  PetscErrorCode GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const override;

private:
  /* each cell, in file order: where its first line starts, its first node and bar in the tissue's
     numbering [cells + 1], the box of its nodes (xmin, ymin, xmax, ymax), its place in the space order */
  std::vector<std::uint64_t>            offset_;
  std::vector<PetscInt>                 node_start_, bar_start_, place_;
  std::vector<std::array<PetscReal, 4>> box_;
  long long                             id0_   = 0; /* the first cell's id in the file */
  PetscReal                             lo_[2] = {0, 0}, hi_[2] = {0, 0};
};

} // namespace turgor
