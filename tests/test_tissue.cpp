static const char help[] = "Tissue generator: particle and spring counts, cell polygons, clamps.\n";
#include "test_util.h"

using namespace turgor;

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  {
    /* the seed's 16 x 16 tissue: 833 wall and 4096 SPH particles (TW 562 Fig. 2) */
    SquareGridSpec spec;
    Tissue         T;
    PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
    const ParticleSet &P = T.particles;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "16x16: %" PetscInt_FMT " wall, %" PetscInt_FMT " fluid, %zu springs\n", P.Count(KIND_WALL), P.Count(KIND_FLUID),
                          P.springs.size()));
    TG_CHECK(P.Count(KIND_WALL) == 833, "wall particles %" PetscInt_FMT, P.Count(KIND_WALL));
    TG_CHECK(P.Count(KIND_FLUID) == 4096, "fluid particles %" PetscInt_FMT, P.Count(KIND_FLUID));
    TG_CHECK(P.springs.size() == 1088, "springs %zu", P.springs.size());
    TG_CHECK(T.NumCells() == 256, "cells");
    /* every cell: 8 wall particles, area 625 µm², springs of rest length 12.5 µm */
    for (PetscInt c = 0; c < T.NumCells(); c++) {
      TG_CHECK(T.cell_walls[c].size() == 8, "cell %" PetscInt_FMT " ring", c);
      TG_CHECK_CLOSE(PolygonArea(T.cell_walls[c], T.X.data()), 625.0, 1e-12, 1.0, "cell area");
    }
    for (const Spring &s : P.springs) TG_CHECK_CLOSE(s.rest_length, 12.5, 1e-12, 1.0, "rest length");
    /* fluid mass from 2D density: 0.01 ng/µm² x 625 µm² / 16 */
    for (PetscInt i = 0; i < P.n; i++) TG_CHECK_CLOSE(P.mass[i], P.kind[i] == KIND_FLUID ? 0.390625 : 0.5, 1e-14, 1.0, "particle mass");
    /* each fluid particle lies inside its own cell */
    for (PetscInt i = 0; i < P.n; i++) {
      if (P.kind[i] != KIND_FLUID) continue;
      const PetscInt cx = P.cell[i] % 16, cy = P.cell[i] / 16;
      TG_CHECK(T.X[2 * i] > 25 * cx && T.X[2 * i] < 25 * (cx + 1) && T.X[2 * i + 1] > 25 * cy && T.X[2 * i + 1] < 25 * (cy + 1),
               "fluid particle %" PetscInt_FMT " outside its cell", i);
    }
    /* left clamp: the 33 wall particles at x = 0; the tip is the wall particle at (400, 200) */
    PetscCall(T.Clamp(PETSC_COMM_SELF, {"left"}, "-fine_clamp"));
    PetscInt nfixed = 0;
    for (char f : P.fixed) nfixed += f;
    TG_CHECK(nfixed == 33, "clamped %" PetscInt_FMT, nfixed);
    const PetscInt tip = T.ClosestWallParticle(400, 200);
    TG_CHECK(T.X[2 * tip] == 400 && T.X[2 * tip + 1] == 200, "tip particle");
  }
  {
    /* general counts: corners (nx+1)(ny+1) + (s-1) per wall segment */
    SquareGridSpec spec;
    spec.cells_x          = 5;
    spec.cells_y          = 3;
    spec.springs_per_side = 4;
    spec.fluid_per_cell   = 9;
    Tissue T;
    PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
    const PetscInt walls = 6 * 4 + 3 * (5 * 4 + 6 * 3);
    TG_CHECK(T.particles.Count(KIND_WALL) == walls, "5x3, s=4: %" PetscInt_FMT " wall particles, expected %" PetscInt_FMT, T.particles.Count(KIND_WALL), walls);
    TG_CHECK(T.particles.Count(KIND_FLUID) == 15 * 9, "5x3 fluid");
    TG_CHECK(T.particles.springs.size() == (size_t)(4 * (5 * 4 + 6 * 3)), "5x3 springs");
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_tissue: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
