#include <turgor/core/finite_scan.h>
#include <turgor/core/vector_clones.h>
#include <cstdint>
#include <cstring>

namespace turgor {

static_assert(sizeof(PetscScalar) == sizeof(std::uint64_t), "AllFinite reads a real double's bits");

namespace {
TURGOR_VECTOR_CLONES std::uint64_t ExponentCarries(const PetscScalar *__restrict u, PetscInt n)
{
  const std::uint64_t E = 0x7ff0000000000000ull, one = 0x0010000000000000ull;
  std::uint64_t       acc = 0;
  for (PetscInt k = 0; k < n; k++) {
    std::uint64_t b;
    std::memcpy(&b, u + k, sizeof b);
    acc |= (b & E) + one;
  }
  return acc;
}
} // namespace

bool AllFinite(const PetscScalar *u, PetscInt n)
{
  return (ExponentCarries(u, n) >> 63) == 0;
}

} // namespace turgor
