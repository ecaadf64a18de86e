#pragma once
/* Declared state: everything an object keeps from one step to the next, declared once, by name, with
   the entity that owns it. Checkpoints are written and read from the declarations alone
   (checkpoint_file.h): no object has checkpoint code of its own.

   An object declares into a StateDeclaration (its name, e.g. "glue"):
   - scalars (Scalar): one value per rank, with the rule that combines them when a checkpoint is
     read on another layout (Combine);
   - tables (Table): rows of one kind of entity (a particle, a bar, a cell, a material point, an entry
     of the integrated state), each with an id that does not depend on the ranks (its key), and
     columns: a name, a width (values per row; 0 = a per-row length), reals or integers, and the
     combination rule. A column that names an entity (a bond's node and bar) is a reference: it is
     written as the entity's id and read back as this rank's number for it.
   A table's rows either exist already (indexed: the hinges of the tissue, the particles; the reader
   finds each row by its key) or are made by the reader (records: glue bonds, contact histories; a row
   is kept by the rank that owns its anchor, the entity its anchor column names).

   Reading on the layout that wrote a rank's rows (the same particles in the same order: the same rank
   count and distribution, or the rank that held every particle of a -fine_distribute 0 run) gives
   that rank its writer's rows exactly, whatever the rule: the run continues bit for bit. On another
   layout the rules say what each rank gets. After the reader has filled every declaration, the owner
   rebuilds what it derives from its state (its own AfterStateRead hooks: lists, trial values). */
#include <turgor/core/petsc_compat.h>
#include <petscsys.h>
#include <cstdint>
#include <cstring>
#include <deque>
#include <type_traits>
#include <functional>
#include <string>
#include <vector>

namespace turgor {

/* What a row of a table is. Rank: one row per rank (an object's scalars). */
enum class StateEntity {
  Rank,
  Particle,
  Bar,
  Cell,
  MaterialPoint,
  StateEntry
};
const char *StateEntityName(StateEntity e);

/* How a column combines when a checkpoint is read on another layout.
   Owner: the value written by the rank that owned the row (scalars: the first rank's, the same on
          every rank);
   Sum:   each holder's share: added up on the owner (scalars: the first rank takes the total);
   Copy:  the owner's value, also given to every other rank that holds a copy (a halo particle);
   Max:   scalars: the largest;
   Local: meaningful on its writer's layout only (the neighbour lists' reference positions): left as
          the owner set it up, which then rebuilds it. */
enum class Combine {
  Owner,
  Sum,
  Copy,
  Max,
  Local
};

struct StateColumn {
  std::string name;
  int         width   = 1;     /* values per row; 0: a per-row length (ragged) */
  bool        integer = false; /* stored as integers (exact), else as reals */
  bool        is_ref  = false; /* an integer that is a local number of `ref`: written as its id */
  StateEntity ref     = StateEntity::Rank;
  Combine     combine = Combine::Owner;
  /* fixed width: row r's `width` values; ragged: row r's values (any number) */
  std::function<void(size_t, PetscReal *)>                         get;
  std::function<void(size_t, const PetscReal *)>                   set;
  std::function<void(size_t, std::vector<PetscReal> &)>            get_ragged;
  std::function<PetscErrorCode(size_t, const PetscReal *, size_t)> set_ragged;
};

class StateTable {
public:
  StateTable(std::string name, StateEntity entity) : name_(std::move(name)), entity_(entity) { }

  /* Indexed rows: `count` rows exist on this rank, row r of entity local(r) (its key: the entity's
     id), owned by this rank or a copy of another rank's (a halo particle). */
  StateTable &Rows(std::function<size_t()> count, std::function<PetscInt(size_t)> local = nullptr, std::function<bool(size_t)> owned = nullptr);
  /* Records: `count` rows, row r's key (unique, rank-free), made by the reader with `resize`; on
     another layout a row is kept by the owner of the entity its column `anchor` names. */
  StateTable &Records(std::function<size_t()> count, std::function<std::uint64_t(size_t)> key, std::function<void(size_t)> resize, const std::string &anchor);

