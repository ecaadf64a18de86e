static const char help[] = "A failure in a 2-rank run ends the job at once, with its message:\n"
                           "  -case collective: every rank fails (a collective check); the first rank prints, all exit with status 1\n"
                           "    (PETSc 3.18's own handler keeps the other ranks asleep 10 s, then exits them with status 0);\n"
                           "  -case one_rank: only the last rank fails while the others wait in a collective call: it prints its own\n"
                           "    message and aborts the job after FinishRanks' timeout (-timeout, 2 s) instead of hanging.\n"
                           "Run under mpiexec -n 2 through expect_error.py, with a ctest timeout well below 10 s.\n";
#include <petscsys.h>
#include <cstring>
#include <turgor/core/errors.h>

static PetscErrorCode Fail(MPI_Comm comm, const char which[])
{
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (!std::strcmp(which, "collective")) SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "collective failure, seen by all %d ranks", (int)size);
  if (rank == size - 1) SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, "failure on rank %d only", (int)rank);
  PetscCallMPI(MPI_Barrier(comm)); /* the last rank never comes */
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  int                 status = 0;
  turgor::ErrorRecord errors;
  char                which[32] = "collective";
  PetscReal           timeout   = 2;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(turgor::PushErrorHandler(&errors));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", which, sizeof which, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-timeout", &timeout, NULL));
  if (Fail(PETSC_COMM_WORLD, which)) status = 1;
  PetscCall(turgor::FinishRanks(PETSC_COMM_WORLD, status, errors, timeout));
  PetscCall(PetscFinalize());
  return status;
}
