static const char help[] = "Snapshots of a polygonal tissue: a hand-built tissue of two closed polygons (a quadrilateral and a pentagon,\n"
                           "Mixed topology; or two quadrilaterals with -quads, Polygon topology), one node pulled by a velocity control,\n"
                           "run by FineRun with springs; particles.xmf then holds the cells grid that check_paraview.py polygons checks\n"
                           "(polygon cells, cell_id, area_ratio against the areas of the points ParaView reads).\n";
#include "test_util.h"
#include <array>
#include <turgor/physics/wall_springs.h>

using namespace turgor;

/* Add a closed polygon (counter-clockwise) of new nodes, with its bars. */
static void AddPolygon(Tissue &T, const std::vector<std::array<PetscReal, 2>> &pts)
{
  PolygonCell    c;
  const PetscInt id = (PetscInt)T.particles.polygons.size();
  for (auto &p : pts) c.nodes.push_back(T.AddParticle(p[0], p[1], 0.5, KIND_WALL));
  for (size_t k = 0; k < c.nodes.size(); k++) {
    c.bars.push_back((PetscInt)T.particles.springs.size());
    T.AddSpring(c.nodes[k], c.nodes[(k + 1) % c.nodes.size()]);
  }
  T.particles.polygons.push_back(c);
  T.cell_walls.push_back(c.nodes);
  T.particles.node_polygon.resize(T.particles.n, -1);
  for (PetscInt i : c.nodes) T.particles.node_polygon[i] = id;
}

int main(int argc, char **argv)
{
  PetscBool quads                   = PETSC_FALSE;
  char      dir[PETSC_MAX_PATH_LEN] = "polygon_snapshots";
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-quads", &quads, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-dir", dir, sizeof dir, NULL));
  Tissue T;
  AddPolygon(T, {{{0, 0}}, {{10, 0}}, {{10, 10}}, {{0, 10}}});
  if (quads) AddPolygon(T, {{{12, 0}}, {{22, 0}}, {{22, 10}}, {{12, 10}}});
  else AddPolygon(T, {{{12, 0}}, {{22, 0}}, {{24, 6}}, {{17, 12}}, {{12, 10}}});
  T.particles.bar_radius = 1;
  T.Finalize();
  const PetscInt pulled = quads ? 5 : 6; /* (22, 0) or (24, 6) */
  {
    FineRun run(PETSC_COMM_WORLD);
    auto    springs        = std::make_unique<WallSprings>();
    springs->stiffness     = 0.01; /* soft: the pulled node stretches its bars, the rest hardly moves */
    springs->damping_ratio = 0;
    run.Physics().names    = {};
    run.Physics().Add(std::move(springs));
    ControlGroup g;
    g.name     = "pull";
    g.node_ids = {pulled};
    g.value[0] = 1.0;
    g.value[1] = 0;
    run.GetControls().Add(g);
    run.Spec().clamp               = {"none"};
    run.Output().dir               = dir;
    run.Output().samples           = 4;
    run.Output().overwrite         = true;
    run.Output().snapshots         = 2;
    run.Output().progress_interval = 0;
    PetscCall(run.SetFromOptions());
    run.SetTissue(T);
    PetscCall(TSSetMaxTime(run.GetTS(), 2.0));
    PetscCall(run.SetUp());
    PetscCall(run.Solve());
    PetscCall(run.WriteSummary());
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_polygon_snapshots: wrote %s/particles.xmf (%s topology)\n", dir, quads ? "Polygon" : "Mixed"));
  PetscCall(PetscFinalize());
  return 0;
}
