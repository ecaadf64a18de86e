#include <turgor/core/memory.h>
#include <sys/resource.h>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unistd.h>

namespace turgor {

/* Bytes the kernel says a new allocation may still get on this node without swapping. */
static PetscReal AvailableBytes()
{
  FILE     *fp = std::fopen("/proc/meminfo", "r");
  char      line[256];
  long long kb = -1;
  if (fp) {
    while (std::fgets(line, sizeof line, fp))
      if (std::sscanf(line, "MemAvailable: %lld kB", &kb) == 1) break;
    std::fclose(fp);
  }
  if (kb > 0) return 1024.0 * (PetscReal)kb;
  return (PetscReal)sysconf(_SC_PHYS_PAGES) * (PetscReal)sysconf(_SC_PAGESIZE);
}

std::string FormatBytes(PetscReal b)
{
  char        buf[64];
  const char *unit[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int         u      = 0;
  while (b >= 1024 && u < 5) {
    b /= 1024;
    u++;
  }
  std::snprintf(buf, sizeof buf, "%.3g %s", (double)b, unit[u]);
  return buf;
}

PetscErrorCode CheckCount(MPI_Comm comm, PetscReal count, const std::string &what)
{
  PetscFunctionBeginUser;
  PetscCheck(std::isfinite(count) && count <= (PetscReal)PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%s: %.3g is more than this build's PetscInt can count (%d)", what.c_str(), (double)count, PETSC_MAX_INT);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CheckMemory(MPI_Comm comm, PetscReal bytes, const std::string &what)
{
  MPI_Comm    node;
  PetscMPIInt rank, noderank;
  PetscReal   node_bytes = 0, avail = 0, worst[2];
  PetscBool   check = PETSC_TRUE;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Memory", "turgor");
  PetscCall(PetscOptionsBool("-memory_check", "Refuse a run whose memory estimate exceeds the node's available memory (false: warn only)", "CheckMemory", check,
                             &check, NULL));
  PetscOptionsEnd();
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &noderank));
  PetscCallMPI(MPI_Allreduce(&bytes, &node_bytes, 1, MPIU_REAL, MPIU_SUM, node));
  if (noderank == 0) avail = AvailableBytes();
  PetscCallMPI(MPI_Bcast(&avail, 1, MPIU_REAL, 0, node));
  PetscCallMPI(MPI_Comm_free(&node));
  worst[0] = node_bytes / avail; /* the fullest node decides */
  worst[1] = node_bytes;
  {
    PetscReal in[2] = {worst[0], worst[1]};
    PetscCallMPI(MPI_Allreduce(in, worst, 2, MPIU_REAL, MPIU_MAX, comm));
  }
  const std::string need = FormatBytes(worst[1]), have = FormatBytes(worst[1] / worst[0]);
  PetscCall(PetscPrintf(comm, "Memory estimate: %s for %s (on the fullest node, %s available)\n", need.c_str(), what.c_str(), have.c_str()));
  if (!(worst[0] <= 1)) {
    PetscCheck(!check, comm, PETSC_ERR_ARG_OUTOFRANGE, /* a refusal, not an allocation that failed */
               "%s needs about %s of memory, more than the %s this node has available: make the problem smaller or use more nodes (-memory_check false to try "
               "anyway)",
               what.c_str(), need.c_str(), have.c_str());
    PetscCall(PetscPrintf(comm, "WARNING: the estimate exceeds the available memory (-memory_check false)\n"));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor

namespace turgor {

PetscReal PeakResidentBytes()
{
  struct rusage u;
  if (getrusage(RUSAGE_SELF, &u) != 0) return 0;
  return 1024.0 * (PetscReal)u.ru_maxrss; /* kilobytes on Linux */
}

} // namespace turgor
