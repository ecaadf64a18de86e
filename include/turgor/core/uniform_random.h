#pragma once
/* A seeded uniform random number in [0, 1) from the top 53 bits of a 64-bit Mersenne twister: the
   same numbers on every machine and rank for the same seed (the tissue generators' seeds). */
#include <petscsys.h>
#include <cstdint>
#include <random>

namespace turgor {

struct UniformRandom {
  std::mt19937_64 g;
  explicit UniformRandom(PetscInt seed) : g((std::uint64_t)(long long)seed) { }
  PetscReal operator()() { return (PetscReal)(g() >> 11) * (1.0 / 9007199254740992.0); }
};

} // namespace turgor
