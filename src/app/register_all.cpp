/* TurgorRegisterAll(): every pluggable part of turgor, one line each -- TS types, physics terms,
   (later) materials, tissue generators and run modes. */
#include <turgor/app/register_all.h>
#include <turgor/modes/eigen_run.h>
#include <turgor/coarse/fe2_run.h>
#include <turgor/modes/fe2_static_run.h>
#include <turgor/fine/fine_static_run.h>
#include <turgor/fine/fine_run.h>
#include <turgor/material/neo_hookean.h>
#include <turgor/modes/strain_path_run.h>
#include <turgor/physics/bars.h>
#include <turgor/physics/body_force.h>
#include <turgor/physics/cell_pressure.h>
#include <turgor/physics/contact.h>
#include <turgor/physics/dashpots.h>
#include <turgor/physics/glue.h>
#include <turgor/physics/hinges.h>
#include <turgor/physics/repulsion.h>
#include <turgor/physics/sph_fluid.h>
#include <turgor/physics/viscosity.h>
#include <turgor/physics/wall_springs.h>
#include <turgor/rve/rve.h>
#include <turgor/rve/polygon_rve_material.h>
#include <turgor/tissue/node_file.h>
#include <turgor/tissue/polyline.h>
#include <turgor/tissue/square_grid.h>
#include <turgor/tissue/voronoi.h>
#include <turgor/ts/ts_register.h>
#include <turgor/core/errors.h>
#include <slepcsys.h>

namespace {
PetscBool registered = PETSC_FALSE; /* PETSc-style registration flag, cleared at PetscFinalize() */

PetscErrorCode Unregister(void)
{
  registered = PETSC_FALSE;
  return SlepcFinalize(); /* SLEPc did not start PETSc: this only marks it finalised */
}

PetscErrorCode RegisterAll(void)
{
  using namespace turgor;
  PetscFunctionBeginUser;
  if (registered) PetscFunctionReturn(PETSC_SUCCESS);
  /* SLEPc (-mode eigen, the stability monitors) on top of the PETSc the caller initialised */
  PetscCall(SlepcInitializeNoArguments());
  PetscCall(TurgorTSRegisterAll());
  /* physics terms (-physics) */
  PetscCall(ForceTermRegister("springs", CreateInstance<ForceTerm, WallSprings>));
  PetscCall(ForceTermRegister("repulsion", CreateInstance<ForceTerm, Repulsion>));
  PetscCall(ForceTermRegister("sph", CreateInstance<ForceTerm, SPHFluid>));
  PetscCall(ForceTermRegister("body_force", CreateInstance<ForceTerm, BodyForce>));
  PetscCall(ForceTermRegister("bars", CreateInstance<ForceTerm, Bars>));
  PetscCall(ForceTermRegister("hinges", CreateInstance<ForceTerm, Hinges>));
  PetscCall(ForceTermRegister("contact", CreateInstance<ForceTerm, Contact>));
  PetscCall(ForceTermRegister("pressure", CreateInstance<ForceTerm, CellPressure>));
  PetscCall(ForceTermRegister("viscosity", CreateInstance<ForceTerm, Viscosity>));
  PetscCall(ForceTermRegister("glue", CreateInstance<ForceTerm, Glue>));
  PetscCall(ForceTermRegister("dashpots", CreateInstance<ForceTerm, Dashpots>));
  /* materials (-material) */
  PetscCall(MaterialModelRegister("rve", CreateInstance<MaterialModel, RVEMaterial>));
  PetscCall(MaterialModelRegister("neo_hookean", CreateInstance<MaterialModel, NeoHookeanMaterial>));
  PetscCall(MaterialModelRegister("polygon_rve", CreateInstance<MaterialModel, PolygonRVEMaterial>));
  /* tissue generators (-tissue_type) */
  PetscCall(TissueGeneratorRegister("square_grid", CreateInstance<TissueGenerator, SquareGridGenerator>));
  PetscCall(TissueGeneratorRegister("node_file", CreateInstance<TissueGenerator, NodeFileGenerator>));
  PetscCall(TissueGeneratorRegister("voronoi", CreateInstance<TissueGenerator, VoronoiGenerator>));
  PetscCall(TissueGeneratorRegister("polyline", CreateInstance<TissueGenerator, PolylineGenerator>));
  /* run modes (-mode) */
  PetscCall(SimulationRegister("fine", CreateInstance<Simulation, FineRun>));
  PetscCall(SimulationRegister("rve", CreateInstance<Simulation, StrainPathRun>));
  PetscCall(SimulationRegister("fe2", CreateInstance<Simulation, FE2Run>));
  PetscCall(SimulationRegister("fe2_static", CreateInstance<Simulation, FE2StaticRun>));
  PetscCall(SimulationRegister("fine_static", CreateInstance<Simulation, FineStaticRun>));
  PetscCall(SimulationRegister("eigen", CreateInstance<Simulation, EigenRun>));
  PetscCall(PetscRegisterFinalize(Unregister));
  registered = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
} // namespace

/* C linkage (called from C): the registries' std::vector/std::string may throw std::bad_alloc */
PetscErrorCode TurgorRegisterAll(void)
{
  PetscFunctionBeginUser;
  PetscCall(turgor::CatchExceptions(PETSC_FUNCTION_NAME, __LINE__, __FILE__, RegisterAll));
  PetscFunctionReturn(PETSC_SUCCESS);
}
