#pragma once
/* a where the mask m is all ones, b where it is zero: an exact select (no floating-point operation,
   so -0 and NaN pass unchanged) in integer operations, which the compiler vectorises where it keeps
   a conditional floating-point sum as a branch. */
#include <petscsys.h>
#include <cstdint>
#include <cstring>

namespace turgor {

inline PetscReal MaskSelect(std::uint64_t m, PetscReal a, PetscReal b)
{
  std::uint64_t x, y;
  std::memcpy(&x, &a, sizeof x), std::memcpy(&y, &b, sizeof y);
  x = (x & m) | (y & ~m);
  std::memcpy(&a, &x, sizeof x);
  return a;
}

} // namespace turgor
