/* Rows in key order (io/key_order.h) on 1, 2 and 3 ranks (sub-communicators of the job), against a
   serial sort of all the keys: non-contiguous keys (glue-bond-like pairs PairKey(node, bar), keys near
   2^64, a single key) dealt to the ranks in a shuffled order, one rank holding none, and no keys at
   all. Checked: every item's row, the slab's keys and layout (PETSC_DECIDE), values of 1, 2 and 3
   components (reals, integers and 64-bit keys) moved to their rows, and on one rank with ascending
   keys the identity. A key held by two ranks is refused on every rank, naming it. */
#include <turgor/io/declared_state.h>
#include <turgor/io/key_order.h>
#include "test_util.h"
#include <algorithm>
#include <cstdio>
#include <string>

using namespace turgor;

namespace {

int failures = 0;

void Expect(bool ok, const std::string &what)
{
  if (!ok) {
    failures++;
    std::printf("FAIL %s\n", what.c_str());
  }
}

/* the values of a key: w components, exactly representable */
PetscReal RealValue(std::uint64_t key, int d)
{
  return (PetscReal)(key % 1000003) + 0.25 * d;
}
PetscInt IntValue(std::uint64_t key, int d)
{
  return (PetscInt)(key % 7919) * 3 + d;
}

/* All keys of a case, and which rank of p holds each (in the order held). */
struct Case {
  std::string                name;
  std::vector<std::uint64_t> keys;
  std::vector<int>           holder;
};

std::vector<Case> Cases(PetscMPIInt p)
{
  std::vector<Case>   cases;
  turgor_test::Random rnd(17 + p);
  { /* bond-like pair keys, shuffled, rank 1 (of 2 or 3) holding none */
    Case c{"pairs", {}, {}};
    for (std::uint64_t node = 0; node < 30; node++)
      for (std::uint64_t bar : {node * 3 + 1, node * 3 + 7})
        if ((node + bar) % 4) c.keys.push_back(PairKey(node * 5 + 2, bar));
    for (size_t i = c.keys.size(); i > 1; i--) std::swap(c.keys[i - 1], c.keys[(size_t)((rnd() + 1) / 2 * i) % i]);
    for (size_t i = 0; i < c.keys.size(); i++) {
      int r = (int)(i * 7 % (size_t)p);
      if (p > 1 && r == 1) r = 0;
      c.holder.push_back(r);
    }
    cases.push_back(c);
  }
  { /* keys near 2^64 and small ones, all on the last rank but one */
    Case c{"wide", {}, {}};
    for (std::uint64_t k = 0; k < 9; k++) c.keys.push_back(k % 2 ? ~0ull - 3 * k : 11 * k + 5);
    for (size_t i = 0; i < c.keys.size(); i++) c.holder.push_back(i % 3 == 0 ? p - 1 : 0);
    cases.push_back(c);
  }
  cases.push_back({"one", {42}, {p - 1}});
  cases.push_back({"none", {}, {}});
  { /* ascending in the items' order on every rank: on one rank the identity */
    Case c{"ascending", {}, {}};
    for (std::uint64_t k = 0; k < 13; k++) c.keys.push_back(3 * k + (k > 6 ? 100 : 0)), c.holder.push_back((int)(k * (unsigned)p / 13));
    cases.push_back(c);
  }
  return cases;
}

PetscErrorCode Check(MPI_Comm comm, PetscMPIInt p, const Case &c)
{
  PetscMPIInt rank;
  KeyOrder    order;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<std::uint64_t> mine, sorted = c.keys;
  for (size_t i = 0; i < c.keys.size(); i++)
    if (c.holder[i] == rank) mine.push_back(c.keys[i]);
  std::sort(sorted.begin(), sorted.end());
  PetscCall(order.SetUp(comm, mine, c.name.c_str()));
  const std::string where = c.name + " on " + std::to_string(p) + " ranks, rank " + std::to_string(rank) + ": ";
  const PetscInt    N     = (PetscInt)sorted.size();
  Expect(order.Count() == N, where + "count");
  Expect(order.LocalCount() == (PetscInt)mine.size(), where + "local count");
  for (size_t i = 0; i < mine.size(); i++) {
    const PetscInt want = (PetscInt)(std::lower_bound(sorted.begin(), sorted.end(), mine[i]) - sorted.begin());
    Expect(order.Row((PetscInt)i) == want,
           where + "row of key " + std::to_string(mine[i]) + ": " + std::to_string(order.Row((PetscInt)i)) + ", want " + std::to_string(want));
    if (p == 1 && c.name == "ascending") Expect(order.Row((PetscInt)i) == (PetscInt)i, where + "not the identity");
  }
  /* the slab: PETSC_DECIDE's layout */
  PetscInt rows = PETSC_DECIDE, total = N, start = 0;
  PetscCall(PetscSplitOwnership(comm, &rows, &total));
  PetscCallMPI(MPI_Exscan(&rows, &start, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) start = 0;
  Expect(order.SlabRows() == rows && order.SlabStart() == start, where + "slab layout");
  Expect(order.SlabKeys().size() == (size_t)rows, where + "slab keys' count");
  for (PetscInt r = 0; r < rows && r < (PetscInt)order.SlabKeys().size(); r++) Expect(order.SlabKeys()[r] == sorted[start + r], where + "slab key");
  /* values of 1, 2, 3 components moved to their rows (each width twice: the cached SF) */
  for (int w = 1; w <= 3; w++)
    for (int again = 0; again < 2; again++) {
      std::vector<PetscReal>     x, xs;
      std::vector<PetscInt>      k, ks;
      std::vector<std::uint64_t> u, us;
      for (std::uint64_t key : mine)
        for (int d = 0; d < w; d++) x.push_back(RealValue(key, d)), k.push_back(IntValue(key, d)), u.push_back(key ^ (std::uint64_t)d << 60);
      PetscCall(order.Order(x.data(), w, xs));
      PetscCall(order.Order(k.data(), w, ks));
      PetscCall(order.Order(u.data(), w, us));
      Expect(xs.size() == (size_t)(w * rows) && ks.size() == xs.size() && us.size() == xs.size(), where + "moved sizes");
      for (PetscInt r = 0; r < rows && xs.size() == (size_t)(w * rows); r++)
        for (int d = 0; d < w; d++) {
          const std::uint64_t key = sorted[start + r];
          Expect(xs[w * r + d] == RealValue(key, d), where + "real value, width " + std::to_string(w));
          Expect(ks[w * r + d] == IntValue(key, d), where + "integer value, width " + std::to_string(w));
          Expect(us[w * r + d] == (key ^ (std::uint64_t)d << 60), where + "key value, width " + std::to_string(w));
        }
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A key held by rank 0 and by the last rank: every rank fails, with the key in the message. */
PetscErrorCode ExpectTwiceRefused(MPI_Comm comm, PetscMPIInt p)
{
  PetscMPIInt rank;
  KeyOrder    order;
  std::string msg;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<std::uint64_t> mine;
  if (rank == 0) mine = {5, 77, 9};
  if (rank == p - 1) mine.push_back(77);
  if (p > 1 && rank != 0 && rank != p - 1) mine = {1000};
  PetscCall(turgor_test::PushMessageCatcher(&msg));
  PetscErrorCode ierr = order.SetUp(comm, mine, "test items");
  PetscCall(PetscPopErrorHandler());
  const bool ok = ierr && msg.find("test items: the key 77 is held more than once") != std::string::npos;
  Expect(ok, "a key held twice on " + std::to_string(p) + " ranks, rank " + std::to_string(rank) + ": " + (ierr ? msg : std::string("accepted")));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "Rows in key order over the ranks"));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  int checked = 0;
  for (PetscMPIInt p = 1; p <= size; p++) {
    MPI_Comm comm;
    PetscCallMPI(MPI_Comm_split(PETSC_COMM_WORLD, rank < p ? 0 : MPI_UNDEFINED, rank, &comm));
    if (comm != MPI_COMM_NULL) {
      for (const Case &c : Cases(p)) {
        PetscCall(Check(comm, p, c));
        checked++;
      }
      PetscCall(ExpectTwiceRefused(comm, p));
      PetscCallMPI(MPI_Comm_free(&comm));
    }
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "key order: %d cases on rank 0 over 1..%d ranks, %d failures\n", checked, size, failures));
  PetscCheck(failures == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%d checks failed", failures);
  PetscCall(PetscFinalize());
  return 0;
}
