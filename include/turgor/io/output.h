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

/* Whether `name` is a file turgor writes into an output directory (summary.json, tip.csv, the
   snapshots, checkpoints, ...): the files -output_overwrite removes and the closing report lists. */
bool IsOutputFile(const std::string &name);
/* The output files in `dir` (this process's view: rank 0 calls it), in turgor's order of them:
   what a run wrote there, since it starts from a directory without them (or continues its own). */
std::vector<std::string> OutputFilesIn(const std::string &dir, bool with_summary = true);
/* Those files as one line, "tip.csv, summary.json, ..." */
std::string OutputFileList(const std::string &dir);

/* A file written by one process with every write, flush and close checked: the first failure is
   kept as "cannot write PATH: REASON" (Error(), "" while all is well), and later writes are
   skipped. Nothing is raised: the caller says it on every rank that must stop (CheckOutputError),
   so that a failure met by the writing rank alone does not leave the others in a collective call.
   `in_place`: an existing file is overwritten from its start and cut to what was written when it
   is closed, instead of being truncated first: it needs no new space up to its old size. */
class OutputFile {
public:
  OutputFile() = default;
  ~OutputFile() { Abandon(); }
  OutputFile(const OutputFile &)                   = delete;
  OutputFile        &operator=(const OutputFile &) = delete;
  void               Open(const std::string &path, bool in_place = false);
  void               Write(const std::string &text);
  void               Flush();
  void               Close();   /* flushed and closed, checked */
  void               Abandon(); /* closed without a check: after a failure elsewhere */
  bool               IsOpen() const { return fp_ != nullptr; }
  const std::string &Error() const { return error_; }
  const std::string &Path() const { return path_; }

private:
  void        Fail(const char *what);
  FILE       *fp_ = nullptr;
  std::string path_, error_;
  bool        in_place_ = false;
};

/* Collective on comm: rank 0's `error` (an OutputFile's; "" when none) becomes an error on every rank
   (PETSC_ERR_FILE_WRITE) that names the file and the reason. */
PetscErrorCode CheckOutputError(MPI_Comm comm, const std::string &error);

/* A CSV file with a header row, written by rank 0 of `comm`; numbers are written with full
   precision. Write failures are kept, not raised (OutputFile): Error() says the first one, Close()
   raises it (collective on comm). */
class CsvWriter {
public:
  PetscErrorCode Open(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns);
  PetscErrorCode Row(const std::vector<PetscReal> &values);
  PetscErrorCode RowText(const std::vector<std::string> &cells); /* cells written as they are (a word, a number already formatted) */
  /* Flushed and closed; a write that failed is an error on every rank of comm (collective). */
  PetscErrorCode Close();
  /* Flushed and closed, a failure kept in Error() (not raised: for a caller that says it on more
     ranks than the writer's). */
  void Finish();
  /* What was written so far handed to the file system (a failure kept in Error()). */
  void Flush() { file_.Flush(); }
  /* Closed without a check (after a failure elsewhere). */
  void               Abandon();
  bool               IsOpen() const { return comm_ != MPI_COMM_NULL; }
  const std::string &Error() const { return file_.Error(); }
  ~CsvWriter() { Abandon(); }
  /* Rows written since Open (with Continue: including the rows kept). */
  PetscInt Rows() const { return rows_; }
  /* What the file holds so far (its header and rows): a checkpoint keeps it. A failure to flush
     or read it back is kept in Error(). */
  PetscErrorCode Contents(std::string *text);
  /* A restart: the file at `path` becomes `text` (a checkpoint's Contents, whose header must be
     these columns), and rows are appended after it. */
  PetscErrorCode Restore(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns, const std::string &text);

private:
  MPI_Comm   comm_ = MPI_COMM_NULL;
  OutputFile file_;
  size_t     ncol_ = 0;
  PetscInt   rows_ = 0;
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
  void        SetRaw(const std::string &key, const std::string &json);
  std::string Str(int indent = 2) const;
  /* The object as the file `path`, by rank 0 of comm (collective): in place over a file there
     (OutputFile), so that a summary reserved at the start (ReserveSummary) is still written on a
     file system that filled up since; a failure is an error naming the file. */
  PetscErrorCode Write(MPI_Comm comm, const std::string &path) const;

private:
  std::vector<std::pair<std::string, std::string>> items_;
};

std::string JsonQuote(const std::string &s);

/* summary.json at the start of a run's outputs (rank 0 of comm, collective): status "running",
   padded to kSummaryReserve bytes, the space its final version takes on a full file system. A run
   that ends without replacing it was killed (SIGKILL, out of memory, a lost node). */
PetscErrorCode   ReserveSummary(MPI_Comm comm, const std::string &path, const std::string &mode);
constexpr size_t kSummaryReserve = 16384;

/* Rank 0's string on every rank (collective). */
PetscErrorCode BroadcastString(MPI_Comm comm, std::string *s);

} // namespace turgor
