#pragma once
/* -tissue_type polyline: one open chain of nodes and bars on a straight segment (a beam, a wall). */
#include <turgor/core/parameters.h>
#include <turgor/tissue/polygon_tissue.h>

namespace turgor {

/* Options -tissue_polyline_start x,y, -tissue_polyline_end x,y, -tissue_polyline_nodes N (prefix
   tissue_polyline_). The default is the L-hyphen model's cantilever chain: 101 nodes 0.01 apart. */
struct PolylineSpec {
  PetscReal start[2] = {0, 0};
  PetscReal end[2]   = {1, 0};
  PetscInt  nodes    = 101;

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
};

/* N equally spaced nodes from start to end, N - 1 bars, one open PolygonCell. */
PetscErrorCode GeneratePolylineTissue(MPI_Comm comm, const PolylineSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue);

class PolylineGenerator : public PolygonGenerator<PolylineSpec, false> {
public:
  const char    *Name() const override { return "polyline"; }
  PetscErrorCode Generate(MPI_Comm comm, Tissue *tissue) const override { return GeneratePolylineTissue(comm, spec, poly, tissue); }
  PetscErrorCode Estimate(PetscReal *particles, PetscReal *springs) const override;
  std::string    SizeOptions() const override;
  PetscErrorCode View(PetscViewer viewer) const override;
};

} // namespace turgor
