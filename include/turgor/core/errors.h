#pragma once
/* Turning every failure into a clear PETSc error, and stopping cleanly.

   - TURGOR_CATCH: ends a try block in every function PETSc calls back (TS, SNES, PC, DM callbacks)
     and in the C entry points: std::bad_alloc and any other C++ exception become a PETSc error with
     a message instead of unwinding through PETSc's C frames (std::terminate).
   - PushOptionValueErrorHandler(): PETSc's message for an option value that does not parse ("Input
     string abc has no numeric value") does not say which option; this error handler names it.
   - Interrupts: SIGINT/SIGTERM set a flag that a time-dependent run checks at every step, so it
     stops after the step, writes summary.json with status "interrupted" and exits non-zero. */
#include <turgor/core/petsc_compat.h>
#include <new>
#include <stdexcept>

#define TURGOR_CATCH \
  catch (const std::bad_alloc &) \
  { \
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_MEM, "Out of memory (std::bad_alloc): the problem is larger than this machine; see the memory estimate printed at start"); \
  } \
  catch (const std::exception &e) \
  { \
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "C++ exception: %s", e.what()); \
  }

namespace turgor {

PetscErrorCode PushOptionValueErrorHandler(void);
/* Install the SIGINT/SIGTERM handler (after PetscInitialize). */
PetscErrorCode InstallInterruptHandler(void);
/* True once SIGINT or SIGTERM arrived on this rank. */
bool           InterruptRequested(void);
/* Collective: true on every rank if it is true on one. */
PetscErrorCode InterruptRequestedAll(MPI_Comm comm, PetscBool *interrupted);

} // namespace turgor
