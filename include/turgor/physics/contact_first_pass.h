#pragma once
/* The contact's first pass: which of the near node-bar pairs are closer than 2 r. Most near pairs do
   not touch, so the pass is branch-free and hand-vectorised; the contact's second pass treats the
   few that touch. Every version makes the same comparisons: the test, lane by lane, is the scalar
   formula's operations in its order. */
#include <petscsys.h>
#include <cstddef>
#include <cstdint>

namespace turgor {

/* A near pair's nodes: the pass reads this list in order, 12 bytes a pair (which candidate a pair is,
   the contact keeps beside the list: only the touching pairs need it). */
struct ContactNearPair {
  std::uint32_t p2, a2, b2; /* node, bar ends: their first component's offset in x (2 p: no sign extension per load) */
};

/* The pairs closer than sqrt(R2): |(x_p - x_a)|e|^2 - t e|^2 < R2 |e|^4 with e = x_b - x_a and t =
   clamp((x_p - x_a).e, 0, |e|^2); their indices in near[] listed in touch[] in order (room for n);
   returns how many.
   Two pairs at a time in AVX registers where the CPU has AVX (and the build makes that version). */
size_t ContactTouchingPairs(const ContactNearPair *near, size_t n, const PetscReal *x, PetscReal R2, PetscInt *touch);
/* The same, one pair at a time (SSE2 where the build has it): the version without AVX. */
size_t ContactTouchingPairsOneByOne(const ContactNearPair *near, size_t n, const PetscReal *x, PetscReal R2, PetscInt *touch);

} // namespace turgor
