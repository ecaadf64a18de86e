#pragma once
/* The material "polygon_rve": a periodic RVE of K polygonal cells (the L-hyphen cell model: bars,
   hinges with plasticity, contact with friction, turgor laws, glue that breaks, dashpots), relaxed
   for the coarse (F, Fdot) like the square-grid RVE (rve.h: the same equations, relaxation, virial
   stress and exact tangents), its geometry from periodic_polygons.h. The physics are the fine
   polygon terms themselves (-physics, the same options), acting on x = F X + w with w periodic; the
   cells' neighbours across the box's faces are explicit periodic images (periodic_cell.h). The
   terms' history (plastic angles, contact springs, glue bonds and damage) moves on at every accepted
   coarse step and goes back on a rejected one. */
#include <turgor/rve/rve.h>
#include <turgor/tissue/periodic_polygons.h>

namespace turgor {

class PolygonRVEMaterial : public RVEMaterialBase {
public:
  const char    *Name() const override { return "polygon_rve"; }
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) override;
  void           ParticlesPerPoint(PetscInt *wall, PetscInt *fluid) const override;
  PetscErrorCode View(PetscViewer viewer) const override;
  void           Describe(JsonObject &js) const override;

  PeriodicPolygonSpec geometry; /* (spec: the relaxation, -rve_*; -rve_cells is the square grid's) */
  PolygonTissueSpec   poly;

protected:
  bool ShareReferenceState() const override { return true; } /* a cold solve: ~10 LU factorisations of G' */
};

} // namespace turgor
