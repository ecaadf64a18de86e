#include <fstream>
#include <turgor/io/output.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <system_error>
#include <unistd.h>
#include <vector>

namespace turgor {

/* The files turgor writes into an output directory (any mode): the only ones -output_overwrite
   removes. */
static const char *const kOutputFiles[] = {"summary.json", "tip.csv",       "groups.csv",   "rve.csv",    "particles.h5", "particles.xmf",
                                           "coarse.h5",    "coarse.xmf",    "eigen.csv",    "modes.h5",   "modes.xmf",    "stability.csv",
                                           "stability.h5", "stability.xmf", "spectrum.png", "energy.csv", "breaks.csv"};

static bool EndsWith(const std::string &s, const char *tail)
{
  const size_t n = std::strlen(tail);
  return s.size() > n && s.compare(s.size() - n, n, tail) == 0;
}

/* checkpoint.h5, checkpoint_<step>.h5 (and one being written, .h5.tmp), a restart's snapshots */
static bool IsRunFile(const std::string &name, bool written)
{
  return (name.rfind("checkpoint", 0) == 0 && (EndsWith(name, ".h5") || (!written && EndsWith(name, ".h5.tmp")))) || name.rfind("particles_restart", 0) == 0 ||
         name.rfind("coarse_restart", 0) == 0;
}

bool IsOutputFile(const std::string &name)
{
  for (const char *o : kOutputFiles)
    if (name == o) return true;
  return IsRunFile(name, false);
}

std::vector<std::string> OutputFilesIn(const std::string &dir, bool with_summary)
{
  namespace fs = std::filesystem;
  std::error_code          ec;
  std::vector<std::string> here, out;
  for (const auto &entry : fs::directory_iterator(dir, ec)) here.push_back(entry.path().filename().string());
  for (const char *o : kOutputFiles)
    if (std::find(here.begin(), here.end(), o) != here.end() && (with_summary || std::strcmp(o, "summary.json") != 0)) out.push_back(o);
  std::vector<std::string> more; /* checkpoints and a restart's snapshots, by name */
  for (const std::string &name : here)
    if (IsRunFile(name, true)) more.push_back(name);
  std::sort(more.begin(), more.end());
  out.insert(out.end(), more.begin(), more.end());
  return out;
}

std::string OutputFileList(const std::string &dir)
{
  std::string              list;
  std::vector<std::string> steps; /* checkpoint_<step>.h5: more than two are one item, first to last */
  for (const std::string &f : OutputFilesIn(dir)) {
    if (f.rfind("checkpoint_", 0) == 0) steps.push_back(f);
    else list += (list.empty() ? "" : ", ") + f;
  }
  if (steps.size() > 2) list += (list.empty() ? "" : ", ") + steps.front() + " to " + steps.back() + " (" + std::to_string(steps.size()) + " checkpoints)";
  else
    for (const std::string &f : steps) list += (list.empty() ? "" : ", ") + f;
  return list;
}

PetscErrorCode OutputDirectory(MPI_Comm comm, std::string *dir, bool *overwrite, bool *prepared)
{
  char        buf[PETSC_MAX_PATH_LEN];
  PetscBool   replace = *overwrite ? PETSC_TRUE : PETSC_FALSE;
  PetscMPIInt rank;
  /* 0: ready; 1: cannot create; 2: not empty and no -output_overwrite; 3: cannot write into it
     (`why`); 4: an earlier output cannot be removed (`why`) */
  int         state = 0;
  std::string why;
  std::string found, kept;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buf, dir->empty() ? "./out" : dir->c_str(), sizeof buf));
  PetscOptionsBegin(comm, NULL, "Output", "turgor");
  PetscCall(PetscOptionsString("-output_dir", "Directory for all outputs of the run", "turgor", buf, buf, sizeof buf, NULL));
  PetscCall(PetscOptionsBool("-output_overwrite", "Replace the outputs of an earlier run in -output_dir (otherwise a directory that is not empty is refused)",
                             "turgor", replace, &replace, NULL));
  PetscOptionsEnd();
  /* -restart continues the run whose outputs the directory holds: nothing is refused or removed
     (the time series are cut back to the checkpoint and appended to) */
  PetscBool restart;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-restart", &restart));
  PetscCheck(buf[0], comm, PETSC_ERR_ARG_WRONG, "Option -output_dir: empty");
  {
    PetscBool help;
    PetscCall(PetscOptionsHasHelp(NULL, &help));
    *prepared = !help;
    if (help) { /* -help lists options: no directory is created, cleared or written */
      *dir       = buf;
      *overwrite = replace;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(buf, ec) && !fs::is_directory(buf, ec)) state = 1;
    else if (fs::exists(buf, ec)) {
      std::vector<fs::path> ours;
      for (const auto &entry : fs::directory_iterator(buf, ec)) {
        const std::string name = entry.path().filename().string();
        if (IsOutputFile(name)) ours.push_back(entry.path());
        else kept += (kept.empty() ? "" : ", ") + name;
        found += (found.empty() ? "" : ", ") + name;
      }
      if (restart) { /* kept: the run continues them */
      } else if (!found.empty() && !replace) state = 2;
      else
        for (const auto &f : ours) {
          std::error_code rec;
          if (!fs::remove(f, rec) && rec && !state) {
            state = 4;
            why   = f.filename().string() + " (" + rec.message() + ")";
          }
        }
    } else {
      fs::create_directories(buf, ec);
      if (ec) state = 1;
    }
    if (!state) {
      /* a directory that exists but cannot be written (read-only, immutable, full): refused now,
         before any work, not when the first output is written */
      const std::string probe = std::string(buf) + "/.turgor_write_check_" + std::to_string((long long)getpid());
      const int         fd    = open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
      if (fd < 0 || write(fd, "\n", 1) != 1) {
        state = 3;
        why   = std::strerror(errno);
      }
      if (fd >= 0) {
        if (close(fd) != 0 && !state) {
          state = 3;
          why   = std::strerror(errno);
        }
        (void)unlink(probe.c_str());
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&state, 1, MPI_INT, 0, comm));
  PetscCall(BroadcastString(comm, &why));
  PetscCheck(state != 3, comm, PETSC_ERR_FILE_WRITE, "Option -output_dir = %s: cannot write into the directory (%s)", buf, why.c_str());
  PetscCheck(state != 4, comm, PETSC_ERR_FILE_WRITE, "Option -output_dir = %s with -output_overwrite: cannot remove the earlier output %s", buf, why.c_str());
  PetscCheck(state != 1, comm, PETSC_ERR_FILE_OPEN, "Option -output_dir = %s: cannot create the directory", buf);
  PetscCheck(state != 2, comm, PETSC_ERR_FILE_OPEN,
             "Option -output_dir = %s: the directory is not empty (%s); -output_overwrite replaces turgor's outputs in it, or choose another directory", buf,
             found.size() > 200 ? (found.substr(0, 200) + ", ...").c_str() : found.c_str());
  if (replace && !found.empty())
    PetscCall(PetscPrintf(comm, "Output directory %s: the outputs of an earlier run are replaced%s%s\n", buf,
                          kept.empty() ? "" : "; other files kept: ", kept.c_str()));
  *dir       = buf;
  *overwrite = replace;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void OutputFile::Fail(const char *what)
{
  if (error_.empty()) error_ = std::string("cannot ") + what + " " + path_ + ": " + std::strerror(errno);
}

void OutputFile::Open(const std::string &path, bool in_place)
{
  Abandon();
  path_     = path;
  in_place_ = in_place;
  error_.clear();
  if (in_place) {
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT, 0644);
    fp_          = fd >= 0 ? fdopen(fd, "w") : nullptr; /* "w" on a descriptor: nothing is truncated */
    if (fd >= 0 && !fp_) (void)close(fd);
  } else fp_ = std::fopen(path.c_str(), "w");
  if (!fp_) Fail("create");
}

