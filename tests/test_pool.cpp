static const char help[] = "Material-point pool on sub-communicators: evaluates six RVEs (stress, density, tangents) spread\n"
                           "over the ranks and writes them in global order to -o FILE; run with 1 and 2 ranks (and\n"
                           "-material_comm_size 2) and compare the files: the results must not depend on the distribution.\n";
#include "test_util.h"
#include <turgor/material/material_pool.h>

using namespace turgor;

int main(int argc, char **argv)
{
  char        path[PETSC_MAX_PATH_LEN] = "pool.txt";
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-o", path, sizeof path, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  const PetscInt N = 6, n = N / size + (rank < N % size ? 1 : 0);
  PetscInt       offset = 0;
  PetscCallMPI(MPI_Exscan(&n, &offset, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  {
    MaterialPointPool pool(PETSC_COMM_WORLD);
    PetscCall(pool.SetFromOptions());
    PetscCall(pool.SetUp(n));
    std::vector<Tensor2>          F(n), Fd(n);
    std::vector<MaterialResponse> r(n);
    std::vector<Tangents>         D(n);
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal g = offset + k;
      F[k]              = {
                     {{1 + 0.01 * g, 0.003 * g}, {0.001 * g, 1 - 0.005 * g}}
      };
      Fd[k] = {
        {{0.001 * g, 0.002}, {0.0, -0.001}}
      };
    }
    PetscCall(pool.Evaluate(F.data(), Fd.data(), r.data(), true, D.data()));
    std::vector<PetscReal> mine, all(N * 23);
    for (PetscInt k = 0; k < n; k++) {
      TG_CHECK(r[k].ok, "point %" PetscInt_FMT ": %s", offset + k, r[k].reason.c_str());
      for (int c = 0; c < 4; c++) mine.push_back(r[k].sigma.a[c / 2][c % 2]);
      mine.push_back(r[k].rho);
      for (int i = 0; i < 9; i++) mine.push_back(D[k].De[i / 3][i % 3]);
      for (int i = 0; i < 9; i++) mine.push_back(D[k].Dv[i / 3][i % 3]);
    }
    std::vector<int> counts(size), displs(size, 0);
    int              m = (int)mine.size();
    PetscCallMPI(MPI_Allgather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, PETSC_COMM_WORLD));
    for (int q = 1; q < size; q++) displs[q] = displs[q - 1] + counts[q - 1];
    PetscCallMPI(MPI_Gatherv(mine.data(), m, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, 0, PETSC_COMM_WORLD));
    FILE *fp;
    PetscCall(PetscFOpen(PETSC_COMM_WORLD, path, "w", &fp));
    for (PetscInt g = 0; g < N; g++) {
      for (int c = 0; c < 23; c++) PetscCall(PetscFPrintf(PETSC_COMM_WORLD, fp, "%.17g ", (double)all[23 * g + c]));
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, fp, "\n"));
    }
    PetscCall(PetscFClose(PETSC_COMM_WORLD, fp));
    MaterialCounters c;
    PetscCall(pool.GlobalCounters(&c));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "%d ranks, %" PetscInt_FMT " groups: %" PetscInt_FMT " points, %" PetscInt_FMT " RVE solves, %" PetscInt_FMT
                          " Psi-tc iterations, sigma_11 of point 5 = %.12g N/m\n",
                          size, pool.NumGroups(), pool.NumGlobal(), c.solves, c.iterations, (double)all[23 * 5]));
    TG_CHECK(c.solves == N * 7, "expected one trial and six tangent solves per point, got %" PetscInt_FMT, c.solves);
  }
  PetscCall(PetscFinalize());
  return 0;
}
