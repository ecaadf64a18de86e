#include <turgor/io/checkpoint_file.h>
#include <turgor/io/key_order.h>
#include <turgor/parallel/rank_reductions.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numeric>
#include <type_traits>

namespace turgor {

namespace {

/* An HDF5 call that returned a negative value (failure) becomes an error naming what and the file. */
#define TG_H5(call, comm, ...) \
  do { \
    if ((call) < 0) SETERRQ(comm, PETSC_ERR_FILE_WRITE, __VA_ARGS__); \
  } while (0)
#define TG_H5R(call, ...) \
  do { \
    if ((call) < 0) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_READ, __VA_ARGS__); \
  } while (0)

/* The values of a dataset as 64-bit words, and the hash that `checksum` holds: a sum over the values
   of a mix of each value with its position, so that every rank can hash its own slab of the rows and
   the slabs add up (a plain checksum would need the whole dataset on one rank). SplitMix64's
   finaliser spreads every bit of its input over the output. */
std::uint64_t Mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

std::uint64_t Word(PetscReal v)
{
  std::uint64_t w;
  std::memcpy(&w, &v, sizeof w);
  return w;
}

/* Rank and Flag: a rank and a 0/1, written as 32-bit and 8-bit integers (the caller narrows them:
   a collective write of a filtered dataset cannot convert types) and read as Int (HDF5 widens them);
   the checksum is of the values either way. */
enum class Kind {
  Real,
  Int,
  Key,
  Byte,
  Rank,
  Flag
};

hid_t MemType(Kind k)
{
  switch (k) {
  case Kind::Real:
    return H5T_NATIVE_DOUBLE;
  case Kind::Int:
    return H5T_NATIVE_INT64;
  case Kind::Rank:
    return H5T_NATIVE_INT32;
  case Kind::Flag:
    return H5T_NATIVE_INT8;
  case Kind::Key:
    return H5T_NATIVE_UINT64;
  case Kind::Byte:
    return H5T_NATIVE_UCHAR;
  }
  return H5T_NATIVE_DOUBLE;
}

/* The rows of one table on one rank: keys, holders, owner flags and, per column, the values (a fixed
   column: rows x width; a ragged one: concatenated, with each row's length). References are ids. */
struct Rows {
  std::vector<std::uint64_t>             key;
  std::vector<std::int64_t>              holder, owned;
  std::vector<std::vector<PetscReal>>    data;
  std::vector<std::vector<std::int64_t>> length;
  size_t                                 Count() const { return key.size(); }
};

/* The names and widths of every declaration's tables and columns: every rank must declare the same
   ones (an object that declared according to its local sizes would make the ranks write different
   datasets). Collective: an error on every rank that names the first declaration that differs. */
PetscErrorCode CheckSameDeclarations(MPI_Comm comm, const std::vector<StateDeclaration *> &decls)
{
  PetscFunctionBeginUser;
  for (const StateDeclaration *d : decls) {
    std::uint64_t h   = 1469598103934665603ull, lo, hi;
    auto          mix = [&h](const std::string &s) {
      for (unsigned char ch : s) h = (h ^ ch) * 1099511628211ull;
      h = (h ^ 0xff) * 1099511628211ull;
    };
    for (const StateTable &t : d->Tables()) {
      mix(t.Name());
      for (const StateColumn &c : t.Columns()) mix(c.name + "/" + std::to_string(c.width) + (c.integer ? "i" : "r"));
    }
    PetscCallMPI(MPI_Allreduce(&h, &lo, 1, MPI_UINT64_T, MPI_MIN, comm));
    PetscCallMPI(MPI_Allreduce(&h, &hi, 1, MPI_UINT64_T, MPI_MAX, comm));
    PetscCheck(lo == hi, comm, PETSC_ERR_PLIB, "Checkpoint: the ranks declare different state for %s (its tables depend on a rank's own sizes)",
               d->Name().c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

std::uint64_t ChecksumTerm(std::uint64_t position, std::uint64_t word)
{
  return Mix(Mix(position) ^ word);
}
std::uint64_t ChecksumTerm(std::uint64_t position, PetscReal value)
{
  return Mix(Mix(position) ^ Word(value));
}

/* ---- writer ---- */

/* Left open on an error (Close() was not reached): closing is collective, and the other ranks may be
   elsewhere; the process ends with the error. */
CheckpointWriter::~CheckpointWriter() { }

PetscErrorCode CheckpointWriter::Open(MPI_Comm comm, const std::string &path)
{
  PetscFunctionBeginUser;
  comm_      = comm;
  path_      = path;
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  TG_H5(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL), comm, "Checkpoint %s: cannot set up MPI-IO", path.c_str());
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  PetscCheck(file_ >= 0, comm, PETSC_ERR_FILE_OPEN, "Checkpoint: cannot create %s (is the output directory writable?)", path.c_str());
  for (const char *g : {"/text", "/state"}) {
    hid_t gid = H5Gcreate2(file_, g, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    TG_H5(gid, comm, "Checkpoint %s: cannot create group %s", path.c_str(), g);
    H5Gclose(gid);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWriter::Attribute(const std::string &name, const std::string &value)
{
  PetscFunctionBeginUser;
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.size() + 1);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a     = H5Acreate2(file_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  TG_H5(a, comm_, "Checkpoint %s: cannot write attribute %s", path_.c_str(), name.c_str());
  herr_t e = H5Awrite(a, type, value.c_str());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  TG_H5(e, comm_, "Checkpoint %s: cannot write attribute %s", path_.c_str(), name.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWriter::Attribute(const std::string &name, PetscInt value)
{
  const std::int64_t v = value;
  PetscFunctionBeginUser;
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a     = H5Acreate2(file_, name.c_str(), H5T_NATIVE_INT64, space, H5P_DEFAULT, H5P_DEFAULT);
  TG_H5(a, comm_, "Checkpoint %s: cannot write attribute %s", path_.c_str(), name.c_str());
  herr_t e = H5Awrite(a, H5T_NATIVE_INT64, &v);
  H5Aclose(a);
  H5Sclose(space);
  TG_H5(e, comm_, "Checkpoint %s: cannot write attribute %s", path_.c_str(), name.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* One dataset of `rows` global rows of `width` values (width 0: a vector), this rank's `n` rows from
   global row `first`, in chunks with Fletcher32, and its checksum attribute. Collective. */
PetscErrorCode WriteDataset(MPI_Comm comm, const std::string &file, hid_t loc, const std::string &name, Kind kind, const void *data, std::uint64_t n,
                            std::uint64_t first, std::uint64_t rows, int width)
{
  PetscFunctionBeginUser;
  const int     ndims   = width > 0 ? 2 : 1;
  const hsize_t w       = width > 0 ? (hsize_t)width : 1;
  hsize_t       dims[2] = {(hsize_t)rows, w};
  hid_t         space   = H5Screate_simple(ndims, dims, NULL);
  hid_t         dcpl    = H5Pcreate(H5P_DATASET_CREATE);
  if (rows > 0 && w > 0) {
    /* chunks of about 64 k values: Fletcher32 needs a chunked layout */
    hsize_t chunk[2] = {std::max<hsize_t>(1, std::min<hsize_t>(rows, 65536 / w)), w};
    TG_H5(H5Pset_chunk(dcpl, ndims, chunk), comm, "Checkpoint %s: %s: cannot set its chunks", file.c_str(), name.c_str());
    TG_H5(H5Pset_fletcher32(dcpl), comm, "Checkpoint %s: %s: cannot set its checksum filter", file.c_str(), name.c_str());
  }
  hid_t d = H5Dcreate2(loc, name.c_str(), MemType(kind), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  TG_H5(d, comm, "Checkpoint %s: cannot create dataset %s", file.c_str(), name.c_str());
  hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE); /* filtered datasets are written collectively */
  hsize_t start[2] = {(hsize_t)first, 0}, count[2] = {(hsize_t)n, w};
  hid_t   mem = H5Screate_simple(ndims, count, NULL);
  if (n > 0) H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
  else {
    H5Sselect_none(space);
    H5Sselect_none(mem);
  }
  const std::uint64_t none = 0; /* a rank with nothing to write still passes a buffer (HDF5 refuses NULL) */
  herr_t              e    = rows > 0 && w > 0 ? H5Dwrite(d, MemType(kind), mem, space, dxpl, n > 0 ? data : &none) : 0;
  H5Sclose(mem);
  H5Pclose(dxpl);
  H5Sclose(space);
  /* the checksum of the whole dataset: every rank's share of the sum */
  std::uint64_t h  = 0, word;
  const size_t  nv = (size_t)n * (size_t)w;
  for (size_t k = 0; k < nv; k++) {
    switch (kind) {
    case Kind::Real:
      word = Word(((const PetscReal *)data)[k]);
      break;
    case Kind::Int:
      word = (std::uint64_t)((const std::int64_t *)data)[k];
      break;
    case Kind::Rank:
      word = (std::uint64_t)(std::int64_t)((const std::int32_t *)data)[k];
      break;
    case Kind::Flag:
      word = (std::uint64_t)(std::int64_t)((const std::int8_t *)data)[k];
      break;
    case Kind::Key:
      word = ((const std::uint64_t *)data)[k];
      break;
    default:
      word = ((const unsigned char *)data)[k];
    }
    h += Mix(Mix((std::uint64_t)first * w + k) ^ word);
  }
  int failed = e < 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &h, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, comm));
  if (!failed) {
    hid_t as = H5Screate(H5S_SCALAR);
    hid_t a  = H5Acreate2(d, "checksum", H5T_NATIVE_UINT64, as, H5P_DEFAULT, H5P_DEFAULT);
    failed   = a < 0 || H5Awrite(a, H5T_NATIVE_UINT64, &h) < 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(as);
  }
  H5Dclose(d);
  PetscCheck(!failed, comm, PETSC_ERR_FILE_WRITE, "Checkpoint %s: cannot write dataset %s (disk full?)", file.c_str(), name.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A table's rows on their way to the rank of their key's range (keys below kmax + 1 spread evenly
   over the ranks; KeyRanges), where they are sorted by (key, holder): each rank then holds a
   contiguous, ordered slab. The keys travel first and fix the order; then each column travels on
   its own through the same order and is written before the next is packed, so that a rank holds
   one column of the table at a time (three copies of it: sent, received, sorted), not the whole
   table twice (a checkpoint of 10^7 particles writes tables of hundreds of MB). */
class RowExchange {
public:
  /* Collective: this rank's rows' keys (in the table's order). */
  PetscErrorCode SetUp(MPI_Comm comm, const std::vector<std::uint64_t> &key)
  {
    KeyRanges ranges;
    PetscFunctionBeginUser;
    comm_ = comm;
    PetscCallMPI(MPI_Comm_size(comm, &size_));
    PetscCall(ranges.SetUp(comm, key.data(), key.size()));
    start_.assign((size_t)size_ + 1, 0);
    for (std::uint64_t k : key) start_[(size_t)ranges.Rank(k) + 1]++;
    for (int q = 0; q < size_; q++) start_[q + 1] += start_[q];
    std::vector<size_t> fill(start_.begin(), start_.end() - 1);
    send_order_.resize(key.size());
    for (size_t r = 0; r < key.size(); r++) send_order_[fill[(size_t)ranges.Rank(key[r])]++] = r;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* Collective: pack(r, &bytes) appends row r's bytes, for every row in the order of sending (of
     row_bytes each, where known: the buffer is then made at its size, not grown to up to twice it);
     *in receives every rank's rows for this one, in rank order. */
  template <class Pack>
  PetscErrorCode Send(Pack &&pack, size_t row_bytes, std::vector<char> *in, const char *what) const
  {
    std::vector<char> send;
    std::vector<int>  count((size_t)size_, 0);
    PetscFunctionBeginUser;
    send.reserve(row_bytes * send_order_.size());
    for (int q = 0; q < size_; q++) {
      const size_t before = send.size();
      for (size_t k = start_[q]; k < start_[q + 1]; k++) pack(send_order_[k], &send);
      PetscCheck(send.size() - before < (size_t)INT32_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s: more than 2 GB for one rank", what);
      count[q] = (int)(send.size() - before);
    }
    PetscCall(ExchangePacked(comm_, send, count, *in, NULL, what));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  MPI_Comm            comm_ = MPI_COMM_NULL;
  PetscMPIInt         size_ = 1;
  std::vector<size_t> start_;      /* [ranks + 1]: the rows for each rank in the order of sending */
  std::vector<size_t> send_order_; /* the table's rows in the order of sending */
};

template <class T>
void Append(std::vector<char> *bytes, const T *p, size_t n)
{
  bytes->insert(bytes->end(), (const char *)p, (const char *)(p + n));
}

} // namespace

PetscErrorCode CheckpointWriter::Text(const std::string &name, const std::string &value)
{
  PetscMPIInt   rank;
  std::uint64_t n;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  n                   = rank == 0 ? value.size() : 0;
  std::uint64_t total = n;
  PetscCallMPI(MPI_Bcast(&total, 1, MPI_UINT64_T, 0, comm_));
  hid_t g = H5Gopen2(file_, "/text", H5P_DEFAULT);
  TG_H5(g, comm_, "Checkpoint %s: no group /text", path_.c_str());
  PetscErrorCode ierr = WriteDataset(comm_, path_, g, name, Kind::Byte, value.data(), n, 0, total, 0);
  H5Gclose(g);
  PetscCall(ierr);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWriter::WriteTable(const std::string &group, const StateTable &table, const StateNumbering &numbering)
{
  const std::vector<StateColumn> &cols = table.Columns();
  const size_t                    ncol = cols.size(), n = table.Count();
  const StateEntity               e = table.Entity();
  PetscMPIInt                     rank;
  RowExchange                     X;
  std::vector<size_t>             perm; /* the received rows in key order: the k-th row of the slab is received row perm[k] */
  std::uint64_t                   nl = 0, first = 0, total = 0;
  PetscErrorCode                  ierr = PETSC_SUCCESS;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  hid_t g = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  TG_H5(g, comm_, "Checkpoint %s: cannot create group %s", path_.c_str(), group.c_str());
  { /* the keys, holders and owner flags: they fix the slab's order */
    std::vector<std::uint64_t> key(n);
    std::vector<std::int8_t>   owned(n);
    const int                  anchor = table.IsRecords() ? table.AnchorColumn() : -1;
    for (size_t r = 0; r < n; r++) {
      bool own = true;
      if (e == StateEntity::Rank) key[r] = (std::uint64_t)rank;
      else if (table.IsRecords()) {
        key[r] = table.RecordKey(r);
        if (anchor >= 0) {
          PetscReal a;
          cols[anchor].get(r, &a);
          own = numbering.Owned(cols[anchor].ref, (PetscInt)a);
        }
      } else {
        key[r] = numbering.Id(e, table.Local(r));
        own    = table.OwnedOverride() ? table.Owned(r) : numbering.Owned(e, table.Local(r));
      }
      owned[r] = own ? 1 : 0;
    }
    PetscCall(X.SetUp(comm_, key));
    std::vector<char> in;
    PetscCall(X.Send(
      [&](size_t r, std::vector<char> *b) {
        const std::int32_t holder = (std::int32_t)rank;
        Append(b, &key[r], 1), Append(b, &holder, 1), Append(b, &owned[r], 1);
      },
      13, &in, "Checkpoint: a table's keys"));
    const size_t row = 13;
    nl               = in.size() / row;
    std::vector<std::uint64_t> k(nl);
    std::vector<std::int32_t>  h(nl);
    std::vector<std::int8_t>   o(nl);
    for (size_t i = 0; i < nl; i++) {
      std::memcpy(&k[i], in.data() + i * row, 8);
      std::memcpy(&h[i], in.data() + i * row + 8, 4);
      std::memcpy(&o[i], in.data() + i * row + 12, 1);
    }
    std::vector<char>().swap(in);
    perm.resize(nl);
    std::iota(perm.begin(), perm.end(), (size_t)0);
    /* stable: rows of one key and holder (records) keep the order they were sent in */
    std::stable_sort(perm.begin(), perm.end(), [&](size_t a, size_t b) { return k[a] != k[b] ? k[a] < k[b] : h[a] < h[b]; });
    auto in_order = [&perm](auto &v) {
      std::remove_reference_t<decltype(v)> sorted(v.size());
      for (size_t i = 0; i < v.size(); i++) sorted[i] = v[perm[i]];
      v.swap(sorted);
    };
    in_order(k), in_order(h), in_order(o);
    /* this rank's slab: its rows' place among all */
    PetscCallMPI(MPI_Exscan(&nl, &first, 1, MPI_UINT64_T, MPI_SUM, comm_));
    if (rank == 0) first = 0;
    PetscCallMPI(MPI_Allreduce(&nl, &total, 1, MPI_UINT64_T, MPI_SUM, comm_));
    ierr = WriteDataset(comm_, path_, g, "key", Kind::Key, k.data(), nl, first, total, 0);
    if (!ierr) ierr = WriteDataset(comm_, path_, g, "holder", Kind::Rank, h.data(), nl, first, total, 0);
    if (!ierr) ierr = WriteDataset(comm_, path_, g, "owned", Kind::Flag, o.data(), nl, first, total, 0);
  }
  /* the columns, one at a time (references as ids) */
  std::vector<PetscReal> buf;
  for (size_t c = 0; c < ncol && !ierr; c++) {
    const StateColumn &col = cols[c];
    const size_t       w   = col.width > 0 ? (size_t)col.width : 0;
    std::vector<char>  in;
    PetscCall(X.Send(
      [&](size_t r, std::vector<char> *b) {
        if (w > 0) {
          buf.resize(w);
          col.get(r, buf.data());
        } else {
          buf.clear();
          col.get_ragged(r, buf);
          const std::int64_t len = (std::int64_t)buf.size();
          Append(b, &len, 1);
        }
        if (col.is_ref)
          for (PetscReal &v : buf) v = v < 0 ? -1 : (PetscReal)numbering.Id(col.ref, (PetscInt)v);
        Append(b, buf.data(), buf.size());
      },
      8 * w, &in, "Checkpoint: a table's column"));
    /* a ragged column's received rows: where each one's values start, and how many */
    std::vector<size_t>       at(w > 0 ? 0 : nl);
    std::vector<std::int64_t> len(w > 0 ? 0 : nl);
    size_t                    nv = w * nl;
    for (size_t i = 0, p = 0; w == 0 && i < nl; i++) {
      std::memcpy(&len[i], in.data() + p, 8);
      at[i] = p + 8;
      p     = at[i] + 8 * (size_t)len[i];
      nv += (size_t)len[i];
    }
    /* the values in the slab's order, as reals or (integer columns) as integers */
    std::vector<PetscReal>    real(col.integer ? 0 : nv);
    std::vector<std::int64_t> ints(col.integer ? nv : 0), lengths(w > 0 ? 0 : nl);
    for (size_t kk = 0, v = 0; kk < nl; kk++) {
      const size_t i = perm[kk], m = w > 0 ? w : (size_t)len[i], from = w > 0 ? 8 * w * i : at[i];
      if (w == 0) lengths[kk] = len[i];
      for (size_t j = 0; j < m; j++, v++) {
        PetscReal x;
        std::memcpy(&x, in.data() + from + 8 * j, 8);
        if (col.integer) ints[v] = (std::int64_t)x;
        else real[v] = x;
      }
    }
    std::vector<char>().swap(in);
    const Kind  kind = col.integer ? Kind::Int : Kind::Real;
    const void *data = col.integer ? (const void *)ints.data() : (const void *)real.data();
    if (w > 0) ierr = WriteDataset(comm_, path_, g, col.name, kind, data, nl, first, total, col.width);
    else {
      std::uint64_t nvl = nv, vfirst = 0, vtotal = 0;
      PetscCallMPI(MPI_Exscan(&nvl, &vfirst, 1, MPI_UINT64_T, MPI_SUM, comm_));
      if (rank == 0) vfirst = 0;
      PetscCallMPI(MPI_Allreduce(&nvl, &vtotal, 1, MPI_UINT64_T, MPI_SUM, comm_));
      ierr = WriteDataset(comm_, path_, g, col.name, kind, data, nvl, vfirst, vtotal, 0);
      if (!ierr) ierr = WriteDataset(comm_, path_, g, col.name + ".length", Kind::Int, lengths.data(), nl, first, total, 0);
    }
  }
  H5Gclose(g);
  PetscCall(ierr);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWriter::State(const std::vector<StateDeclaration *> &decls, const StateNumbering &numbering)
{
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(CheckSameDeclarations(comm_, decls));
  {
    const std::uint64_t layout = numbering.Layout();
    PetscCall(WriteDataset(comm_, path_, file_, "layout", Kind::Key, &layout, 1, (std::uint64_t)rank, (std::uint64_t)size, 0));
  }
  for (const StateDeclaration *d : decls) {
    if (between_) PetscCall(between_());
    const std::string group = "/state/" + d->Name();
    hid_t             g     = H5Gcreate2(file_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    TG_H5(g, comm_, "Checkpoint %s: cannot create group %s (two objects of one name?)", path_.c_str(), group.c_str());
    H5Gclose(g);
    for (const StateTable &t : d->Tables()) PetscCall(WriteTable(group + "/" + t.Name(), t, numbering));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointWriter::Close()
{
  PetscFunctionBeginUser;
  if (file_ >= 0) {
    herr_t e = H5Fclose(file_);
    file_    = -1;
    int bad  = e < 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm_));
    PetscCheck(!bad, comm_, PETSC_ERR_FILE_WRITE, "Checkpoint: cannot close %s (disk full?)", path_.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- reader ---- */

CheckpointReader::~CheckpointReader()
{
  if (file_ >= 0) H5Fclose(file_);
}

PetscErrorCode CheckpointReader::Open(MPI_Comm comm, const std::string &path)
{
  PetscFunctionBeginUser;
  comm_      = comm;
  path_      = path;
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL);
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  PetscCheck(file_ >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "not an HDF5 file, or damaged");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::HasAttribute(const std::string &name, bool *has)
{
  PetscFunctionBeginUser;
  *has = H5Aexists(file_, name.c_str()) > 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::Attribute(const std::string &name, std::string *value)
{
  PetscFunctionBeginUser;
  hid_t a = H5Aopen(file_, name.c_str(), H5P_DEFAULT);
  TG_H5R(a, "no attribute %s", name.c_str());
  hid_t             type = H5Aget_type(a);
  size_t            n    = H5Tget_size(type);
  std::vector<char> s(n + 1, 0);
  herr_t            e = H5Tget_class(type) == H5T_STRING ? H5Aread(a, type, s.data()) : -1;
  H5Tclose(type);
  H5Aclose(a);
  TG_H5R(e, "attribute %s is not a text", name.c_str());
  *value = s.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::Attribute(const std::string &name, PetscInt *value)
{
  std::int64_t v = 0;
  PetscFunctionBeginUser;
  hid_t a = H5Aopen(file_, name.c_str(), H5P_DEFAULT);
  TG_H5R(a, "no attribute %s", name.c_str());
  hid_t  type = H5Aget_type(a);
  herr_t e    = H5Tget_class(type) == H5T_INTEGER ? H5Aread(a, H5T_NATIVE_INT64, &v) : -1;
  H5Tclose(type);
  H5Aclose(a);
  TG_H5R(e, "attribute %s is not an integer", name.c_str());
  *value = (PetscInt)v;
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* A dataset opened for reading: its dimensions (dims[1] = 0 for a vector), the kind its values are
   read as and the checksum it carries. Errors name it. */
class Dataset {
public:
  ~Dataset()
  {
    if (id_ >= 0) H5Dclose(id_);
  }
  PetscErrorCode Open(hid_t loc, const std::string &path, Kind kind)
  {
    PetscFunctionBeginUser;
    path_ = path;
    kind_ = kind;
    id_   = H5Dopen2(loc, path.c_str(), H5P_DEFAULT);
    TG_H5R(id_, "the checkpoint has no dataset %s (written by another version of turgor, or for another scene?)", path.c_str());
    hid_t space = H5Dget_space(id_);
    nd_         = H5Sget_simple_extent_ndims(space);
    if (nd_ >= 1 && nd_ <= 2) H5Sget_simple_extent_dims(space, dims_, NULL);
    H5Sclose(space);
    PetscCheck(nd_ >= 1 && nd_ <= 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "dataset %s has %d dimensions", path.c_str(), nd_);
    if (nd_ == 1) dims_[1] = 0;
    herr_t ea = -1;
    if (H5Aexists(id_, "checksum") > 0) {
      hid_t a = H5Aopen(id_, "checksum", H5P_DEFAULT);
      ea      = H5Aread(a, H5T_NATIVE_UINT64, &stored_);
      H5Aclose(a);
    }
    TG_H5R(ea, "dataset %s has no checksum attribute", path.c_str());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  hsize_t            Rows() const { return dims_[0]; }
  hsize_t            Columns() const { return dims_[1]; } /* 0: a vector */
  std::uint64_t      Stored() const { return stored_; }
  Kind               ValueKind() const { return kind_; }
  const std::string &Path() const { return path_; }
  /* Rows [lo, hi) (clipped), and their share of the checksum (added to *share); T is the type of
     the dataset's kind (PetscReal, std::int64_t, std::uint64_t, unsigned char). */
  template <class T>
  PetscErrorCode Read(hsize_t lo, hsize_t hi, std::vector<T> &out, std::uint64_t *share) const
  {
    PetscFunctionBeginUser;
    const hsize_t width = dims_[1] ? dims_[1] : 1;
    lo                  = std::min(lo, dims_[0]);
    hi                  = std::max(lo, std::min(hi, dims_[0]));
    const size_t nv     = (size_t)(hi - lo) * (size_t)width;
    out.resize(nv);
    herr_t e = 0;
    if (nv > 0) {
      const hsize_t start[2] = {lo, 0}, count[2] = {hi - lo, dims_[1]};
      hid_t         space = H5Dget_space(id_), mem = H5Screate_simple(nd_, count, NULL);
      e = H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
      if (e >= 0) e = H5Dread(id_, MemType(kind_), mem, space, H5P_DEFAULT, out.data());
      H5Sclose(mem);
      H5Sclose(space);
    }
    TG_H5R(e, "dataset %s is damaged (HDF5 cannot read it, or its Fletcher32 checksum fails)", path_.c_str());
    std::uint64_t h = 0;
    for (size_t k = 0; k < nv; k++) {
      std::uint64_t w;
      if constexpr (sizeof(T) == 8) std::memcpy(&w, &out[k], 8);
      else w = (std::uint64_t)out[k];
      h += ChecksumTerm((std::uint64_t)(lo * width + k), w);
    }
    *share += h;
    PetscFunctionReturn(PETSC_SUCCESS);
  }

private:
  hid_t         id_      = -1;
  Kind          kind_    = Kind::Real;
  hsize_t       dims_[2] = {0, 0};
  int           nd_      = 0;
  std::uint64_t stored_  = 0;
  std::string   path_;
};

PetscErrorCode CheckChecksum(const std::string &path, std::uint64_t share, std::uint64_t stored)
{
  PetscFunctionBeginUser;
  PetscCheck(share == stored, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "dataset %s was changed after it was written (its values do not match its checksum)",
             path.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A whole dataset on this rank (its values as `kind`), checked against its checksum; dims[1] = 0 for a
   vector. */
template <class T>
PetscErrorCode ReadDataset(hid_t loc, const std::string &path, Kind kind, std::vector<T> &out, hsize_t dims[2])
{
  Dataset       d;
  std::uint64_t share = 0;
  PetscFunctionBeginUser;
  PetscCall(d.Open(loc, path, kind));
  dims[0] = d.Rows(), dims[1] = d.Columns();
  PetscCall(d.Read(0, d.Rows(), out, &share));
  PetscCall(CheckChecksum(path, share, d.Stored()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* This rank's entities of a table: (id, row), sorted by id, ids unique. */
using KeyRows = std::vector<std::pair<std::uint64_t, size_t>>;

/* An indexed table's rows for this rank's keys (`keys`), handed to `consume` a
   chunk at a time in the file's order. No rank holds more of the table than a chunk:
   - the checksums: each rank streams an equal slab of every dataset's rows in chunks, and the
     slabs' shares are summed over the ranks (collective; the same verdict everywhere);
   - the rows (in key order, RowExchange): the range from the first key >= this rank's smallest
     to the last <= its largest is found by bisection on the keys and streamed in chunks of
     chunk rows (-restart_read_rows: the reader's transient, whatever the table's size), keeping
     the rows of this rank's keys (every row of such a key, whatever its holder). On any rank
     count the ranks' own keys are close in the numbering, so the range is about their share.
   A rank's read error is every rank's. */
PetscErrorCode ReadRowsOfKeys(MPI_Comm comm, hid_t file, const std::string &group, const std::vector<StateColumn> &cols, const KeyRows &keys, hsize_t chunk,
                              const std::function<PetscErrorCode(const Rows &)> &consume)
{
  const size_t           ncol = cols.size();
  PetscMPIInt            size, rank;
  Dataset                key, holder, owned;
  std::vector<Dataset>   data(ncol), length(ncol);
  std::vector<Dataset *> all; /* every dataset, in one order on every rank */
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  auto open = [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(key.Open(file, group + "/key", Kind::Key));
    PetscCall(holder.Open(file, group + "/holder", Kind::Int));
    PetscCall(owned.Open(file, group + "/owned", Kind::Int));
    const hsize_t N = key.Rows();
    PetscCheck(holder.Rows() == N && owned.Rows() == N, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: key, holder and owned differ in length",
               group.c_str());
    all = {&key, &holder, &owned};
    for (size_t c = 0; c < ncol; c++) {
      const StateColumn &col  = cols[c];
      const std::string  path = group + "/" + col.name;
      PetscCall(data[c].Open(file, path, col.integer ? Kind::Int : Kind::Real));
      all.push_back(&data[c]);
      if (col.width > 0)
        PetscCheck(data[c].Rows() == N && data[c].Columns() == (hsize_t)col.width, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
                   "%s holds %llu x %llu values, this run keeps %llu x %d (another scene?)", path.c_str(), (unsigned long long)data[c].Rows(),
                   (unsigned long long)data[c].Columns(), (unsigned long long)N, col.width);
      else {
        PetscCall(length[c].Open(file, path + ".length", Kind::Int));
        all.push_back(&length[c]);
        PetscCheck(length[c].Rows() == N, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s.length has %llu rows, the table %llu", path.c_str(),
                   (unsigned long long)length[c].Rows(), (unsigned long long)N);
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCall(AgreeOnError(comm, open(), "reading the checkpoint"));

  /* the checksums, from the ranks' slabs */
  std::vector<std::uint64_t> shares(all.size(), 0);
  auto                       hash_slabs = [&]() -> PetscErrorCode {
    std::vector<PetscReal>     real;
    std::vector<std::int64_t>  ints;
    std::vector<std::uint64_t> words;
    PetscFunctionBeginUser;
    for (size_t k = 0; k < all.size(); k++) {
      const Dataset &d  = *all[k];
      const hsize_t  lo = d.Rows() * (hsize_t)rank / (hsize_t)size, hi = d.Rows() * (hsize_t)(rank + 1) / (hsize_t)size;
      for (hsize_t a = lo; a < hi; a += chunk) {
        const hsize_t b = std::min(hi, a + chunk);
        if (d.ValueKind() == Kind::Real) PetscCall(d.Read(a, b, real, &shares[k]));
        else if (d.ValueKind() == Kind::Key) PetscCall(d.Read(a, b, words, &shares[k]));
        else PetscCall(d.Read(a, b, ints, &shares[k]));
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCall(AgreeOnError(comm, hash_slabs(), "reading the checkpoint"));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, shares.data(), (PetscMPIInt)shares.size(), MPI_UINT64_T, MPI_SUM, comm));
  for (size_t k = 0; k < all.size(); k++) PetscCall(CheckChecksum(all[k]->Path(), shares[k], all[k]->Stored()));

  /* this rank's range of rows: bisection on the keys (one key read a probe) */
  if (keys.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  std::vector<std::uint64_t> probe;
  std::uint64_t              ignore = 0;
  /* the first row whose key is >= k (with `after`: > k) */
  auto first_row = [&](std::uint64_t k, bool after, hsize_t *row) -> PetscErrorCode {
    hsize_t lo = 0, hi = key.Rows();
    PetscFunctionBeginUser;
    while (lo < hi) {
      const hsize_t mid = lo + (hi - lo) / 2;
      PetscCall(key.Read(mid, mid + 1, probe, &ignore));
      if (after ? probe[0] <= k : probe[0] < k) lo = mid + 1;
      else hi = mid;
    }
    *row = lo;
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  hsize_t a = 0, b = 0;
  PetscCall(first_row(keys.front().first, false, &a));
  PetscCall(first_row(keys.back().first, true, &b));
  /* the ragged columns' values before row a */
  std::vector<hsize_t>      value_at(ncol, 0);
  std::vector<std::int64_t> lens;
  for (size_t c = 0; c < ncol; c++)
    if (cols[c].width == 0)
      for (hsize_t r = 0; r < a; r += chunk) {
        PetscCall(length[c].Read(r, std::min(a, r + chunk), lens, &ignore));
        for (std::int64_t l : lens) value_at[c] += (hsize_t)std::max((std::int64_t)0, l);
      }
  /* rows [a, b) in chunks, this rank's keys' handed on chunk by chunk */
  Rows          C, R;
  size_t        next = 0; /* this rank's first key not yet passed */
  std::uint64_t last = 0;
  C.data.assign(ncol, {});
  C.length.assign(ncol, {});
  for (hsize_t r0 = a; r0 < b; r0 += chunk) {
    R.key.clear(), R.holder.clear(), R.owned.clear();
    R.data.assign(ncol, {});
    R.length.assign(ncol, {});
    const hsize_t r1 = std::min(b, r0 + chunk);
    PetscCall(key.Read(r0, r1, C.key, &ignore));
    PetscCall(holder.Read(r0, r1, C.holder, &ignore));
    PetscCall(owned.Read(r0, r1, C.owned, &ignore));
    std::vector<size_t> start(ncol, 0);
    for (size_t c = 0; c < ncol; c++) {
      if (cols[c].width == 0) {
        PetscCall(length[c].Read(r0, r1, C.length[c], &ignore));
        hsize_t n = 0;
        for (std::int64_t l : C.length[c]) {
          PetscCheck(l >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s.length: a negative length", data[c].Path().c_str());
          n += (hsize_t)l;
        }
        if (cols[c].integer) {
          PetscCall(data[c].Read(value_at[c], value_at[c] + n, lens, &ignore));
          C.data[c].assign(lens.begin(), lens.end());
        } else PetscCall(data[c].Read(value_at[c], value_at[c] + n, C.data[c], &ignore));
        PetscCheck(C.data[c].size() == n, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: fewer values than its lengths say", data[c].Path().c_str());
        value_at[c] += n;
      } else if (cols[c].integer) {
        PetscCall(data[c].Read(r0, r1, lens, &ignore));
        C.data[c].assign(lens.begin(), lens.end());
      } else PetscCall(data[c].Read(r0, r1, C.data[c], &ignore));
    }
    for (size_t i = 0; i < C.key.size(); i++) {
      PetscCheck(C.key[i] >= last, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: the rows are not in key order", group.c_str());
      last = C.key[i];
      while (next < keys.size() && keys[next].first < C.key[i]) next++;
      const bool mine = next < keys.size() && keys[next].first == C.key[i];
      for (size_t c = 0; c < ncol; c++) {
        const size_t w = cols[c].width > 0 ? (size_t)cols[c].width : (size_t)C.length[c][i];
        if (mine) R.data[c].insert(R.data[c].end(), C.data[c].begin() + start[c], C.data[c].begin() + start[c] + w);
        if (mine && cols[c].width == 0) R.length[c].push_back((std::int64_t)w);
        start[c] += w;
      }
      if (!mine) continue;
      R.key.push_back(C.key[i]);
      R.holder.push_back(C.holder[i]);
      R.owned.push_back(C.owned[i]);
    }
    PetscCall(consume(R));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode CheckpointReader::HasText(const std::string &name, bool *has)
{
  PetscFunctionBeginUser;
  const std::string p = "/text/" + name;
  *has                = H5Lexists(file_, "/text", H5P_DEFAULT) > 0 && H5Lexists(file_, p.c_str(), H5P_DEFAULT) > 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::Text(const std::string &name, std::string *value)
{
  std::vector<unsigned char> b;
  hsize_t                    dims[2];
  PetscFunctionBeginUser;
  PetscCall(ReadDataset(file_, "/text/" + name, Kind::Byte, b, dims));
  value->assign(b.begin(), b.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::Layouts(const StateNumbering &numbering, PetscInt *writers, bool *same_layout)
{
  std::vector<std::uint64_t> layout;
  hsize_t                    dims[2];
  PetscMPIInt                rank, size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCall(ReadDataset(file_, "/layout", Kind::Key, layout, dims));
  writers_                        = (PetscInt)layout.size();
  std::uint64_t              mine = numbering.Layout();
  std::vector<std::uint64_t> ours((size_t)size);
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_UINT64_T, ours.data(), 1, MPI_UINT64_T, comm_));
  /* every rank pairs the ranks of this run with the writers the same way: each with the first writer
     of its layout not yet taken */
  writer_taken_.assign(layout.size(), 0);
  bool all = (size_t)size == layout.size();
  for (PetscMPIInt q = 0; q < size; q++) {
    PetscInt m = -1;
    for (size_t w = 0; w < layout.size() && m < 0; w++)
      if (!writer_taken_[w] && layout[w] == ours[q]) m = (PetscInt)w;
    if (m >= 0) writer_taken_[m] = 1;
    else all = false;
    if (q == rank) matched_ = m;
  }
  *writers     = writers_;
  *same_layout = all;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::ReadTable(const std::string &group, StateTable &table, const StateNumbering &numbering)
{
  const std::vector<StateColumn> &cols = table.Columns();
  const size_t                    ncol = cols.size();
  const StateEntity               e    = table.Entity();
  PetscMPIInt                     rank;
  hsize_t                         dims[2];
  Rows                            R;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  {
    hid_t g = H5Gopen2(file_, group.c_str(), H5P_DEFAULT);
    TG_H5R(g, "the checkpoint has no %s (its run had other physics, or another version of turgor wrote it)", group.c_str());
    /* every dataset of the group must be declared: key, holder, owned, the columns */
    hsize_t    nlinks = 0;
    H5G_info_t info;
    if (H5Gget_info(g, &info) >= 0) nlinks = info.nlinks;
    for (hsize_t i = 0; i < nlinks; i++) {
      char name[256] = "";
      H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, i, name, sizeof name, H5P_DEFAULT);
      std::string s     = name;
      bool        known = s == "key" || s == "holder" || s == "owned";
      for (const StateColumn &c : cols) known = known || s == c.name || (c.width == 0 && s == c.name + ".length");
      if (!known) {
        H5Gclose(g);
        SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "the checkpoint holds %s/%s, which this run does not keep (its run had other physics?)",
                group.c_str(), name);
      }
    }
    H5Gclose(g);
  }
  if (e == StateEntity::Rank || table.IsRecords()) { /* a row per writer, or records found by their contents: the whole table on every rank */
    PetscCall(ReadDataset(file_, group + "/key", Kind::Key, R.key, dims));
    const size_t N = R.key.size();
    PetscCall(ReadDataset(file_, group + "/holder", Kind::Int, R.holder, dims));
    PetscCall(ReadDataset(file_, group + "/owned", Kind::Int, R.owned, dims));
    PetscCheck(R.holder.size() == N && R.owned.size() == N, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: key, holder and owned differ in length",
               group.c_str());
    R.data.assign(ncol, {});
    R.length.assign(ncol, {});
    for (size_t c = 0; c < ncol; c++) {
      const StateColumn &col  = cols[c];
      const std::string  path = group + "/" + col.name;
      if (col.integer) {
        std::vector<std::int64_t> v;
        PetscCall(ReadDataset(file_, path, Kind::Int, v, dims));
        R.data[c].assign(v.begin(), v.end());
      } else PetscCall(ReadDataset(file_, path, Kind::Real, R.data[c], dims));
      if (col.width > 0)
        PetscCheck(dims[0] == N && dims[1] == (hsize_t)col.width, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
                   "%s holds %llu x %llu values, this run keeps %zu x %d (another scene?)", path.c_str(), (unsigned long long)dims[0],
                   (unsigned long long)dims[1], N, col.width);
      else {
        PetscCall(ReadDataset(file_, path + ".length", Kind::Int, R.length[c], dims));
        PetscCheck(R.length[c].size() == N, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s.length has %zu rows, the table %zu", path.c_str(),
                   R.length[c].size(), N);
      }
    }
  }
  /* the rows being read (the whole table, or a chunk of this rank's rows), and a ragged column's
     rows' starts in them */
  const Rows                      *rows = &R;
  std::vector<std::vector<size_t>> offset(ncol);
  auto                             take = [&](const Rows &T) -> PetscErrorCode {
    PetscFunctionBeginUser;
    rows = &T;
    for (size_t c = 0; c < ncol; c++) {
      offset[c].clear();
      if (cols[c].width > 0) continue;
      const std::string path = group + "/" + cols[c].name;
      size_t            sum  = 0;
      for (std::int64_t l : T.length[c]) {
        PetscCheck(l >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s.length: a negative length", path.c_str());
        offset[c].push_back(sum), sum += (size_t)l;
      }
      PetscCheck(sum == T.data[c].size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: %zu values, its lengths say %zu", path.c_str(), T.data[c].size(),
                                             sum);
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCall(take(R));
  const size_t N = R.key.size();
  /* row i's values of column c into the table's row r (references made local) */
  std::vector<PetscReal> buf;
  auto                   put = [&](size_t i, size_t c, size_t r) -> PetscErrorCode {
    const StateColumn &col = cols[c];
    PetscFunctionBeginUser;
    const size_t w = col.width > 0 ? (size_t)col.width : (size_t)rows->length[c][i];
    const size_t o = col.width > 0 ? i * w : offset[c][i];
    buf.assign(rows->data[c].begin() + o, rows->data[c].begin() + o + w);
    if (col.is_ref)
      for (PetscReal &v : buf) {
        if (v < 0) continue;
        const PetscInt l = numbering.Local(col.ref, (std::uint64_t)v);
        PetscCheck(l >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
                                     "%s/%s names %s %.0f, which is not on rank %d (its halo is narrower than the run's that wrote it?)", group.c_str(), col.name.c_str(),
                                     StateEntityName(col.ref), (double)v, rank);
        v = (PetscReal)l;
      }
    if (col.width > 0) col.set(r, buf.data());
    else PetscCall(col.set_ragged(r, buf.data(), buf.size()));
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  auto value = [&](size_t i, size_t c, size_t k) { return rows->data[c][i * (size_t)cols[c].width + k]; };

  if (e == StateEntity::Rank) {
    /* one row per writer: this rank's writer's, or the rules */
    PetscCheck(N == (size_t)writers_, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s has %zu rows, the file %" PetscInt_FMT " writers", group.c_str(), N,
               writers_);
    std::vector<PetscReal> v;
    for (size_t c = 0; c < ncol; c++) {
      const StateColumn &col = cols[c];
      if (col.width == 0) { /* a sequence: its writer's, or the first writer's */
        if (matched_ >= 0) PetscCall(put((size_t)matched_, c, 0));
        else if (col.combine != Combine::Local && N > 0) PetscCall(put(0, c, 0));
        continue;
      }
      if (matched_ >= 0 && (col.combine != Combine::Sum || rank != 0)) { /* its writer's value, as written */
        PetscCall(put((size_t)matched_, c, 0));
        continue;
      }
      const size_t w = (size_t)col.width;
      v.assign(w, 0);
      switch (col.combine) {
      case Combine::Sum: /* the first rank: its writer's share and those of the writers nobody took */
        if (matched_ >= 0)
          for (size_t k = 0; k < w; k++) v[k] = value((size_t)matched_, c, k);
        if (rank == 0)
          for (size_t i = 0; i < N; i++)
            if (!writer_taken_[i])
              for (size_t k = 0; k < w; k++) v[k] += value(i, c, k);
        col.set(0, v.data());
        break;
      case Combine::Max:
        for (size_t k = 0; k < w; k++) {
          v[k] = value(0, c, k);
          for (size_t i = 1; i < N; i++) v[k] = std::max(v[k], value(i, c, k));
        }
        col.set(0, v.data());
        break;
      case Combine::Local:
        break;
      default: /* Owner, Copy: the first writer's, the same on every writer */
        if (N > 0) PetscCall(put(0, c, 0));
      }
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  if (table.IsRecords()) {
    const int           anchor = table.AnchorColumn();
    std::vector<size_t> keep;
    for (size_t i = 0; i < N; i++) {
      if (matched_ >= 0) {
        if (R.holder[i] == matched_) keep.push_back(i);
        continue;
      }
      if (!R.owned[i]) continue;
      if (anchor < 0) { /* no anchor: the first rank keeps every record */
        if (rank == 0) keep.push_back(i);
        continue;
      }
      const PetscReal id = value(i, (size_t)anchor, 0);
      const PetscInt  l  = id < 0 ? -1 : numbering.Local(cols[anchor].ref, (std::uint64_t)id);
      if (l >= 0 && numbering.Owned(cols[anchor].ref, l)) keep.push_back(i);
    }
    table.Resize(keep.size());
    for (size_t r = 0; r < keep.size(); r++)
      for (size_t c = 0; c < ncol; c++) PetscCall(put(keep[r], c, r));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  /* indexed rows: each local row by its entity's id, read in chunks of this rank's rows
     (ReadRowsOfKeys) */
  const size_t      n = table.Count();
  std::vector<char> owned(n), found(n, 0);
  KeyRows           keys(n); /* (id, row), by id: the chunks come in the ids' order, a cursor finds a row's (a hash map took 40 B an entity) */
  for (size_t r = 0; r < n; r++) {
    keys[r]  = {numbering.Id(e, table.Local(r)), r};
    owned[r] = table.OwnedOverride() ? table.Owned(r) : numbering.Owned(e, table.Local(r));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end(), [](const auto &x, const auto &y) { return x.first == y.first; }), keys.end());
  size_t cursor = 0;
  auto   row_of = [&](std::uint64_t id) -> PetscInt { /* ids asked in increasing order */
                                                    while (cursor < keys.size() && keys[cursor].first < id) cursor++;
                                                    return cursor < keys.size() && keys[cursor].first == id ? (PetscInt)keys[cursor].second : -1;
  };
  if (matched_ >= 0) {
    PetscCall(ReadRowsOfKeys(comm_, file_, group, cols, keys, read_rows_, [&](const Rows &T) -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(take(T));
      for (size_t i = 0; i < T.key.size(); i++) {
        if (T.holder[i] != matched_) continue;
        const PetscInt r = row_of(T.key[i]);
        PetscCheck(r >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: the checkpoint's %s %llu is not on rank %d", group.c_str(), StateEntityName(e),
                   (unsigned long long)T.key[i], rank);
        for (size_t c = 0; c < ncol; c++) PetscCall(put(i, c, (size_t)r));
        found[r] = 1;
      }
      PetscFunctionReturn(PETSC_SUCCESS);
    }));
    for (size_t r = 0; r < n; r++)
      PetscCheck(found[r], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: the checkpoint has no row for rank %d's %s %llu", group.c_str(), rank,
                 StateEntityName(e), (unsigned long long)numbering.Id(e, table.Local(r)));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* another layout: sums start from zero on every local row, shares are added on the owner (in the
     file's order, as one rank reading the whole table would) */
  std::vector<PetscReal> zero;
  for (size_t c = 0; c < ncol; c++)
    if (cols[c].combine == Combine::Sum) {
      PetscCheck(cols[c].width > 0, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s/%s: a ragged share", group.c_str(), cols[c].name.c_str());
      zero.assign((size_t)cols[c].width, 0);
      for (size_t r = 0; r < n; r++) cols[c].set(r, zero.data());
    }
  std::vector<PetscReal> cur;
  PetscCall(ReadRowsOfKeys(comm_, file_, group, cols, keys, read_rows_, [&](const Rows &T) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(take(T));
    for (size_t i = 0; i < T.key.size(); i++) {
      const PetscInt ri = row_of(T.key[i]);
      if (ri < 0) continue;
      const size_t r = (size_t)ri;
      for (size_t c = 0; c < ncol; c++) {
        const StateColumn &col = cols[c];
        switch (col.combine) {
        case Combine::Sum:
          if (!owned[r]) break;
          cur.resize((size_t)col.width);
          col.get(r, cur.data());
          for (int k = 0; k < col.width; k++) cur[k] += value(i, c, (size_t)k);
          col.set(r, cur.data());
          break;
        case Combine::Copy:
          if (T.owned[i]) PetscCall(put(i, c, r));
          break;
        case Combine::Local:
          break;
        default:
          if (T.owned[i] && owned[r]) PetscCall(put(i, c, r));
        }
      }
      if (T.owned[i]) found[r] = 1;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }));
  for (size_t r = 0; r < n; r++)
    PetscCheck(found[r] || !owned[r], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: the checkpoint has no row for %s %llu", group.c_str(),
               StateEntityName(e), (unsigned long long)numbering.Id(e, table.Local(r)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::State(const std::vector<StateDeclaration *> &decls, const StateNumbering &numbering)
{
  PetscFunctionBeginUser;
  PetscCheck(writers_ > 0, PETSC_COMM_SELF, PETSC_ERR_ORDER, "CheckpointReader::Layouts() first");
  PetscCall(CheckSameDeclarations(comm_, decls));
  /* a rank's error is every rank's: the next table is read collectively */
  for (StateDeclaration *d : decls)
    for (StateTable &t : d->Tables()) PetscCall(AgreeOnError(comm_, ReadTable("/state/" + d->Name() + "/" + t.Name(), t, numbering), "reading the checkpoint"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckpointReader::Close()
{
  PetscFunctionBeginUser;
  if (file_ >= 0) H5Fclose(file_);
  file_ = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
