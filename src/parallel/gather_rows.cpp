#include <turgor/parallel/rank_reductions.h>
#include <algorithm>

namespace turgor {

/* A row travels as its cells separated by unit separators, ended by a record separator. */
PetscErrorCode GatherRows(MPI_Comm comm, bool to_all, const TextRows &mine, TextRows *all)
{
  const char  US = '\x1f', RS = '\x1e';
  std::string text;
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (const auto &row : mine) {
    for (size_t c = 0; c < row.size(); c++) text += (c ? std::string(1, US) : std::string()) + row[c];
    text += RS;
  }
  PetscMPIInt              len = (PetscMPIInt)text.size();
  std::vector<PetscMPIInt> lens(size), displs(size + 1, 0);
  if (to_all) PetscCallMPI(MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, comm));
  else PetscCallMPI(MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, comm));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + lens[r];
  std::string joined(to_all || rank == 0 ? (size_t)displs[size] : 0, '\0');
  if (to_all) PetscCallMPI(MPI_Allgatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, comm));
  else PetscCallMPI(MPI_Gatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, 0, comm));
  all->clear();
  for (size_t at = 0; at < joined.size();) {
    const size_t             end = joined.find(RS, at);
    std::vector<std::string> row;
    for (size_t p = at;;) {
      const size_t q = std::min(joined.find(US, p), end);
      row.push_back(joined.substr(p, q - p));
      if (q == end) break;
      p = q + 1;
    }
    all->push_back(std::move(row));
    at = end + 1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
