#include <turgor/parallel/rank_reductions.h>
#include <algorithm>
#include <functional>

namespace turgor {

/* A row travels as its cells separated by unit separators, ended by a record separator. */
namespace {

const char US = '\x1f', RS = '\x1e';

std::string Join(const TextRows &rows)
{
  std::string text;
  for (const auto &row : rows) {
    for (size_t c = 0; c < row.size(); c++) {
      if (c) text += US;
      text += row[c];
    }
    text += RS;
  }
  return text;
}

/* The rows of `text` (Join's), appended to *rows. */
void Split(const std::string &text, TextRows *rows)
{
  for (size_t at = 0; at < text.size();) {
    const size_t             end = text.find(RS, at);
    std::vector<std::string> row;
    for (size_t p = at;;) {
      const size_t q = std::min(text.find(US, p), end);
      row.push_back(text.substr(p, q - p));
      if (q == end) break;
      p = q + 1;
    }
    rows->push_back(std::move(row));
    at = end + 1;
  }
}

} // namespace

PetscErrorCode GatherRows(MPI_Comm comm, bool to_all, const TextRows &mine, TextRows *all)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  const std::string        text = Join(mine);
  PetscMPIInt              len  = (PetscMPIInt)text.size();
  std::vector<PetscMPIInt> lens(size), displs(size + 1, 0);
  if (to_all) PetscCallMPI(MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, comm));
  else PetscCallMPI(MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, comm));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + lens[r];
  std::string joined(to_all || rank == 0 ? (size_t)displs[size] : 0, '\0');
  if (to_all) PetscCallMPI(MPI_Allgatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, comm));
  else PetscCallMPI(MPI_Gatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, 0, comm));
  all->clear();
  Split(joined, all);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForEachRowOnFirstRank(MPI_Comm comm, TextRows &mine, const std::function<PetscErrorCode(std::vector<std::string> &)> &take)
{
  PetscMPIInt size, rank, len;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::string text = rank == 0 ? std::string() : Join(mine);
  len              = (PetscMPIInt)text.size();
  std::vector<PetscMPIInt> lens(rank == 0 ? size : 0);
  PetscCallMPI(MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, comm));
  if (rank != 0) {
    if (len > 0) PetscCallMPI(MPI_Send(text.data(), len, MPI_CHAR, 0, 0, comm));
    mine.clear();
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscErrorCode ierr = PETSC_SUCCESS; /* rank 0 still receives every message after a failure (the others have sent) */
  for (auto &row : mine)
    if (!ierr) ierr = take(row);
  mine.clear();
  for (PetscMPIInt r = 1; r < size; r++) {
    if (lens[r] == 0) continue;
    TextRows rows;
    text.assign((size_t)lens[r], '\0');
    PetscCallMPI(MPI_Recv(text.data(), lens[r], MPI_CHAR, r, 0, comm, MPI_STATUS_IGNORE));
    Split(text, &rows);
    for (auto &row : rows)
      if (!ierr) ierr = take(row);
  }
  PetscCall(ierr);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
