#pragma once
/* -tissue_type voronoi: Voronoi or Laguerre (power-diagram) cells in a box, from a seeded random
   point set, with Lloyd relaxation, shrunk by the bar radius so that neighbours are 2 r apart. */
#include <turgor/core/parameters.h>
#include <turgor/tissue/polygon_tissue.h>

namespace turgor {

/* Options -tissue_voronoi_cells N, -tissue_box xmin,ymin,xmax,ymax, -tissue_seed S,
   -tissue_lloyd_steps K, -tissue_size_cv c, -tissue_gap g (prefix tissue_). */
struct VoronoiSpec {
  PetscInt  cells       = 256;              /* 16 x 16 cells of 25 µm on average, like the square grid */
  PetscReal box[4]      = {0, 0, 400, 400}; /* µm */
  PetscInt  seed        = 1;
  PetscInt  lloyd_steps = 0;
  PetscReal size_cv     = 0; /* target coefficient of variation of the cell areas; 0: plain Voronoi */
  PetscReal gap         = 0; /* µm between neighbouring cells' bar surfaces (each cell shrunk by r + g/2) */

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
};

/* A convex cell of a power diagram, counter-clockwise: edge k joins v[k] to v[k+1]; across it lies
   cell label[k] (>= 0) or a side of the box (-1 bottom, -2 right, -3 top, -4 left). Empty: no cell. */
struct PowerCell {
  std::vector<Point2>   v;
  std::vector<PetscInt> label;
};

/* The diagram before shrinking: seeds, weights (power distance |x - s|^2 - w), target areas (cv > 0)
   and the cells that tile the box. */
struct VoronoiDiagram {
  std::vector<Point2>    seeds;
  std::vector<PetscReal> weights, targets;
  std::vector<PowerCell> cells;
  PetscInt               weight_iterations = 0; /* Laguerre weight updates done */
  PetscReal              max_area_error    = 0; /* largest |A - target| / target at the end (cv > 0) */
};

/* The seeds of a power diagram binned on a grid (a counting sort: a seed's order in its bin is its
   index order), from which any one cell is built on its own: the box clipped by the power bisectors
   of the nearby seeds, visited ring by ring of bins until the security radius says no farther seed
   can cut the cell. The same cell, bit for bit, whichever others are built. */
class PowerCells {
public:
  PowerCells() = default;
  PowerCells(const PetscReal box[4], std::vector<Point2> seeds, std::vector<PetscReal> weights);
  size_t                     Size() const { return seeds_.size(); }
  const std::vector<Point2> &Seeds() const { return seeds_; }
  PetscReal                  Weight(size_t i) const { return weights_.empty() ? (PetscReal)0 : weights_[i]; }
  /* cell i (scratch: work space) */
  PetscErrorCode Cell(size_t i, PowerCell *cell, PowerCell *scratch) const;

private:
  PetscReal              box_[4] = {0, 0, 0, 0}, cw_ = 1, ch_ = 1, hmin_ = 1, wmax_ = 0;
  PetscInt               gx_ = 1, gy_ = 1;
  std::vector<Point2>    seeds_;
  std::vector<PetscReal> weights_; /* empty: all 0 (Voronoi) */
  std::vector<PetscInt>  start_, bin_;
  void                   BinOf(const Point2 &p, PetscInt *ix, PetscInt *iy) const;
};

/* Power cells of the seeds in the box: each cell is the box clipped by the power bisectors of the
   nearby seeds, found on a grid and stopped by the security radius (a seed farther than the bound
   cannot cut the cell). O(N x neighbours). */
PetscErrorCode ComputePowerDiagram(const PetscReal box[4], const std::vector<Point2> &seeds, const std::vector<PetscReal> &weights,
                                   std::vector<PowerCell> *cells);
/* Seeds, Lloyd steps and (cv > 0) Laguerre weights: everything up to the shrinking. */
PetscErrorCode BuildVoronoiDiagram(MPI_Comm comm, const VoronoiSpec &spec, VoronoiDiagram *diagram);
/* The cell shrunk by r (every edge moved inward by r), with edges shorter than min_edge merged;
   empty if nothing is left. */
void ShrinkPowerCell(const PowerCell &cell, PetscReal r, PetscReal min_edge, std::vector<Point2> *out);
/* The tissue: the diagram, its cells shrunk by poly.bar_radius + spec.gap / 2, edges cut into bars. `diagram`
   (optional) receives the diagram before shrinking. */
PetscErrorCode GenerateVoronoiTissue(MPI_Comm comm, const VoronoiSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue, VoronoiDiagram *diagram = nullptr);

/* The tissue in parts (TissueGenerator::GeneratePart): PrepareParts runs the Lloyd steps with each
   rank building the cells of one range of seeds (their new seeds gathered to every rank after each
   step), then counts every cell's nodes the same way; the cells' space order is the Hilbert curve
   through their seeds. Every rank keeps the seeds, their bins and the node offsets of all cells
   (about 60 B a cell against some 300 B for each of a cell's nodes); a part's cells are built from
   them exactly as the whole tissue's are, so a part is the whole tissue's bit for bit. With
   -tissue_size_cv the Laguerre weights are fitted on the whole diagram on every rank (a Newton
   solve over all cells), its power cells freed before the parts are built. Plates and a
   -tissue_cut_box number the cells after the whole tissue: not in parts. */
class VoronoiGenerator : public PolygonGenerator<VoronoiSpec> {
public:
  const char    *Name() const override { return "voronoi"; }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GenerateVoronoiTissue(comm, spec, poly, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
  PetscInt       NumCellsOfParts() const override;
  std::string    PartsRefused() const override;
  PetscErrorCode PrepareParts(MPI_Comm comm) override;
  PetscInt       CellPlace(PetscInt gid) const override { return place_[(size_t)gid]; }
  PetscErrorCode GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const override;

private:
  PetscErrorCode        Ring(size_t i, PolygonRing *ring, PowerCell *cell, PowerCell *scratch) const; /* cell i shrunk (empty if it vanished) */
  PowerCells            cells_;                                                                       /* the final seeds and weights */
  std::vector<PetscInt> place_, node_start_;              /* each cell's place in the space order; its first node (and bar) [cells + 1] */
  PetscReal             radius_ = 0;                      /* the largest distance from a seed to a corner of its power cell */
  PetscReal             lo_[2] = {0, 0}, hi_[2] = {0, 0}; /* the whole tissue's bounding box */
};

} // namespace turgor