  /* Columns. A per-row array: values [rows x width] in `v` (indexed tables; the reader fills it in place). */
  StateTable &Column(const std::string &name, std::vector<PetscReal> &v, int width = 1, Combine c = Combine::Owner);
  StateTable &Column(const std::string &name, std::vector<PetscInt> &v, int width = 1, Combine c = Combine::Owner);
  /* A member of a record type held in `rows` (rows.size() is the table's row count). */
  template <class T>
  StateTable &Field(const std::string &name, std::vector<T> &rows, PetscReal T::*m, Combine c = Combine::Owner)
  {
    return Add(Real1(
      name, [&rows, m](size_t r) { return rows[r].*m; }, [&rows, m](size_t r, PetscReal v) { rows[r].*m = v; }, c));
  }
  template <class T>
  StateTable &Field(const std::string &name, std::vector<T> &rows, PetscInt T::*m, Combine c = Combine::Owner)
  {
    StateColumn col = Real1(
      name, [&rows, m](size_t r) { return (PetscReal)(rows[r].*m); }, [&rows, m](size_t r, PetscReal v) { rows[r].*m = (PetscInt)v; }, c);
    col.integer = true;
    return Add(col);
  }
  /* A member made of reals only (a Tensor2, a pair of 3 x 3 tangents), as that many values (trivially
     copyable: memcpy through void *, which such types with default member initialisers need to build
     without -Wclass-memaccess). */
  template <class T, class M>
  StateTable &Field(const std::string &name, std::vector<T> &rows, M T::*m, Combine c = Combine::Owner)
  {
    static_assert(std::is_trivially_copyable<M>::value && sizeof(M) % sizeof(PetscReal) == 0, "a member of reals");
    const int w = (int)(sizeof(M) / sizeof(PetscReal));
    return Column(
      name, w, [&rows, m](size_t r, PetscReal *v) { std::memcpy(v, &(rows[r].*m), sizeof(M)); },
      [&rows, m](size_t r, const PetscReal *v) { std::memcpy(static_cast<void *>(&(rows[r].*m)), v, sizeof(M)); }, c);
  }
  /* Rows that are made of reals only (Tensor2), each as that many values. */
  template <class T>
  StateTable &Packed(const std::string &name, std::vector<T> &rows, Combine c = Combine::Owner)
  {
    static_assert(std::is_trivially_copyable<T>::value && sizeof(T) % sizeof(PetscReal) == 0, "rows of reals");
    const int w = (int)(sizeof(T) / sizeof(PetscReal));
    return Column(
      name, w, [&rows](size_t r, PetscReal *v) { std::memcpy(v, &rows[r], sizeof(T)); },
      [&rows](size_t r, const PetscReal *v) { std::memcpy(static_cast<void *>(&rows[r]), v, sizeof(T)); }, c);
  }
  /* An integer member that is this rank's number of an entity of kind `e` (written as its id). */
  template <class T>
  StateTable &Ref(const std::string &name, std::vector<T> &rows, PetscInt T::*m, StateEntity e)
  {
    StateColumn col = Real1(
      name, [&rows, m](size_t r) { return (PetscReal)(rows[r].*m); }, [&rows, m](size_t r, PetscReal v) { rows[r].*m = (PetscInt)v; }, Combine::Owner);
    col.integer = col.is_ref = true;
    col.ref                  = e;
    return Add(col);
  }
  /* Any other column: get and set row r's `width` values. */
  StateTable &Column(const std::string &name, int width, std::function<void(size_t, PetscReal *)> get, std::function<void(size_t, const PetscReal *)> set,
                     Combine c = Combine::Owner, bool integer = false);
  /* A column with a length of its own in every row (an RVE's unknowns). */
  StateTable &Ragged(const std::string &name, std::function<void(size_t, std::vector<PetscReal> &)> get,
                     std::function<PetscErrorCode(size_t, const PetscReal *, size_t)> set, bool integer = false);

  const std::string              &Name() const { return name_; }
  void                            Rename(const std::string &name) { name_ = name; }
  void                            SetLastCombine(Combine c) { columns_.back().combine = c; }
  StateEntity                     Entity() const { return entity_; }
  bool                            IsRecords() const { return (bool)resize_; }
  const std::vector<StateColumn> &Columns() const { return columns_; }
  size_t                          Count() const { return count_(); }
  /* row r: this rank's number of its entity (indexed tables), whether this rank owns it */
  PetscInt Local(size_t r) const { return local_ ? local_(r) : (PetscInt)r; }
  bool     OwnedOverride() const { return (bool)owned_; } /* else the numbering says who owns the row's entity */
  bool     Owned(size_t r) const { return owned_ ? owned_(r) : true; }
  /* records: row r's key, make n rows, the anchor column (index into Columns()) */
  std::uint64_t RecordKey(size_t r) const { return key_(r); }
  void          Resize(size_t n) const { resize_(n); }
  int           AnchorColumn() const;

private:
  StateColumn Real1(const std::string &name, std::function<PetscReal(size_t)> get, std::function<void(size_t, PetscReal)> set, Combine c);
  StateTable &Add(StateColumn col);

