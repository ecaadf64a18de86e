#include <turgor/io/output.h>
#include <cmath>
#include <filesystem>
#include <system_error>

namespace turgor {

PetscErrorCode OutputDirectory(MPI_Comm comm, std::string *dir)
{
  char        buf[PETSC_MAX_PATH_LEN];
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(buf, dir->empty() ? "./out" : dir->c_str(), sizeof buf));
  PetscOptionsBegin(comm, NULL, "Output", "turgor");
  PetscCall(PetscOptionsString("-output_dir", "Directory for all outputs of the run", "turgor", buf, buf, sizeof buf, NULL));
  PetscOptionsEnd();
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    std::error_code ec;
    std::filesystem::create_directories(buf, ec);
    err = ec ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Option -output_dir = %s: cannot create the directory", buf);
  *dir = buf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CsvWriter::Open(MPI_Comm comm, const std::string &path, const std::vector<std::string> &columns)
{
  PetscFunctionBeginUser;
  PetscCall(Close());
  comm_ = comm;
  ncol_ = columns.size();
  PetscCall(PetscFOpen(comm, path.c_str(), "w", &fp_));
  std::string header;
  for (const std::string &c : columns) header += (header.empty() ? "" : ",") + c;
  PetscCall(PetscFPrintf(comm, fp_, "%s\n", header.c_str()));
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
