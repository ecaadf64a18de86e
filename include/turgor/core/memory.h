#pragma once
/* Memory estimates before the first large allocation: a run that cannot fit is refused with the
   figure instead of dying of std::bad_alloc (or swapping) minutes later. Estimates are per rank and
   summed over the ranks that share a node, then compared with that node's available memory
   (MemAvailable). -memory_check false turns the refusal into a warning. */
#include <turgor/core/petsc_compat.h>
#include <string>

namespace turgor {

/* Collective on comm. `bytes` is this rank's estimate for `what` ("the fine tissue: 4929 particles").
   Prints the estimate once (rank 0) and errors if it exceeds what the node has. */
PetscErrorCode CheckMemory(MPI_Comm comm, PetscReal bytes, const std::string &what);
/* A count computed in floating point (to detect overflow) that must fit in PetscInt. */
PetscErrorCode CheckCount(MPI_Comm comm, PetscReal count, const std::string &what);
std::string    FormatBytes(PetscReal bytes);
/* This process's peak resident set so far [bytes] (getrusage's ru_maxrss); 0 where unknown. */
PetscReal PeakResidentBytes();

} // namespace turgor
