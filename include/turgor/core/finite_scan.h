#pragma once
/* Whether every value of an array is finite, by a scan without branches. A double is infinite or NaN
   exactly when its exponent bits are all ones: (bits & E) + 2^52, with E the exponent's mask, then
   carries into the sign bit, and an OR of those over the array keeps it. Integer operations the
   compiler vectorises (a floating-point sum, 0 x u, it may not reorder: one such chain of dependent
   additions costs about four cycles a value, most of a small tissue's step beyond its forces). */
#include <petscsys.h>

namespace turgor {

bool AllFinite(const PetscScalar *u, PetscInt n);

} // namespace turgor
