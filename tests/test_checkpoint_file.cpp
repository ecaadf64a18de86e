/* The checkpoint file's one writer and reader (io/checkpoint_file.h) on declared state
   (io/declared_state.h), against values known by construction: a run of N particles dealt
   round-robin over P ranks (each rank with a halo: the next particle after each of its own) writes
   scalars, a particle table with each combination rule and a table of records with a ragged column;
   the file is read back on 1, 2 and 3 ranks (sub-communicators of the job) and on the writer's own
   layout, and every value is checked: owners' values, shares added up on the owner, copies on every
   holder, records kept by their anchor's owner, scalars summed, maximised or taken from the first
   writer, and the writer's own values exactly where the layout is its own. Also: the keys are written
   in ascending order whatever the ranks, and a changed value or a damaged byte is refused. */
#include <turgor/io/checkpoint_file.h>
#include "test_util.h"
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

using namespace turgor;

namespace {

const PetscInt N = 23; /* particles */

/* Rank r of P: its particles (g % P == r, ascending) then its halo (g + 1 of each, when another's). */
struct RoundRobin : public StateNumbering {
  PetscMPIInt                  rank, size;
  std::vector<PetscInt>        gid;
  PetscInt                     n_owned;
  std::map<PetscInt, PetscInt> local;
  RoundRobin(PetscMPIInt r, PetscMPIInt p) : rank(r), size(p)
  {
    for (PetscInt g = 0; g < N; g++)
      if (g % p == r) gid.push_back(g);
    n_owned = (PetscInt)gid.size();
    for (PetscInt k = 0; k < n_owned; k++) {
      const PetscInt h = (gid[k] + 1) % N;
      if (h % p != r) gid.push_back(h);
    }
    for (size_t l = 0; l < gid.size(); l++) local[gid[l]] = (PetscInt)l;
  }
  std::uint64_t Id(StateEntity, PetscInt l) const override { return (std::uint64_t)gid[l]; }
  PetscInt      Local(StateEntity, std::uint64_t id) const override
  {
    auto it = local.find((PetscInt)id);
    return it == local.end() ? -1 : it->second;
  }
  bool          Owned(StateEntity, PetscInt l) const override { return l >= 0 && l < n_owned; }
  std::uint64_t Layout() const override
  {
    std::uint64_t h = 1469598103934665603ull;
    for (PetscInt g : gid) h = (h ^ (std::uint64_t)g) * 1099511628211ull;
    return h;
  }
};

struct Record {
  PetscInt  node;
  PetscReal value;
};

/* The state of one rank: what a force term with history would keep. */
struct Thing {
  PetscReal                           count = 0, time = 0, largest = 0;
  std::vector<PetscReal>              owner, share, copy; /* per local particle */
  std::vector<Record>                 rec;
  std::vector<std::vector<PetscReal>> ragged;
  const RoundRobin                   *L;
  void                                Declare(StateDeclaration &d)
  {
    d.Scalar("count", &count, Combine::Sum);
    d.Scalar("time", &time, Combine::Owner);
    d.Scalar("largest", &largest, Combine::Max);
    d.Table("particles", StateEntity::Particle)
      .Rows([this] { return L->gid.size(); })
      .Column("owner", owner)
      .Column("share", share, 1, Combine::Sum)
      .Column("copy", copy, 1, Combine::Copy);
    d.Table("records", StateEntity::Particle)
      .Records([this] { return rec.size(); },
               [this](size_t r) { return PairKey((std::uint64_t)L->gid[rec[r].node], (std::uint64_t)(L->gid[rec[r].node] * 7 % N)); },
               [this](size_t n) {
                 rec.resize(n);
                 ragged.resize(n);
               },
               "node")
      .Ref("node", rec, &Record::node, StateEntity::Particle)
      .Field("value", rec, &Record::value)
      .Ragged(
        "list", [this](size_t r, std::vector<PetscReal> &v) { v = ragged[r]; },
        [this](size_t r, const PetscReal *v, size_t n) {
          ragged[r].assign(v, v + n);
          return PETSC_SUCCESS;
        });
  }
};

/* The written state of rank r of P */
void Fill(Thing &T, const RoundRobin &L)
{
  T.L            = &L;
  const size_t n = L.gid.size();
  T.count        = (PetscReal)L.n_owned;
  T.time         = 1.5;
  T.largest      = L.rank;
  T.owner.assign(n, 0), T.share.assign(n, 0), T.copy.assign(n, 0);
  for (size_t l = 0; l < n; l++) {
    const bool own = (PetscInt)l < L.n_owned;
    T.owner[l]     = own ? 100 + L.gid[l] : -7; /* a halo copy's is never read */
    T.share[l]     = own ? 1 : 0.5;
    T.copy[l]      = own ? 2.0 * L.gid[l] : -9;
  }
  for (PetscInt l = 0; l < L.n_owned; l++) {
    T.rec.push_back({l, 0.25 * L.gid[l]});
    std::vector<PetscReal> v;
    for (PetscInt k = 0; k < L.gid[l] % 3; k++) v.push_back(L.gid[l] + k);
    T.ragged.push_back(v);
  }
}

int  failures = 0;
void Expect(bool ok, const char *what, double got, double want)
{
  if (!ok) {
    failures++;
    std::printf("FAIL %s: got %g, want %g\n", what, got, want);
  }
}

/* Read `file` on the first `p` ranks of comm; check against construction (`own`: the writer's layout). */
PetscErrorCode ReadAndCheck(MPI_Comm world, const char *file, PetscMPIInt p, PetscMPIInt written_on)
{
  PetscMPIInt wr;
  MPI_Comm    comm;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(world, &wr));
  PetscCallMPI(MPI_Comm_split(world, wr < p ? 0 : MPI_UNDEFINED, wr, &comm));
  if (comm == MPI_COMM_NULL) PetscFunctionReturn(PETSC_SUCCESS);
  RoundRobin L(wr, p);
  Thing      T;
  T.L = &L;
  T.owner.assign(L.gid.size(), -1), T.share.assign(L.gid.size(), -1), T.copy.assign(L.gid.size(), -1);
  StateDeclaration d("thing");
  T.Declare(d);
  CheckpointReader R;
  PetscInt         writers;
  bool             same;
  PetscCall(R.Open(comm, file));
  PetscCall(R.Layouts(L, &writers, &same));
  PetscCall(R.State({&d}, L));
  PetscCall(R.Close());
  Expect(writers == written_on, "writers", writers, written_on);
  Expect(same == (p == written_on), "same layout", same, p == written_on);
  for (size_t l = 0; l < L.gid.size(); l++) {
    const PetscInt g        = L.gid[l];
    const bool     own      = (PetscInt)l < L.n_owned;
    PetscInt       copies_w = 0; /* halo copies of g in the writing run */
    for (PetscInt q = 0; q < written_on; q++) copies_w += (g % written_on != q) && ((g - 1 + N) % N) % written_on == q;
    if (own) Expect(T.owner[l] == 100 + g, "owner value", T.owner[l], 100 + g);
    if (same) Expect(T.share[l] == (own ? 1 : 0.5), "own share", T.share[l], own ? 1 : 0.5);
    else Expect(T.share[l] == (own ? 1 + 0.5 * copies_w : 0), "shares added", T.share[l], own ? 1 + 0.5 * copies_w : 0);
    const double want = own || !same ? 2.0 * g : -9; /* on the writer's layout a copy comes back as it was written */
    Expect(T.copy[l] == want, "copy", T.copy[l], want);
  }
  Expect(T.rec.size() == (size_t)L.n_owned, "records kept", (double)T.rec.size(), (double)L.n_owned);
  for (size_t r = 0; r < T.rec.size(); r++) {
    const PetscInt g = L.gid[T.rec[r].node];
    Expect(T.rec[r].node < L.n_owned, "record's anchor owned", (double)T.rec[r].node, (double)L.n_owned);
    Expect(T.rec[r].value == 0.25 * g, "record value", T.rec[r].value, 0.25 * g);
    Expect(T.ragged[r].size() == (size_t)(g % 3), "ragged length", (double)T.ragged[r].size(), (double)(g % 3));
    for (size_t k = 0; k < T.ragged[r].size(); k++) Expect(T.ragged[r][k] == g + (PetscReal)k, "ragged value", T.ragged[r][k], g + (double)k);
  }
  PetscReal total = T.count;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPIU_REAL, MPI_SUM, comm));
  Expect(total == N, "summed scalar", total, N);
  Expect(T.time == 1.5, "owner scalar", T.time, 1.5);
  Expect(same ? T.largest == wr : T.largest == written_on - 1, "max scalar", T.largest, same ? wr : written_on - 1);
  PetscCallMPI(MPI_Comm_free(&comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Write(MPI_Comm world, const char *file, PetscMPIInt p)
{
  PetscMPIInt wr;
  MPI_Comm    comm;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(world, &wr));
  PetscCallMPI(MPI_Comm_split(world, wr < p ? 0 : MPI_UNDEFINED, wr, &comm));
  if (comm != MPI_COMM_NULL) {
    RoundRobin L(wr, p);
    Thing      T;
    Fill(T, L);
    StateDeclaration d("thing");
    T.Declare(d);
    CheckpointWriter W;
    PetscCall(W.Open(comm, file));
    PetscCall(W.Attribute("mode", "test"));
    PetscCall(W.Text("note", "written on " + std::to_string(p)));
    PetscCall(W.State({&d}, L));
    PetscCall(W.Close());
    PetscCallMPI(MPI_Comm_free(&comm));
  }
  PetscCallMPI(MPI_Barrier(world));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether reading `file` on one rank fails with a message containing `what`. */
PetscErrorCode ExpectRefused(const char *file, const char *what)
{
  PetscFunctionBeginUser;
  RoundRobin       L(0, 1);
  Thing            T;
  StateDeclaration d("thing");
  T.L = &L;
  T.owner.assign(L.gid.size(), 0), T.share.assign(L.gid.size(), 0), T.copy.assign(L.gid.size(), 0);
  T.Declare(d);
  CheckpointReader R;
  PetscInt         writers;
  bool             same;
  std::string      msg;
  PetscCall(turgor_test::PushMessageCatcher(&msg));
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  PetscErrorCode ierr = R.Open(PETSC_COMM_SELF, file);
  if (!ierr) ierr = R.Layouts(L, &writers, &same);
  if (!ierr) ierr = R.State({&d}, L);
  PetscCall(PetscPopErrorHandler());
  const bool ok = ierr && msg.find(what) != std::string::npos;
  if (!ok) failures++;
  std::printf("%s: %s refused (%s)\n", ok ? "ok" : "FAIL", file, msg.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "Checkpoint file: declared state written and read on other rank counts"));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  char name[64];
  for (PetscMPIInt p = 1; p <= size; p++) {
    std::snprintf(name, sizeof name, "ckpt_test_%d.h5", p);
    PetscCall(Write(PETSC_COMM_WORLD, name, p));
    for (PetscMPIInt q = 1; q <= size; q++) PetscCall(ReadAndCheck(PETSC_COMM_WORLD, name, q, p));
  }
  if (rank == 0) {
    /* the keys of the particle table: ascending, the same sequence of owners' rows whatever wrote it */
    for (PetscMPIInt p = 1; p <= size; p++) {
      std::snprintf(name, sizeof name, "ckpt_test_%d.h5", p);
      hid_t                      f = H5Fopen(name, H5F_ACC_RDONLY, H5P_DEFAULT);
      hid_t                      d = H5Dopen2(f, "/state/thing/records/key", H5P_DEFAULT);
      std::vector<std::uint64_t> k(N);
      H5Dread(d, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, k.data());
      H5Dclose(d);
      H5Fclose(f);
      for (PetscInt i = 0; i + 1 < N; i++) Expect(k[i] < k[i + 1], "records' keys ascending", (double)k[i], (double)k[i + 1]);
    }
    /* a value changed by a tool that keeps the file valid (h5py, say): the checksum finds it */
    {
      hid_t     f = H5Fopen("ckpt_test_1.h5", H5F_ACC_RDWR, H5P_DEFAULT);
      hid_t     d = H5Dopen2(f, "/state/thing/particles/owner", H5P_DEFAULT);
      PetscReal v[N];
      H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
      v[5] += 1;
      H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
      H5Dclose(d);
      H5Fclose(f);
      PetscCall(ExpectRefused("ckpt_test_1.h5", "/state/thing/particles/owner was changed after it was written"));
    }
    /* a damaged byte in the file: Fletcher32 (or the checksum) finds it */
    if (size >= 2) {
      std::fstream s("ckpt_test_2.h5", std::ios::in | std::ios::out | std::ios::binary);
      s.seekg(0, std::ios::end);
      const std::streamoff n = s.tellg();
      std::vector<char>    b((size_t)n);
      s.seekg(0);
      s.read(b.data(), n);
      /* the particle table's owner values: 100 + g as doubles, find 123.0's neighbour 110.0 */
      const double      x = 110.0;
      const std::string pat((const char *)&x, 8);
      const size_t      at = std::string(b.begin(), b.end()).find(pat);
      if (at != std::string::npos) {
        s.seekp((std::streamoff)at);
        const double y = 111.5;
        s.write((const char *)&y, 8);
      }
      s.close();
      PetscCall(ExpectRefused("ckpt_test_2.h5", "damaged"));
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %d failures\n", failures ? "FAILED" : "passed", failures));
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
