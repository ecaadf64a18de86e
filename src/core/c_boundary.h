#pragma once
/* The C boundary of turgor's C entry points (<turgor/turgor.h>, for src/ only): C++ code called
   from them returns a C++ exception escaping it as a PETSc error, so that none reaches C code. */
#include <turgor/core/petsc_compat.h>
#include <exception>
#include <new>

namespace turgor {

/* body() (a callable returning PetscErrorCode), or the PETSc error that an exception escaping it
   becomes, raised at func/line/file (the C entry point's): PETSC_ERR_MEM for std::bad_alloc,
   PETSC_ERR_LIB with what() for another std::exception, PETSC_ERR_LIB for anything else. */
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
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_MEM, PETSC_ERROR_INITIAL, "%s(): out of memory (C++ std::bad_alloc)", func);
  } catch (const std::exception &e) {
    TurgorRestoreStack();
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_LIB, PETSC_ERROR_INITIAL, "%s(): C++ exception: %s", func, e.what());
  } catch (...) {
    TurgorRestoreStack();
    return PetscError(PETSC_COMM_SELF, line, func, file, PETSC_ERR_LIB, PETSC_ERROR_INITIAL, "%s(): unknown C++ exception", func);
  }
#undef TurgorRestoreStack
}

} // namespace turgor
