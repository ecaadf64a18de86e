static const char help[] = "A tissue with an intercellular air space, built with the turgor library.\n"
                           "The fluid of the cells listed in -empty_cells is removed: those cells keep their walls\n"
                           "but no turgor, so the tissue sags more around them. Runs the fine model with the usual\n"
                           "options (-tissue_*, -physics, -ts_*, -output_dir) and prints the tip displacement.\n\n"
                           "  make -C examples && ./examples/air_space -tissue_cells_x 6 -tissue_cells_y 4 -empty_cells 8,9,14,15\n";

#include <turgor/turgor.hpp>
#include <algorithm>

/* Copy `in` without the fluid particles of the cells in `empty`. */
static turgor::Tissue WithoutFluid(const turgor::Tissue &in, const std::vector<PetscInt> &empty)
{
  turgor::Tissue        out;
  const auto           &P = in.particles;
  std::vector<PetscInt> index(P.n, -1);
  for (PetscInt i = 0; i < P.n; i++) {
    if (P.kind[i] == turgor::KIND_FLUID && std::count(empty.begin(), empty.end(), P.cell[i])) continue;
    index[i] = out.AddParticle(in.X[2 * i], in.X[2 * i + 1], P.mass[i], (turgor::ParticleKind)P.kind[i], P.cell[i]);
  }
  for (const turgor::Spring &s : P.springs) out.AddSpring(index[s.i], index[s.j]);
  for (const auto &ring : in.cell_walls) {
    std::vector<PetscInt> r;
    for (PetscInt i : ring) r.push_back(index[i]);
    out.cell_walls.push_back(r);
  }
  out.Finalize();
  return out;
}

int main(int argc, char **argv)
{
  PetscInt empty[64], nempty = 64;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-empty_cells", empty, &nempty, NULL));
  PetscCheck(nempty < 64, PETSC_COMM_WORLD, PETSC_ERR_ARG_SIZ, "Option -empty_cells: at most 63 cells"); /* a full buffer may have dropped some */
  {
    turgor::Tissue  tissue;
    turgor::FineRun run(PETSC_COMM_WORLD);
    PetscCall(run.SetFromOptions());
    PetscCall(run.Tissues().Generate(PETSC_COMM_WORLD, &tissue));
    for (PetscInt k = 0; k < nempty; k++)
      PetscCheck(empty[k] >= 0 && empty[k] < tissue.NumCells(), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
                 "Option -empty_cells: cell %" PetscInt_FMT " is not in 0..%" PetscInt_FMT, empty[k], tissue.NumCells() - 1);
    run.SetTissue(WithoutFluid(tissue, std::vector<PetscInt>(empty, empty + nempty)));
    PetscCall(run.SetUp());
    PetscCall(run.Solve());
    PetscCall(run.WriteSummary());
  }
  PetscCall(PetscFinalize());
  return 0;
}
