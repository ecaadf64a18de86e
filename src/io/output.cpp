#include <fstream>
#include <turgor/io/output.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <vector>

namespace turgor {

/* The files turgor writes into an output directory (any mode): the only ones -output_overwrite
   removes. */
static const char *const kOutputFiles[] = {"summary.json", "tip.csv",       "groups.csv",   "rve.csv",    "particles.h5", "particles.xmf",
                                           "coarse.h5",    "coarse.xmf",    "eigen.csv",    "modes.h5",   "modes.xmf",    "stability.csv",
                                           "stability.h5", "stability.xmf", "spectrum.png", "energy.csv", "breaks.csv"};

PetscErrorCode OutputDirectory(MPI_Comm comm, std::string *dir, bool *overwrite, bool *prepared)
{
  char        buf[PETSC_MAX_PATH_LEN];
  PetscBool   replace = *overwrite ? PETSC_TRUE : PETSC_FALSE;
  PetscMPIInt rank;
  /* 0: ready; 1: cannot create; 2: not empty and no -output_overwrite */
  int         state = 0;
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
        bool              own  = false;
        for (const char *o : kOutputFiles) own = own || name == o;
        own = own ||
              (name.rfind("checkpoint", 0) == 0 &&
               ((name.size() > 3 && name.compare(name.size() - 3, 3, ".h5") == 0) || (name.size() > 7 && name.compare(name.size() - 7, 7, ".h5.tmp") == 0))) ||
              name.rfind("particles_restart", 0) == 0 || name.rfind("coarse_restart", 0) == 0; /* checkpoint.h5, checkpoint_<step>.h5, a restart's snapshots */
        if (own) ours.push_back(entry.path());
        else kept += (kept.empty() ? "" : ", ") + name;
        found += (found.empty() ? "" : ", ") + name;
      }
      if (restart) { /* kept: the run continues them */
      } else if (!found.empty() && !replace) state = 2;
      else
        for (const auto &f : ours) fs::remove(f, ec);
    } else {
      fs::create_directories(buf, ec);
      if (ec) state = 1;
    }
  }
  PetscCallMPI(MPI_Bcast(&state, 1, MPI_INT, 0, comm));
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

PetscErrorCode CsvWriter::Open(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns)
{
  PetscFunctionBeginUser;
  PetscCall(Close());
  comm_ = comm;
  path_ = path;
  ncol_ = columns.size();
  PetscCall(PetscFOpen(comm, path.c_str(), "w", &fp_));
  std::string header;
  for (const std::string &c : columns) header += (header.empty() ? "" : ",") + c;
  PetscCall(PetscFPrintf(comm, fp_, "%s\n", header.c_str()));
  rows_ = 0;
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
  PetscCall(PetscFPrintf(comm_, fp_, "%s\n", line.c_str()));
  rows_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::RowText(const std::vector<std::string> &cells)
{
  PetscFunctionBeginUser;
  PetscCheck(cells.size() == ncol_, comm_, PETSC_ERR_ARG_SIZ, "CSV row has %zu cells for %zu columns", cells.size(), ncol_);
  std::string line;
  for (size_t k = 0; k < cells.size(); k++) line += (k ? "," : "") + cells[k];
  PetscCall(PetscFPrintf(comm_, fp_, "%s\n", line.c_str()));
  rows_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Close()
{
  PetscFunctionBeginUser;
  if (comm_ != MPI_COMM_NULL) PetscCall(PetscFClose(comm_, fp_));
  comm_ = MPI_COMM_NULL;
  fp_   = nullptr;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Contents(std::string *text)
{
  PetscFunctionBeginUser;
  text->clear();
  if (comm_ == MPI_COMM_NULL) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(std::fflush(fp_) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write %s (disk full?)", path_.c_str());
  std::ifstream in(path_, std::ios::binary);
  PetscCheck(in, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "Cannot read back %s", path_.c_str());
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
  PetscCall(Close());
  comm_ = comm;
  path_ = path;
  ncol_ = columns.size();
  PetscCall(PetscFOpen(comm, path.c_str(), "w", &fp_));
  PetscCall(PetscFPrintf(comm, fp_, "%s", text.c_str()));
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
  FILE *fp;
  PetscFunctionBeginUser;
  PetscCall(PetscFOpen(comm, path.c_str(), "w", &fp));
  PetscCall(PetscFPrintf(comm, fp, "%s\n", Str().c_str()));
  PetscCall(PetscFClose(comm, fp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
