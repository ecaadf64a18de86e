#pragma once
/* Sums and extremes over the ranks of a communicator, in place, for summaries and reports: one
   collective call each (every rank must make it). */
#include <turgor/core/petsc_compat.h>
#include <petscsys.h>
#include <functional>
#include <string>
#include <vector>

namespace turgor {

template <class T>
MPI_Datatype RankDatatype();
template <>
inline MPI_Datatype RankDatatype<PetscReal>()
{
  return MPIU_REAL;
}
template <>
inline MPI_Datatype RankDatatype<PetscInt>()
{
  return MPIU_INT;
}

template <class T>
PetscErrorCode SumOverRanks(MPI_Comm comm, T *v, int n = 1)
{
  return MPI_Allreduce(MPI_IN_PLACE, v, n, RankDatatype<T>(), MPI_SUM, comm) == MPI_SUCCESS ? PETSC_SUCCESS : PETSC_ERR_MPI;
}
template <class T>
PetscErrorCode MaxOverRanks(MPI_Comm comm, T *v, int n = 1)
{
  return MPI_Allreduce(MPI_IN_PLACE, v, n, RankDatatype<T>(), MPI_MAX, comm) == MPI_SUCCESS ? PETSC_SUCCESS : PETSC_ERR_MPI;
}
template <class T>
PetscErrorCode MinOverRanks(MPI_Comm comm, T *v, int n = 1)
{
  return MPI_Allreduce(MPI_IN_PLACE, v, n, RankDatatype<T>(), MPI_MIN, comm) == MPI_SUCCESS ? PETSC_SUCCESS : PETSC_ERR_MPI;
}

/* This rank's number in comm, and (if asked) comm's size. */
inline PetscErrorCode RankAndSize(MPI_Comm comm, PetscMPIInt *rank, PetscMPIInt *size = nullptr)
{
  if (MPI_Comm_rank(comm, rank) != MPI_SUCCESS) return PETSC_ERR_MPI;
  return size && MPI_Comm_size(comm, size) != MPI_SUCCESS ? PETSC_ERR_MPI : PETSC_SUCCESS;
}

/* The end of AgreeOnError's message on the ranks that did not fail (an error handler that keeps the
   first message skips it, the failing rank's being the one to report). */
inline constexpr const char *kFailedOnAnotherRank = "failed on another rank";

/* Collective: a failure on some rank becomes one on every rank (a rank that goes on alone would wait
   in the next collective call for ever). Returns e where this rank failed, elsewhere an error
   saying that `what` failed on another rank (its own message is the failing rank's). */
inline PetscErrorCode AgreeOnError(MPI_Comm comm, PetscErrorCode e, const char *what)
{
  int bad = e ? 1 : 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm));
  if (e) PetscFunctionReturn(e);
  PetscCheck(!bad, PETSC_COMM_SELF, PETSC_ERR_LIB, "%s %s", what, kFailedOnAnotherRank);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rows of text cells gathered from every rank, in rank order: on the first rank only (to_all false;
   the others get none) or on every rank. */
using TextRows = std::vector<std::vector<std::string>>;
PetscErrorCode GatherRows(MPI_Comm comm, bool to_all, const TextRows &mine, TextRows *all);
/* Collective: every rank's rows handed to take() on the first rank, in rank order, received one
   rank at a time (the first rank holds its own rows and one other rank's, never all of them: a
   step that breaks a whole tissue's bonds); `mine` is emptied. A failure of take() is returned
   on the first rank after every rank's rows have been received. */
PetscErrorCode ForEachRowOnFirstRank(MPI_Comm comm, TextRows &mine, const std::function<PetscErrorCode(std::vector<std::string> &)> &take);

} // namespace turgor
