#pragma once
/* Output files of a run: the directory (-output_dir), CSV time series and summary.json. All are
   written by rank 0 of the given communicator. */
#include <turgor/core/petsc_compat.h>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace turgor {

/* Read -output_dir (default: *dir, or ./out if empty) and -output_overwrite (default *overwrite),
   and make the directory ready on rank 0: created if missing; if it is not empty it is refused
   unless overwrite, which removes the files turgor writes (summary.json, tip.csv, ...) and keeps
   any others. A run then writes only files it owns. Under -help nothing is touched on disk and
   *prepared is false (the run only lists its options); otherwise true. */
PetscErrorCode OutputDirectory(MPI_Comm comm, std::string *dir, bool *overwrite, bool *prepared);

/* A CSV file with a header row; numbers are written with full precision. */
class CsvWriter {
public:
  PetscErrorCode Open(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns);
  PetscErrorCode Row(const std::vector<PetscReal> &values);
  PetscErrorCode RowText(const std::vector<std::string> &cells); /* cells written as they are (a word, a number already formatted) */
  PetscErrorCode Close();
  bool           IsOpen() const { return comm_ != MPI_COMM_NULL; }
  ~CsvWriter() { PetscCallVoid(Close()); }
  /* Rows written since Open (with Continue: including the rows kept). */
  PetscInt Rows() const { return rows_; }
  /* What the file holds so far (its header and rows): a checkpoint keeps it. */
  PetscErrorCode Contents(std::string *text);
  /* A restart: the file at `path` becomes `text` (a checkpoint's Contents, whose header must be
     these columns), and rows are appended after it. */
  PetscErrorCode Restore(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns, const std::string &text);

private:
  MPI_Comm    comm_ = MPI_COMM_NULL;
  FILE       *fp_   = nullptr;
  std::string path_;
  size_t      ncol_ = 0;
  PetscInt    rows_ = 0;
};

/* A flat JSON object whose keys keep their insertion order. */
class JsonObject {
public:
  void Set(const std::string &key, const std::string &value);
  void Set(const std::string &key, const char *value) { Set(key, std::string(value)); }
  void Set(const std::string &key, PetscReal value);
  void Set(const std::string &key, PetscInt value);
  void Set(const std::string &key, bool value);
  void Set(const std::string &key, const std::vector<std::string> &values);
  void Set(const std::string &key, const std::vector<PetscReal> &values);
  /* Insert an already formatted JSON value (object, array). */
  void           SetRaw(const std::string &key, const std::string &json);
  std::string    Str(int indent = 2) const;
  PetscErrorCode Write(MPI_Comm comm, const std::string &path) const;

private:
  std::vector<std::pair<std::string, std::string>> items_;
};

std::string JsonQuote(const std::string &s);

/* Rank 0's string on every rank (collective). */
PetscErrorCode BroadcastString(MPI_Comm comm, std::string *s);

} // namespace turgor
