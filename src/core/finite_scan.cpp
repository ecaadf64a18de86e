#include <turgor/core/finite_scan.h>
#include <turgor/core/vector_clones.h>

namespace turgor {

namespace {
TURGOR_VECTOR_CLONES std::uint64_t ExponentCarries(const PetscScalar *__restrict u, PetscInt n)
{
  std::uint64_t acc = 0;
  for (PetscInt k = 0; k < n; k++) acc |= ExponentCarry(u[k]);
  return acc;
}
} // namespace

bool AllFinite(const PetscScalar *u, PetscInt n)
{
  return CarriesFinite(ExponentCarries(u, n));
}

} // namespace turgor
