#pragma once
/* Rigid-looking plates around a polygonal tissue (-tissue_plates bottom,right,top,left): each is an
   open cell of one bar, parallel to its side of the tissue's bounding box at 2 r from it (a node of
   the tissue there just touches the plate), reaching -tissue_plate_overhang past the tissue. A lid
   or a floor is a plate moved or held by a control group (-control_<name>_plates top). With side
   plates, the top and bottom plates stop 3 r short of their centrelines, so that a lid slides down
   between the walls without touching them and no node (2 r wide) fits through the gap left. */
#include <turgor/core/parameters.h>
#include <turgor/tissue/tissue.h>
#include <array>
#include <string>
#include <vector>

namespace turgor {

struct PolygonRing;

struct PlateSpec {
  std::vector<std::string> sides;         /* any of bottom, right, top, left */
  PetscReal                overhang = -1; /* µm past the tissue; < 0: 10% of the tissue's larger side */

  /* -tissue_plates, -tissue_plate_overhang (prefix tissue_). */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
  bool           Any() const { return !sides.empty(); }
};

/* The plate rings for a tissue whose rings are `rings` (bar radius r), appended to `rings` after the
   tissue's cells in the order bottom, right, top, left; *names gets ("bottom", cell id), ... A bottom
   or top plate that would have no length (a tissue no wider than 2 r between side plates) is an
   error naming -tissue_plates. */
PetscErrorCode AddPlateRings(MPI_Comm comm, const PlateSpec &spec, PetscReal r, std::vector<PolygonRing> *rings,
                             std::vector<std::pair<std::string, PetscInt>> *names);

} // namespace turgor
