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

class VoronoiGenerator : public PolygonGenerator<VoronoiSpec> {
public:
  const char    *Name() const override { return "voronoi"; }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GenerateVoronoiTissue(comm, spec, poly, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
};

} // namespace turgor
