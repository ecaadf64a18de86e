#include <turgor/core/errors.h>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace turgor {

namespace {

/* The option(s) whose value is `value`, as "-name" (PetscOptionsGetAll gives "-a 1 -b abc ..."). */
std::string OptionsWithValue(const std::string &value)
{
  char       *all = nullptr;
  std::string names;
  if (PetscOptionsGetAll(NULL, &all) || !all) return names;
  std::string prev, tok;
  for (const char *c = all;; c++) {
    if (*c == ' ' || *c == '\0') {
      if (!tok.empty()) {
        if (tok == value && prev.size() > 1 && prev[0] == '-') names += (names.empty() ? "" : ", ") + prev;
        prev = tok;
        tok.clear();
      }
      if (*c == '\0') break;
    } else tok += *c;
  }
  (void)PetscFree(all); /* in an error handler: nothing more can be reported */
  return names;
}

PetscErrorCode ErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  static const char *const patterns[][2] = {
    {"Input string ",           " has no"}, /* PetscOptionsStringToReal/Int */
    {"Unknown logical value: ", nullptr  }, /* PetscOptionsStringToBool */
  };
  std::string better;
  if (p == PETSC_ERROR_INITIAL && mess) {
    for (const auto &pat : patterns) {
      const size_t lead = std::strlen(pat[0]);
      if (std::strncmp(mess, pat[0], lead) != 0) continue;
      const char       *end   = pat[1] ? std::strstr(mess + lead, pat[1]) : nullptr;
      const std::string value = end ? std::string(mess + lead, end) : std::string(mess + lead);
      const std::string names = OptionsWithValue(value);
      if (names.empty()) break;
      better = "Option " + names + " = " + value + ": not a valid value (" + mess + ")";
      break;
    }
  }
  const char *text = better.empty() ? mess : better.c_str();
  PetscMPIInt size = 1, rank = 0;
  if (comm != PETSC_COMM_SELF && comm != MPI_COMM_NULL) {
    (void)MPI_Comm_size(comm, &size);
    (void)MPI_Comm_rank(comm, &rank);
  }
  ErrorRecord *record = (ErrorRecord *)ctx;
  if (size > 1 && rank > 0) { /* the first rank prints; PETSc's handler would sleep 10 s and exit here */
    if (record && p == PETSC_ERROR_INITIAL) {
      if (!record->have)
        record->message = std::string(text ? text : "") + " (" + (fun ? fun : "?") + "() at " + (file ? file : "?") + ":" + std::to_string(line) + ")";
      record->have = record->quiet = true;
    }
    return n;
  }
  /* the callers' frames of an error kept quiet (PetscCall passes them on PETSC_COMM_SELF) */
  if (record && record->quiet && p == PETSC_ERROR_REPEAT) return n;
  if (record && p == PETSC_ERROR_INITIAL) record->quiet = false;
  return PetscTraceBackErrorHandler(comm, line, fun, file, n, p, text, ctx);
}

volatile std::sig_atomic_t interrupted = 0; /* signals received; written by the signal handler only */

extern "C" void OnInterrupt(int)
{
  if (interrupted < 2) interrupted = interrupted + 1;
}

/* SIGINT and SIGTERM to OnInterrupt, restarting the system calls they interrupt or not */
void SetInterruptHandler(bool restart)
{
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = OnInterrupt;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = restart ? SA_RESTART : 0;
  (void)sigaction(SIGINT, &sa, nullptr);
  (void)sigaction(SIGTERM, &sa, nullptr);
}

} // namespace

PetscErrorCode FirstMessage(MPI_Comm comm, const std::string &mine, std::string *first)
{
  PetscMPIInt rank, size, root;
  int         n;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  root = mine.empty() ? size : rank;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &root, 1, MPI_INT, MPI_MIN, comm));
  first->clear();
  if (root == size) PetscFunctionReturn(PETSC_SUCCESS);
  n = rank == root ? (int)mine.size() : 0;
  PetscCallMPI(MPI_Bcast(&n, 1, MPI_INT, root, comm));
  std::vector<char> buf(mine.begin(), mine.end());
  buf.resize(n);
  PetscCallMPI(MPI_Bcast(buf.data(), n, MPI_CHAR, root, comm));
  first->assign(buf.begin(), buf.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PushErrorHandler(ErrorRecord *record)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(ErrorHandler, record));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FinishRanks(MPI_Comm comm, int status, const ErrorRecord &record, double timeout)
{
  PetscMPIInt size, rank, done = 0;
  MPI_Request req;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Ibarrier(comm, &req));
  if (!status) { /* a rank that completed waits for the others however long they take */
    PetscCallMPI(MPI_Wait(&req, MPI_STATUS_IGNORE));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  const double start = MPI_Wtime();
  while (!done && MPI_Wtime() - start < timeout) {
    PetscCallMPI(MPI_Test(&req, &done, MPI_STATUS_IGNORE));
    if (!done) PetscCall(PetscSleep(0.01));
  }
  if (done) PetscFunctionReturn(PETSC_SUCCESS);
  /* the others are stuck in a collective call this rank left: say why, and end the job */
  if (record.have) (void)fprintf(stderr, "[%d]turgor ERROR: %s\n", (int)rank, record.message.c_str());
  (void)fprintf(stderr, "[%d]turgor ERROR: this rank failed and the other ranks did not finish within %g s: aborting\n", (int)rank, timeout);
  (void)fflush(stderr);
  PetscCallMPI(MPI_Abort(comm, status));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode InstallInterruptHandler(void)
{
  PetscFunctionBeginUser;
  SetInterruptHandler(true);
  /* beyond a file size limit (ulimit -f) a write then fails with EFBIG, and the run reports it */
  std::signal(SIGXFSZ, SIG_IGN);
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool InterruptRequested(void)
{
  return interrupted != 0;
}

PetscErrorCode CheckStopNow(void)
{
  PetscFunctionBeginUser;
  PetscCheck(interrupted < 2, PETSC_COMM_SELF, PETSC_ERR_SIG,
             "Interrupted twice (SIGINT/SIGTERM): stopped inside a step; the outputs end at the last sample before it");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode InterruptRequestedAll(MPI_Comm comm, PetscBool *all)
{
  int         mine = interrupted ? 1 : 0, any;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1) any = mine;
  else PetscCallMPI(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm));
  *all = any ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode StopIfInterrupted(MPI_Comm comm, const char during[])
{
  PetscBool stop;
  PetscFunctionBeginUser;
  PetscCall(InterruptRequestedAll(comm, &stop));
  PetscCheck(!stop, comm, PETSC_ERR_SIG, "Interrupted (SIGINT/SIGTERM) during %s", during);
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool IsInterruptError(PetscErrorCode ierr)
{
  return ierr == PETSC_ERR_SIG && interrupted != 0;
}

InterruptibleCalls::InterruptibleCalls()
{
  SetInterruptHandler(false);
}

InterruptibleCalls::~InterruptibleCalls()
{
  SetInterruptHandler(true);
}

} // namespace turgor
