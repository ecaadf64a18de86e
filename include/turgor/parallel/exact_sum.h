#pragma once
/* A sum over the ranks whose bits do not depend on the number of ranks or the order of its terms
   (the outputs of a run with -fine_reproducible_sums: the kinetic energy of tip.csv).

   Every term t is split into a high part, t rounded to a multiple of a power of two q1, and a low
   part, the rest rounded to a multiple of q2; q1 and q2 are chosen from the largest |t| (< 2^e) and
   the number of terms (N < 2^k) so that every partial sum of either part is a multiple of its grain
   below 2^53 times it, hence exact in any order (q1 = 2^(e+k-52), q2 = 2^(e+2k-104)). The result,
   the two exact sums added once, is within N q2 / 2 = 2^(e+3k-105) (2^-66 of the largest term for
   5 000 terms, 2^-33 of it for 10^7) and the last addition's half ulp of the exact sum. Two reductions (the largest term and the
   count, then the two sums) and two passes over the terms. */
#include <turgor/parallel/rank_reductions.h>
#include <cmath>

namespace turgor {

template <class Term>
PetscErrorCode ExactSumOverRanks(MPI_Comm comm, PetscInt n, const Term &term, PetscReal *sum)
{
  PetscReal m[2] = {0, (PetscReal)n}; /* the largest |term|, the number of terms (exact in a double) */
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) m[0] = std::max(m[0], std::fabs(term(i)));
  PetscCall(SumOverRanks(comm, &m[1]));
  PetscCall(MaxOverRanks(comm, &m[0]));
  PetscReal s[2] = {0, 0};
  if (!(m[0] > 0) || !std::isfinite(m[0])) { /* all zero, or a NaN or infinity that the sum must show */
    for (PetscInt i = 0; i < n; i++) s[0] += term(i);
  } else {
    int e, k;
    (void)std::frexp(m[0], &e);                                                                    /* every |term| < 2^e */
    (void)std::frexp(m[1], &k);                                                                    /* N < 2^k */
    const PetscReal c1 = 1.5 * std::ldexp(1.0, e + k), c2 = 1.5 * std::ldexp(1.0, e + 2 * k - 52); /* 1.5 2^52 q */
    for (PetscInt i = 0; i < n; i++) {
      const PetscReal t = term(i), hi = (t + c1) - c1;
      s[0] += hi;
      s[1] += ((t - hi) + c2) - c2; /* t - hi is exact: |t - hi| <= q1/2, a multiple of t's spacing */
    }
  }
  PetscCall(SumOverRanks(comm, s, 2));
  *sum = s[0] + s[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
