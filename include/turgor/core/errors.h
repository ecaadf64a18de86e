#pragma once
/* Turning every failure into a clear PETSc error, and stopping cleanly.

   - CatchExceptions(): around the C entry points and the functions PETSc calls back (TS, SNES,
     PC, DM callbacks): std::bad_alloc and any other C++ exception become a PETSc error with a
     message instead of unwinding through PETSc's C frames.
   - PushErrorHandler(): PETSc's message for an option value that does not parse ("Input string abc
     has no numeric value") does not say which option; this error handler names it. On a rank other
     than the first of a parallel communicator PETSc 3.18's own handler sleeps 10 s and exits
     (status 0, without MPI_Finalize) so that the first rank can print; this one lets the error
     return instead, keeping its message, and FinishRanks() ends the run on every rank at once.
   - Interrupts: SIGINT/SIGTERM set a flag. A time-dependent run checks it after every step, so it
     stops after the step, writes summary.json with status "interrupted" and exits with 130. A
     second signal stops inside the step (CheckStopNow() in the right-hand sides). Set-up checks it
     in its long loops and readers (StopIfInterrupted): a run interrupted there stops before its
     first step. An error raised for an interrupt (IsInterruptError) ends the run "interrupted",
     never "failed". A file size limit (SIGXFSZ) makes the write fail, reported, instead of
     killing the run. */
#include <turgor/core/petsc_compat.h>
#include <exception>
#include <new>
#include <string>

namespace turgor {

/* body() (a callable returning PetscErrorCode), or the PETSc error that an exception escaping it
   becomes, raised at func/line/file: PETSC_ERR_MEM for std::bad_alloc, PETSC_ERR_LIB with what()
   for another std::exception, PETSC_ERR_LIB for anything else. */
template <class Body>
PetscErrorCode CatchExceptions(const char func[], int line, const char file[], Body &&body)
{
#if defined(PETSC_USE_DEBUG)
  /* an exception skips the PetscFunctionReturn()s between it and here: drop their stack frames */
  const int stack_depth = petscstack.currentsize;
  #define TurgorRestoreStack() (void)(petscstack.currentsize = stack_depth)
#else
  #define TurgorRestoreStack() (void)0
#endif
  try {
    return body();
  } catch (const std::bad_alloc &) {
    TurgorRestoreStack();
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_MEM, PETSC_ERROR_INITIAL,
                      "%s(): out of memory (C++ std::bad_alloc): see the memory estimate printed at start", func);
  } catch (const std::exception &e) {
    TurgorRestoreStack();
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_LIB, PETSC_ERROR_INITIAL, "%s(): C++ exception: %s", func, e.what());
  } catch (...) {
    TurgorRestoreStack();
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_LIB, PETSC_ERROR_INITIAL, "%s(): unknown C++ exception", func);
  }
#undef TurgorRestoreStack
}

/* The body of a function PETSc calls (a callback) or a C entry point, guarded by CatchExceptions. */
#define TURGOR_GUARDED(...) turgor::CatchExceptions(PETSC_FUNCTION_NAME, __LINE__, __FILE__, [&]() -> PetscErrorCode __VA_ARGS__)

/* The non-empty `mine` of the lowest rank that has one, on every rank ("" if none): a problem
   found on one rank, reported by a collective error on all. */
PetscErrorCode FirstMessage(MPI_Comm comm, const std::string &mine, std::string *first);

/* The first error a rank met on a parallel communicator where it is not the first rank (the
   first rank prints it); printed by FinishRanks() only if the other ranks do not finish. */
struct ErrorRecord {
  bool        have  = false; /* a message is kept */
  bool        quiet = false; /* the error being passed up is one kept quiet: its callers' frames too */
  std::string message;
};
/* Push turgor's error handler; `record` (owned by the caller, alive until PetscFinalize) keeps the
   messages other ranks would otherwise print. */
PetscErrorCode PushErrorHandler(ErrorRecord *record);
/* Collective on comm, at the end of main: every rank waits for the others. A rank that failed
   (status != 0) waits at most `timeout` seconds: a failure met by one rank only leaves the others
   in a collective call, and then this rank prints its message and aborts the job (MPI_Abort)
   instead of hanging. */
PetscErrorCode FinishRanks(MPI_Comm comm, int status, const ErrorRecord &record, double timeout);
/* Install the SIGINT/SIGTERM handler (after PetscInitialize); SIGXFSZ is ignored. */
PetscErrorCode InstallInterruptHandler(void);
/* True once SIGINT or SIGTERM arrived on this rank. */
bool InterruptRequested(void);
/* An error (PETSC_ERR_SIG) once a second SIGINT/SIGTERM arrived on this rank; right-hand sides call
   it, so that a step that takes too long (an adaptive integrator rejecting again and again) ends. */
PetscErrorCode CheckStopNow(void);
/* Collective: true on every rank if it is true on one. */
PetscErrorCode InterruptRequestedAll(MPI_Comm comm, PetscBool *interrupted);
/* Collective: an error (PETSC_ERR_SIG) on every rank if SIGINT/SIGTERM arrived on one, saying that
   the run stopped `during` (e.g. "set-up: the Voronoi tissue's Lloyd step 3"). */
PetscErrorCode StopIfInterrupted(MPI_Comm comm, const char during[]);
/* The error ierr was raised because of SIGINT/SIGTERM (StopIfInterrupted, CheckStopNow, a reader
   that stopped): the run ends "interrupted" (exit status 130). */
bool IsInterruptError(PetscErrorCode ierr);

/* While one exists, SIGINT/SIGTERM make a blocking open() or read() fail (EINTR) instead of
   restarting it: a reader of a user's file (a FIFO without a writer) then sees the failure and
   checks InterruptRequested(). Elsewhere system calls restart, as the libraries expect. */
class InterruptibleCalls {
public:
  InterruptibleCalls();
  ~InterruptibleCalls();
  InterruptibleCalls(const InterruptibleCalls &)            = delete;
  InterruptibleCalls &operator=(const InterruptibleCalls &) = delete;
};

} // namespace turgor
