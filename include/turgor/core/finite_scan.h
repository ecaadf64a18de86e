#pragma once
/* Whether every value of an array is finite, by a scan without branches. A double is infinite or NaN
   exactly when its exponent bits are all ones: (bits & E) + 2^52, with E the exponent's mask, then
   carries into the sign bit, and an OR of those over the array keeps it. Integer operations the
   compiler vectorises (a floating-point sum, 0 x u, it may not reorder: one such chain of dependent
   additions costs about four cycles a value, most of a small tissue's step beyond its forces). */
#include <petscsys.h>
#include <cstdint>
#include <cstring>

namespace turgor {

bool AllFinite(const PetscScalar *u, PetscInt n);

/* One value's carry, for a loop that checks the values it writes: OR them, then CarriesFinite. */
inline std::uint64_t ExponentCarry(PetscScalar u)
{
  static_assert(sizeof(PetscScalar) == sizeof(std::uint64_t), "ExponentCarry reads a real double's bits");
  std::uint64_t b;
  std::memcpy(&b, &u, sizeof b);
  return (b & 0x7ff0000000000000ull) + 0x0010000000000000ull;
}
inline bool CarriesFinite(std::uint64_t carries)
{
  return (carries >> 63) == 0;
}

} // namespace turgor
