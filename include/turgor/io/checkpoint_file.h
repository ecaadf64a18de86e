#pragma once
/* The checkpoint file: one writer and one reader of declared state (declared_state.h), in parallel
   HDF5 (MPI-IO, collective writes).

   Layout:
     /                      attributes format_version, mode, ranks (the writing run's)
     /layout                one value per writing rank: its StateNumbering::Layout()
     /text/<name>           texts of the run (its physics parameters, its time series so far): bytes
     /state/<object>/<table>/key       the rows' rank-free ids, ascending (uint64)
                            /holder    the rank that wrote the row (its copy: a halo particle's too)
                            /owned     1 where the writer owned the row
                            /<column>  [rows x width] reals or integers; a ragged column's values
                                       with <column>.length [rows]
   Rows are in the order of their keys (then of their holders), whatever the number of ranks: the
   writer sorts them over the ranks (a bucket sort by key ranges), so a file of the same state written
   on 1 or 3 ranks holds the same rows in the same order. An object's scalars are its table
   "scalars", one row per rank. A reader takes only its own entities' rows, streamed in chunks from
   the range its keys span (records and per-rank tables whole).

   Integrity: every dataset is written in chunks with HDF5's Fletcher32 filter (damage to the file is
   found by HDF5 when the chunk is read) and carries the attribute `checksum`, a hash of its values
   and their positions computed by turgor (a value changed by a tool that rewrites the chunk and its
   Fletcher32 is found by it). A damaged, edited or incomplete file is refused naming the dataset. */
#include <turgor/io/declared_state.h>
#include <hdf5.h>
#include <functional>
#include <string>
#include <vector>

namespace turgor {

/* One value's share of a checksum: a mix of its bits and its position (rank-free: a dataset's row and
   column, a state's entry id), so that the shares of every rank's values add up (mod 2^64) to the
   checksum of all, in any order. */
std::uint64_t ChecksumTerm(std::uint64_t position, std::uint64_t word);
std::uint64_t ChecksumTerm(std::uint64_t position, PetscReal value);

class CheckpointWriter {
public:
  ~CheckpointWriter();
  /* Collective. The file is created (truncated). */
  PetscErrorCode Open(MPI_Comm comm, const std::string &path);
  PetscErrorCode Attribute(const std::string &name, const std::string &value);
  PetscErrorCode Attribute(const std::string &name, PetscInt value);
  /* A text (the first rank's) as /text/<name>. */
  PetscErrorCode Text(const std::string &name, const std::string &value);
  /* Every declaration's scalars and tables, and /layout. */
  PetscErrorCode State(const std::vector<StateDeclaration *> &decls, const StateNumbering &numbering);
  PetscErrorCode Close();
  /* Called on every rank before each declaration's tables are written (collective): a long write
     lets its caller act meanwhile (a run that is interrupted says so before the file is done). */
  void BetweenDeclarations(std::function<PetscErrorCode()> f) { between_ = std::move(f); }

private:
  PetscErrorCode                  WriteTable(const std::string &group, const StateTable &table, const StateNumbering &numbering);
  MPI_Comm                        comm_ = MPI_COMM_NULL;
  hid_t                           file_ = -1;
  std::string                     path_;
  std::function<PetscErrorCode()> between_;
};

class CheckpointReader {
public:
  ~CheckpointReader();
  /* Collective. Errors name the file. */
  PetscErrorCode Open(MPI_Comm comm, const std::string &path);
  PetscErrorCode HasAttribute(const std::string &name, bool *has);
  PetscErrorCode Attribute(const std::string &name, std::string *value);
  PetscErrorCode Attribute(const std::string &name, PetscInt *value);
  PetscErrorCode HasText(const std::string &name, bool *has);
  PetscErrorCode Text(const std::string &name, std::string *value);
  /* The number of ranks that wrote the file and whether every rank of this run holds what one of them
     held (StateNumbering::Layout): then the state is read back exactly as it was written. */
  PetscErrorCode Layouts(const StateNumbering &numbering, PetscInt *writers, bool *same_layout);
  /* Fill every declaration (collective; a file whose declarations differ from the run's, or whose
     rows do not fit this rank's entities, is refused naming the dataset). */
  PetscErrorCode State(const std::vector<StateDeclaration *> &decls, const StateNumbering &numbering);
  /* Rows of a table read at once (the read's memory beyond the run's; default 65 536). */
  void SetReadRows(PetscInt rows) { read_rows_ = rows > 0 ? (hsize_t)rows : 1; }
  /* After Layouts: whether this rank's rows are its writer's, as they were written. */
  bool           Matched() const { return matched_ >= 0; }
  PetscErrorCode Close();

private:
  PetscErrorCode ReadTable(const std::string &group, StateTable &table, const StateNumbering &numbering);
  MPI_Comm       comm_ = MPI_COMM_NULL;
  hid_t          file_ = -1;
  std::string    path_;
  PetscInt       writers_   = 0;
  hsize_t        read_rows_ = 1 << 16;
  /* the writer whose rows this rank takes as they are (-1: none, another layout), and whether some
     writer's rows were taken by no rank (its shares go to the first rank) */
  PetscInt          matched_ = -1;
  std::vector<char> writer_taken_;
};

} // namespace turgor
