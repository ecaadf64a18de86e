#pragma once
/* Whether every value of an array is finite, by a scan without branches: 0 x a value is NaN for an
   infinite or NaN one, and a NaN stays in a sum. Eight independent sums: one sum is a chain of
   dependent additions (about four cycles each, a 404-value state 0.5 µs: most of a small tissue's
   step beyond its forces), eight run at the adder's throughput; the compiler may not reorder one
   floating-point sum itself. */
#include <petscsys.h>

namespace turgor {

inline bool AllFinite(const PetscScalar *u, PetscInt n)
{
  PetscReal s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  PetscInt  k    = 0;
  for (; k + 8 <= n; k += 8)
    for (int j = 0; j < 8; j++) s[j] += 0 * PetscRealPart(u[k + j]);
  for (; k < n; k++) s[0] += 0 * PetscRealPart(u[k]);
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7])) == 0;
}

} // namespace turgor
