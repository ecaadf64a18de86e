#include <turgor/io/key_order.h>
#include <algorithm>
#include <cstring>
#include <numeric>

namespace turgor {

PetscErrorCode KeyRanges::SetUp(MPI_Comm comm, const std::uint64_t *keys, size_t n)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  size_ = size;
  kmax_ = 0;
  for (size_t i = 0; i < n; i++) kmax_ = std::max(kmax_, keys[i]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &kmax_, 1, MPI_UINT64_T, MPI_MAX, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ExchangeBytes(MPI_Comm comm, std::vector<std::vector<char>> &out, std::vector<char> &in, std::vector<int> *from, const char *what)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> count((size_t)size);
  for (int q = 0; q < size; q++) {
    PetscCheck(out[q].size() < (size_t)INT32_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s: more than 2 GB for one rank", what);
    count[q] = (int)out[q].size();
  }
  std::vector<char> send;
  {
    size_t bytes = 0;
    for (int q = 0; q < size; q++) bytes += out[q].size();
    send.reserve(bytes); /* its exact size: grown piece by piece it would hold up to twice the rows, the checkpoint's peak */
  }
  for (int q = 0; q < size; q++) {
    send.insert(send.end(), out[q].begin(), out[q].end());
    std::vector<char>().swap(out[q]);
  }
  PetscCall(ExchangePacked(comm, send, count, in, from, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ExchangePacked(MPI_Comm comm, std::vector<char> &send, const std::vector<int> &count, std::vector<char> &in, std::vector<int> *from,
                              const char *what)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<int> rcount((size_t)size), sdisp((size_t)size, 0), rdisp((size_t)size, 0);
  PetscCallMPI(MPI_Alltoall(count.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm));
  for (int q = 1; q < size; q++) sdisp[q] = sdisp[q - 1] + count[q - 1];
  size_t total = 0;
  for (int q = 0; q < size; q++) {
    rdisp[q] = (int)total;
    total += (size_t)rcount[q];
  }
  PetscCheck(total < (size_t)INT32_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s: more than 2 GB on one rank", what);
  in.resize(total);
  PetscCallMPI(MPI_Alltoallv(send.data(), count.data(), sdisp.data(), MPI_CHAR, in.data(), rcount.data(), rdisp.data(), MPI_CHAR, comm));
  std::vector<char>().swap(send);
  if (from) *from = rcount;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void KeyOrder::Reset()
{
  for (auto &kv : sf_) PetscCallVoid(PetscSFDestroy(&kv.second));
  sf_.clear();
  row_.clear();
  slab_keys_.clear();
  count_ = slab_start_ = slab_rows_ = 0;
  comm_                             = MPI_COMM_NULL;
}

PetscErrorCode KeyOrder::SetUp(MPI_Comm comm, const std::vector<std::uint64_t> &keys, const char *what)
{
  PetscMPIInt size, rank;
  KeyRanges   ranges;
  PetscFunctionBeginUser;
  Reset();
  comm_ = comm;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  const size_t n = keys.size();
  PetscCall(ranges.SetUp(comm, keys.data(), n));
  /* every key to the rank of its range */
  std::vector<std::vector<char>> out((size_t)size);
  std::vector<int>               dest(n);
  for (size_t i = 0; i < n; i++) {
    dest[i]           = ranges.Rank(keys[i]);
    const char *bytes = (const char *)&keys[i];
    out[dest[i]].insert(out[dest[i]].end(), bytes, bytes + sizeof keys[i]);
  }
  std::vector<char> in;
  std::vector<int>  from;
  PetscCall(ExchangeBytes(comm, out, in, &from, "KeyOrder: the keys"));
  /* this range's keys sorted: their rows follow the ranges before it */
  const size_t               m = in.size() / sizeof(std::uint64_t);
  std::vector<std::uint64_t> got(m);
  if (m) std::memcpy(got.data(), in.data(), in.size());
  std::vector<size_t> perm(m);
  std::iota(perm.begin(), perm.end(), 0);
  std::sort(perm.begin(), perm.end(), [&got](size_t a, size_t b) { return got[a] < got[b]; });
  std::uint64_t twice[2] = {0, 0}; /* (found, the key) */
  for (size_t k = 0; k + 1 < m && !twice[0]; k++)
    if (got[perm[k]] == got[perm[k + 1]]) twice[0] = 1, twice[1] = got[perm[k]];
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, twice, 2, MPI_UINT64_T, MPI_MAX, comm));
  PetscCheck(!twice[0], comm, PETSC_ERR_ARG_WRONG, "%s: the key %llu is held more than once (the keys must be unique over the ranks)", what,
             (unsigned long long)twice[1]);
  PetscInt mine = (PetscInt)m, first = 0;
  PetscCallMPI(MPI_Exscan(&mine, &first, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) first = 0;
  PetscCallMPI(MPI_Allreduce(&mine, &count_, 1, MPIU_INT, MPI_SUM, comm));
  std::vector<PetscInt> rows(m);
  for (size_t k = 0; k < m; k++) rows[perm[k]] = first + (PetscInt)k;
  /* the rows back to the keys' ranks, in the order their keys came */
  out.assign((size_t)size, {});
  for (int q = 0, at = 0; q < size; q++) {
    const int c = from[q] / (int)sizeof(std::uint64_t);
    out[q].resize(c * sizeof(PetscInt));
    if (c) std::memcpy(out[q].data(), rows.data() + at, c * sizeof(PetscInt));
    at += c;
  }
  PetscCall(ExchangeBytes(comm, out, in, &from, "KeyOrder: the rows"));
  std::vector<size_t> next((size_t)size, 0); /* per rank: its next row in `in` (the keys went in item order) */
  for (int q = 1; q < size; q++) next[q] = next[q - 1] + (size_t)from[q - 1] / sizeof(PetscInt);
  row_.resize(n);
  for (size_t i = 0; i < n; i++) std::memcpy(&row_[i], in.data() + sizeof(PetscInt) * next[dest[i]]++, sizeof(PetscInt));
  /* the even layout of the rows */
  slab_rows_ = PETSC_DECIDE;
  PetscCall(PetscSplitOwnership(comm, &slab_rows_, &count_));
  slab_start_ = 0;
  PetscCallMPI(MPI_Exscan(&slab_rows_, &slab_start_, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) slab_start_ = 0;
  PetscCall(Order(keys.data(), 1, slab_keys_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Leaves: the items' components (w i + d), roots: the slab's (w row + d). */
PetscErrorCode KeyOrder::Graph(int w, PetscSF *sf)
{
  PetscLayout layout;
  PetscFunctionBeginUser;
  auto it = sf_.find(w);
  if (it != sf_.end()) {
    *sf = it->second;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  const PetscInt        n = (PetscInt)row_.size();
  std::vector<PetscInt> remote((size_t)w * n);
  for (PetscInt i = 0; i < n; i++)
    for (int d = 0; d < w; d++) remote[(size_t)w * i + d] = w * row_[i] + d;
  PetscCall(PetscLayoutCreateFromSizes(comm_, w * slab_rows_, w * count_, 1, &layout));
  PetscCall(PetscSFCreate(comm_, sf));
  PetscCall(PetscSFSetGraphLayout(*sf, layout, w * n, NULL, PETSC_OWN_POINTER, remote.data()));
  PetscCall(PetscSFSetUp(*sf));
  PetscCall(PetscLayoutDestroy(&layout));
  sf_[w] = *sf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
template <typename T>
MPI_Datatype Unit();
template <>
MPI_Datatype Unit<PetscReal>()
{
  return MPIU_REAL;
}
template <>
MPI_Datatype Unit<PetscInt>()
{
  return MPIU_INT;
}
template <>
MPI_Datatype Unit<std::uint64_t>()
{
  return MPIU_INT64; /* copied (MPI_REPLACE): the bits are kept */
}
} // namespace

template <typename T>
PetscErrorCode KeyOrder::Order(const T *values, int w, std::vector<T> &slab)
{
  PetscSF sf;
  PetscFunctionBeginUser;
  PetscCheck(w > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "KeyOrder: %d components per item", w);
  PetscCheck(comm_ != MPI_COMM_NULL, PETSC_COMM_SELF, PETSC_ERR_ORDER, "KeyOrder: Order before SetUp");
  PetscCall(Graph(w, &sf));
  slab.assign((size_t)w * slab_rows_, T());
  const T none = T(); /* a rank without items passes a buffer all the same */
  PetscCall(PetscSFReduceBegin(sf, Unit<T>(), row_.empty() ? &none : values, slab.empty() ? NULL : slab.data(), MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(sf, Unit<T>(), row_.empty() ? &none : values, slab.empty() ? NULL : slab.data(), MPI_REPLACE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

template PetscErrorCode KeyOrder::Order<PetscReal>(const PetscReal *, int, std::vector<PetscReal> &);
template PetscErrorCode KeyOrder::Order<PetscInt>(const PetscInt *, int, std::vector<PetscInt> &);
template PetscErrorCode KeyOrder::Order<std::uint64_t>(const std::uint64_t *, int, std::vector<std::uint64_t> &);

} // namespace turgor