void OutputFile::Write(const std::string &text)
{
  if (!fp_ || !error_.empty()) return;
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), fp_) != text.size()) Fail("write");
}

void OutputFile::Flush()
{
  if (!fp_ || !error_.empty()) return;
  if (std::fflush(fp_) != 0) Fail("write");
}

void OutputFile::Close()
{
  if (!fp_) return;
  Flush();
  if (in_place_ && error_.empty()) {
    const long end = std::ftell(fp_);
    if (end < 0 || ftruncate(fileno(fp_), (off_t)end) != 0) Fail("write");
  }
  if (std::fclose(fp_) != 0) Fail("close");
  fp_ = nullptr;
}

void OutputFile::Abandon()
{
  if (fp_) (void)std::fclose(fp_);
  fp_ = nullptr;
}

PetscErrorCode CheckOutputError(MPI_Comm comm, const std::string &error)
{
  std::string e = error;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size > 1) PetscCall(BroadcastString(comm, &e));
  PetscCheck(e.empty(), comm, PETSC_ERR_FILE_WRITE, "Output: %s", e.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Open(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  Abandon();
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  comm_ = comm;
  ncol_ = columns.size();
  rows_ = 0;
  if (rank != 0) PetscFunctionReturn(PETSC_SUCCESS);
  std::string header;
  for (const std::string &c : columns) header += (header.empty() ? "" : ",") + c;
  file_.Open(path);
  file_.Write(header + "\n");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Row(const std::vector<PetscReal> &values)
{
  PetscFunctionBeginUser;
  PetscCheck(values.size() == ncol_, comm_, PETSC_ERR_ARG_SIZ, "CSV row has %zu values for %zu columns", values.size(), ncol_);
  std::string line;
  char        num[32];
  for (size_t k = 0; k < values.size(); k++) {
    std::snprintf(num, sizeof num, "%.17g", (double)values[k]);
    line += (k ? "," : "") + std::string(num);
  }
  file_.Write(line + "\n");
  rows_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::RowText(const std::vector<std::string> &cells)
{
  PetscFunctionBeginUser;
  PetscCheck(cells.size() == ncol_, comm_, PETSC_ERR_ARG_SIZ, "CSV row has %zu cells for %zu columns", cells.size(), ncol_);
  std::string line;
  for (size_t k = 0; k < cells.size(); k++) line += (k ? "," : "") + cells[k];
  file_.Write(line + "\n");
  rows_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Close()
{
  PetscFunctionBeginUser;
  if (comm_ == MPI_COMM_NULL) PetscFunctionReturn(PETSC_SUCCESS);
  const MPI_Comm comm = comm_;
  Finish();
  PetscCall(CheckOutputError(comm, file_.Error()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void CsvWriter::Finish()
{
  file_.Close();
  comm_ = MPI_COMM_NULL;
}

void CsvWriter::Abandon()
{
  file_.Abandon();
  comm_ = MPI_COMM_NULL;
}

PetscErrorCode CsvWriter::Contents(std::string *text)
{
  PetscFunctionBeginUser;
  text->clear();
  if (comm_ == MPI_COMM_NULL || !file_.IsOpen()) PetscFunctionReturn(PETSC_SUCCESS);
  file_.Flush();
  if (!file_.Error().empty()) PetscFunctionReturn(PETSC_SUCCESS);
  std::ifstream in(file_.Path(), std::ios::binary);
  PetscCheck(in, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "Cannot read back %s", file_.Path().c_str());
  text->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Restore(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns, const std::string &text)
{
  std::string header;
  PetscFunctionBeginUser;
  for (const std::string &c : columns) header += (header.empty() ? "" : ",") + c;
  PetscCheck(text.compare(0, header.size() + 1, header + "\n") == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's %s has other columns than this run's (another scene?)", path.c_str());
  Abandon();
  comm_ = comm;
  ncol_ = columns.size();
  file_.Open(path);
  file_.Write(text);
  rows_ = (PetscInt)std::count(text.begin(), text.end(), '\n') - 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BroadcastString(MPI_Comm comm, std::string *s)
{
  int n = (int)s->size();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, 0, comm));
  std::vector<char> buf(s->begin(), s->end());
  buf.resize(n);
  PetscCallMPI(MPI_Bcast(buf.data(), n, MPI_CHAR, 0, comm));
  s->assign(buf.begin(), buf.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string JsonQuote(const std::string &s)
{
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if ((unsigned char)c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else out += c;
  }
  return out + "\"";
}

static std::string JsonNumber(PetscReal v)
{
  if (!std::isfinite(v)) return "null"; /* JSON has no NaN/Inf */
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", (double)v);
  return buf;
}

void JsonObject::SetRaw(const std::string &key, const std::string &json)
{
  for (auto &kv : items_)
    if (kv.first == key) {
      kv.second = json;
      return;
    }
  items_.emplace_back(key, json);
}
void JsonObject::Set(const std::string &key, const std::string &value)
{
  SetRaw(key, JsonQuote(value));
}
void JsonObject::Set(const std::string &key, PetscReal value)
{
  SetRaw(key, JsonNumber(value));
}
void JsonObject::Set(const std::string &key, PetscInt value)
{
  SetRaw(key, std::to_string(value));
}
void JsonObject::Set(const std::string &key, bool value)
{
  SetRaw(key, value ? "true" : "false");
}
void JsonObject::Set(const std::string &key, const std::vector<std::string> &values)
{
  std::string a = "[";
  for (size_t k = 0; k < values.size(); k++) a += (k ? ", " : "") + JsonQuote(values[k]);
  SetRaw(key, a + "]");
}
void JsonObject::Set(const std::string &key, const std::vector<PetscReal> &values)
{
  std::string a = "[";
  for (size_t k = 0; k < values.size(); k++) a += (k ? ", " : "") + JsonNumber(values[k]);
  SetRaw(key, a + "]");
}

std::string JsonObject::Str(int indent) const
{
  const std::string pad(indent, ' ');
  std::string       s = "{\n";
  for (size_t k = 0; k < items_.size(); k++) s += pad + JsonQuote(items_[k].first) + ": " + items_[k].second + (k + 1 < items_.size() ? ",\n" : "\n");
  return s + "}";
}

PetscErrorCode JsonObject::Write(MPI_Comm comm, const std::string &path) const
{
  PetscMPIInt rank;
  OutputFile  f;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    f.Open(path, true);
    f.Write(Str() + "\n");
    f.Close();
  }
  PetscCall(CheckOutputError(comm, f.Error()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReserveSummary(MPI_Comm comm, const std::string &path, const std::string &mode)
{
  JsonObject js;
  PetscFunctionBeginUser;
  js.Set("mode", mode);
  js.Set("status", "running");
  js.Set("reason", "the run has not ended: if it is not running any more, it was killed (SIGKILL, out of memory, a lost node) before it could say why");
  std::string text = js.Str() + "\n";
  text.resize(std::max(text.size(), kSummaryReserve), ' '); /* JSON allows trailing white space */
  PetscMPIInt rank;
  OutputFile  f;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    f.Open(path);
    f.Write(text);
    f.Close();
  }
  PetscCall(CheckOutputError(comm, f.Error()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
