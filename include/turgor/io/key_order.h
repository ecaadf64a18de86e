#pragma once
/* Rows in key order, whatever the number of ranks: items spread over the ranks, each named by a
   64-bit key unique over all ranks (not necessarily contiguous: a particle's id, a glue bond's
   PairKey(node, bar)), placed at their row in the global ascending order of the keys.

   SetUp (collective) sorts the keys over the ranks: each key goes to the rank of its key range
   (KeyRanges, the bucket sort the checkpoint file uses too), each rank sorts the keys of its range,
   the counts are scanned and every key's row goes back to its item. Order then moves values of w
   components per item to the rows, in an even layout of the global count (PETSC_DECIDE: rank r holds
   rows SlabStart() .. SlabStart() + SlabRows() - 1): this rank's slab of the ordered table, ready for
   a parallel write (a Vec or IS of the slab's local size). The move is a PetscSF from the items
   (leaves) to the rows (roots), reduced with MPI_REPLACE; one SF per width, made on first use.

   A rank may hold no items (it still takes part in every collective call). On one rank the rows are
   the items' order sorted by key: the identity when the keys are already ascending. */
#include <turgor/core/petsc_compat.h>
#include <petscsf.h>
#include <cstdint>
#include <map>
#include <vector>

namespace turgor {

/* The ranges of a bucket sort by key: keys 0..kmax (the largest over the ranks) spread evenly over
   the ranks, rank q taking the keys k with floor(k size / (kmax + 1)) = q. */
class KeyRanges {
public:
  /* Collective: kmax over every rank's keys. */
  PetscErrorCode SetUp(MPI_Comm comm, const std::uint64_t *keys, size_t n);
  int            Rank(std::uint64_t key) const { return (int)((unsigned __int128)key * (unsigned)size_ / ((unsigned __int128)kmax_ + 1)); }

private:
  std::uint64_t kmax_ = 0;
  int           size_ = 1;
};

/* Collective: out[q] (bytes) sent to rank q, and what every rank sent this one, in rank order, into
   `in`, with the bytes from each rank in `from` (may be NULL). `what` names the data in errors
   (MPI counts are ints: 2 GB per rank at most). out is emptied. */
PetscErrorCode ExchangeBytes(MPI_Comm comm, std::vector<std::vector<char>> &out, std::vector<char> &in, std::vector<int> *from, const char *what);
/* The same from one buffer: send holds count[0] bytes for rank 0, then count[1] for rank 1, ...;
   send is emptied. */
PetscErrorCode ExchangePacked(MPI_Comm comm, std::vector<char> &send, const std::vector<int> &count, std::vector<char> &in, std::vector<int> *from,
                              const char *what);

class KeyOrder {
public:
  KeyOrder()                            = default;
  KeyOrder(const KeyOrder &)            = delete;
  KeyOrder &operator=(const KeyOrder &) = delete;
  ~KeyOrder() { Reset(); }

  /* Collective. `what` names the items in the error for a key held twice (over all ranks). */
  PetscErrorCode SetUp(MPI_Comm comm, const std::vector<std::uint64_t> &keys, const char *what);
  void           Reset();

  PetscInt Count() const { return count_; }                     /* items over all ranks */
  PetscInt LocalCount() const { return (PetscInt)row_.size(); } /* this rank's items */
  PetscInt Row(PetscInt i) const { return row_[i]; }            /* item i's row among all */
  PetscInt SlabStart() const { return slab_start_; }
  PetscInt SlabRows() const { return slab_rows_; }
  /* the keys of this rank's slab's rows, ascending */
  const std::vector<std::uint64_t> &SlabKeys() const { return slab_keys_; }
  /* Collective: the values of this rank's items (w per item, item after item) as this rank's slab
     of the ordered table (w per row). T: PetscReal, PetscInt or std::uint64_t. */
  template <typename T>
  PetscErrorCode Order(const T *values, int w, std::vector<T> &slab);

private:
  PetscErrorCode Graph(int w, PetscSF *sf);

  MPI_Comm                   comm_  = MPI_COMM_NULL;
  PetscInt                   count_ = 0, slab_start_ = 0, slab_rows_ = 0;
  std::vector<PetscInt>      row_;
  std::vector<std::uint64_t> slab_keys_;
  std::map<int, PetscSF>     sf_; /* by width */
};

} // namespace turgor