  std::string                          name_;
  StateEntity                          entity_;
  std::function<size_t()>              count_;
  std::function<PetscInt(size_t)>      local_;
  std::function<bool(size_t)>          owned_;
  std::function<std::uint64_t(size_t)> key_;
  std::function<void(size_t)>          resize_;
  std::string                          anchor_;
  std::vector<StateColumn>             columns_;
};

/* One object's declarations: its scalars (one row per rank) and its tables. */
class StateDeclaration {
public:
  explicit StateDeclaration(std::string name) : name_(std::move(name)) { }
  StateDeclaration(const StateDeclaration &)            = delete;
  StateDeclaration &operator=(const StateDeclaration &) = delete;
  StateDeclaration(StateDeclaration &&)                 = default;

  void Scalar(const std::string &name, PetscReal *v, Combine c);
  void Scalar(const std::string &name, PetscInt *v, Combine c);
  void Scalar(const std::string &name, bool *v, Combine c);
  void Scalar(const std::string &name, PetscBool *v, Combine c);
  /* A small array whose length the scene fixes (one value per term, say), combined value by value. */
  void Vector(const std::string &name, std::vector<PetscReal> *v, Combine c);
  void Array(const std::string &name, PetscReal *v, int n, Combine c);
  /* A sequence of any length, one per rank (an RVE's unknowns; the neighbour lists' build
     positions, Combine::Local): its writer's, or on another layout the first writer's (Owner). */
  void Sequence(const std::string &name, std::vector<PetscReal> *v, Combine c = Combine::Owner);
  void Sequence(const std::string &name, std::function<void(std::vector<PetscReal> &)> get, std::function<PetscErrorCode(const PetscReal *, size_t)> set,
                Combine c = Combine::Owner);
  /* A part's declarations as this one's tables, named "<part>.<table>" (an RVE's equations and
     relaxation, its force model's terms). */
  void Include(StateDeclaration &&part);
  /* A table of entity rows, named within the object ("bonds": the file's /state/glue/bonds). */
  StateTable &Table(const std::string &name, StateEntity e);

  const std::string            &Name() const { return name_; }
  std::deque<StateTable>       &Tables() { return tables_; }
  const std::deque<StateTable> &Tables() const { return tables_; }

private:
  StateTable            &Scalars();
  std::string            name_;
  std::deque<StateTable> tables_; /* the first: "scalars" (one row per rank), made at the first Scalar */
};

/* Nested state: an object that belongs to one row of a table (a material point's RVE) declares
   into its own StateDeclaration, whose tables become columns of that row: "<table>.rows" (the
   number of rows) and "<table>.<column>", each a sequence of numbers (a fixed column's values row
   after row; a ragged column's length before each row's values). References are not translated:
   such an object moves whole from rank to rank. Unpack makes a records table's rows and checks that
   every sequence is used up. */
std::vector<std::string> NestedColumns(const StateDeclaration &d);
PetscErrorCode           PackNested(const StateDeclaration &d, std::vector<std::vector<PetscReal>> &columns);
PetscErrorCode           UnpackNested(StateDeclaration &d, const std::vector<std::vector<PetscReal>> &columns);
/* The same as one sequence of numbers (each column's length, then its values): a material point
   sent to another rank. */
PetscErrorCode PackState(const StateDeclaration &d, std::vector<PetscReal> &out);
PetscErrorCode UnpackState(StateDeclaration &d, const PetscReal *in, size_t n);

/* The declarations of a run, in the order they are read back (an object's lists before the terms that
   use them), and how this rank numbers the entities. */
class StateNumbering {
public:
  virtual ~StateNumbering() = default;
  /* rank-free id of this rank's entity `local`, and back (-1: not on this rank) */
  virtual std::uint64_t Id(StateEntity e, PetscInt local) const      = 0;
  virtual PetscInt      Local(StateEntity e, std::uint64_t id) const = 0;
  /* whether this rank owns its entity `local` */
  virtual bool Owned(StateEntity e, PetscInt local) const = 0;
  /* a fingerprint of this rank's layout: equal on a rank of another run that holds the same entities
     in the same order (its rows are then read back as they were written) */
  virtual std::uint64_t Layout() const = 0;
};

/* The key of a pair of ids (a node and a bar), ordered by the first: ids below 2^32. */
inline std::uint64_t PairKey(std::uint64_t a, std::uint64_t b)
{
  return (a << 32) | b;
}

} // namespace turgor
