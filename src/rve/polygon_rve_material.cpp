#include <turgor/rve/polygon_rve_material.h>
#include <turgor/core/memory.h>
#include <turgor/io/output.h>
#include <turgor/physics/glue.h>
#include <algorithm>

namespace turgor {

PetscErrorCode PolygonRVEMaterial::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscFunctionBeginUser;
  PetscCall(geometry.SetFromOptions(comm, params));
  PetscCall(poly.SetFromOptions(comm, true, params));
  PetscCheck(!poly.has_cut_box, comm, PETSC_ERR_ARG_INCOMP, "Option -tissue_cut_box: a periodic RVE (-material polygon_rve) has no notch to cut");
  PetscCheck(!poly.plates.Any(), comm, PETSC_ERR_ARG_INCOMP, "Option -tissue_plates: a periodic RVE (-material polygon_rve) has no sides for plates");
  spec.psi_rule = PseudoStepRule::SER; /* contact and glue are piecewise: the seed's schedule overshoots their kinks */
  spec.warm_dt0 = 1e8;                 /* walls bend through hinges of ~1e-4 in the scaled units: a shift 1/warm_dt0 near that stalls modified Newton */
  PetscCall(spec.SetFromOptions(comm, params));
  physics.names      = {"bars", "hinges", "pressure", "contact", "glue"};
  physics.with_loads = false; /* the body force is a load on the coarse model, not part of the material */
  PetscCall(physics.SetFromOptions(comm, TermContext{nullptr, params}));
  bool joined = false;
  for (const auto &t : physics.Terms()) {
    const std::string n = t->Name();
    PetscCheck(n != "springs" && n != "repulsion" && n != "sph", comm, PETSC_ERR_ARG_INCOMP,
               "Option -physics: term '%s' belongs to the square-grid cells (-material rve), not to polygonal cells (-material polygon_rve)", n.c_str());
    joined = joined || n == "glue" || n == "contact";
  }
  for (const auto &t : physics.Terms())
    if (const Glue *g = dynamic_cast<const Glue *>(t.get()))
      PetscCheck(geometry.gap < g->distance, comm, PETSC_ERR_ARG_INCOMP,
                 "Options -prve_gap = %g, -glue_distance = %g: the glue bonds cells closer than 2 r + its distance, and these are 2 r + gap apart: no "
                 "bond would be made (a gap below the gluing distance)",
                 (double)geometry.gap, (double)g->distance);
  PetscCheck(joined, comm, PETSC_ERR_ARG_INCOMP,
             "Option -physics: -material polygon_rve needs glue or contact between its cells (without, each cell floats free and the RVE has no stiffness)");
  {
    ParticleSet probe; /* the terms' reach depends only on the bar radius */
    probe.bar_radius = poly.bar_radius;
    PetscReal reach  = 0;
    for (const auto &t : physics.Terms()) reach = std::max(reach, t->Reach(probe));
    std::vector<PolygonRing> rings;
    PetscReal                period[2];
    PetscCall(PeriodicPolygonRings(comm, geometry, poly.bar_radius, &rings, period));
    PetscCall(prototype_.SetUpPolygons(comm, rings, poly, period, reach + physics.neighbour_skin, geometry.halo_margin));
  }
  const PetscReal   particles = (PetscReal)prototype_.GetTissue().particles.n;
  const std::string what      = "one RVE of -prve_cells " + std::to_string((long long)geometry.cells) + " (" + std::to_string((long long)particles) +
                           " nodes with its periodic images)";
  PetscCall(CheckCount(comm, 2 * particles, what));
  PetscCall(CheckMemory(comm, BytesPerPoint(), what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void PolygonRVEMaterial::ParticlesPerPoint(PetscInt *wall, PetscInt *fluid) const
{
  *wall  = prototype_.GetTissue().particles.NumOwned();
  *fluid = 0;
}

void PolygonRVEMaterial::Describe(JsonObject &js) const
{
  const ParticleSet &P = prototype_.GetTissue().particles;
  js.Set("rve_lattice", std::string(geometry.LatticeName()));
  js.Set("rve_cells", geometry.cells);
  js.Set("rve_nodes", P.NumOwned());
  js.Set("rve_bars", (PetscInt)P.OwnedSprings());
  js.Set("rve_image_nodes", P.n - P.NumOwned());
}

PetscErrorCode PolygonRVEMaterial::View(PetscViewer viewer) const
{
  const char *const  modes[] = {"relaxed", "cauchy_born", "frozen"};
  const ParticleSet &P       = prototype_.GetTissue().particles;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "material polygon_rve: %" PetscInt_FMT " periodic %s cells of %g µm (%" PetscInt_FMT " nodes, %zu bars; %" PetscInt_FMT
                                   " image nodes within %g µm), %s, Psi-tc atol %g, steptol %g, at most %" PetscInt_FMT " iterations\n",
                                   geometry.cells, geometry.LatticeName(), (double)geometry.cell_size, P.NumOwned(), P.OwnedSprings(), P.n - P.NumOwned(),
                                   (double)(prototype_.Reach() + geometry.halo_margin), modes[(int)spec.relax], (double)spec.psi_atol, (double)spec.psi_steptol,
                                   spec.max_it));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
