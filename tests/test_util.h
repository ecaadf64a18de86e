#pragma once
/* Minimal checks for turgor's test programs: each test is a PETSc program that prints what it
   measured and returns non-zero (through PETSc's error handling) when a check fails. */
#include <turgor/turgor.hpp>
#include <cmath>
#include <string>

#define TG_CHECK(cond, ...) \
  do { \
    if (!(cond)) SETERRQ(PETSC_COMM_SELF, PETSC_ERR_PLIB, "CHECK FAILED (" #cond "): " __VA_ARGS__); \
  } while (0)

/* |a - b| <= tol * max(|b|, floor) */
#define TG_CHECK_CLOSE(a, b, tol, floor_, what) \
  do { \
    const double _a = (double)(a), _b = (double)(b), _s = std::fmax(std::fabs(_b), (double)(floor_)); \
    if (!(std::fabs(_a - _b) <= (tol)*_s)) \
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_PLIB, "CHECK FAILED: %s: %.10g vs %.10g (relative difference %.3g > %.3g)", what, _a, _b, std::fabs(_a - _b) / _s, \
              (double)(tol)); \
  } while (0)

namespace turgor_test {

/* Deterministic pseudo-random numbers in [-1, 1) (a test must not depend on the platform's rand). */
struct Random {
  unsigned long long s;
  explicit Random(unsigned long long seed) : s(seed * 6364136223846793005ULL + 1442695040888963407ULL) { }
  double operator()()
  {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((s >> 11) * (1.0 / 9007199254740992.0)) * 2.0 - 1.0;
  }
};

/* Push an error handler that keeps the first error's message in *msg and returns the error (no
   printout): a test that expects a refusal checks what it said. Pop it with PetscPopErrorHandler. */
inline PetscErrorCode PushMessageCatcher(std::string *msg)
{
  return PetscPushErrorHandler(
    [](MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType, const char *mess, void *ctx) -> PetscErrorCode {
      std::string *m = (std::string *)ctx;
      if (m->empty() && mess) *m = mess;
      return n;
    },
    msg);
}

} // namespace turgor_test
