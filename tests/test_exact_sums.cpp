static const char help[] = "Sums whose bits do not depend on their order or the number of ranks:\n"
                           "  ForceGrain (a force share rounded to a grain): the rounded shares of a particle summed in 20 random\n"
                           "    orders give one result, within N q/2 of the exact sum; the grain is the one SetFor chooses, Fits\n"
                           "    agrees, and the grain of a largest share just below and at a power of two;\n"
                           "  ExactSumOverRanks: terms spread over the ranks (one rank empty) in shuffled orders, against the same\n"
                           "    terms on one rank and a sum in long double, within its bound 2^(e+3k-105) and half an ulp.\n"
                           "  AllFinite (the branch-free finiteness scan): a NaN, +inf or -inf at every place of arrays of 0 to 40\n"
                           "    values (the vector lanes and the remainder) is found, and finite values of any size pass (the largest,\n"
                           "    subnormals, zeros).\n"
                           "Run on 1, 2 and 3 ranks: every rank count must print the same sum, bit for bit.\n";
#include <turgor/core/finite_scan.h>
#include <turgor/parallel/exact_sum.h>
#include <turgor/physics/force_grain.h>
#include <algorithm>
#include <cfloat>
#include <limits>
#include <cinttypes>
#include <cstring>
#include <random>
#include <vector>

using namespace turgor;

static PetscErrorCode CheckGrain()
{
  std::mt19937_64                        rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  PetscFunctionBeginUser;
  /* the shares of one particle: a few large ones that nearly cancel, many small ones */
  std::vector<PetscReal> s;
  for (int k = 0; k < 40; k++) s.push_back(1e3 * u(rng));
  for (int k = 0; k < 400; k++) s.push_back(1e-4 * u(rng));
  PetscReal largest = 0;
  for (PetscReal x : s) largest = std::max(largest, std::fabs(x));
  ForceGrain g;
  g.SetFor(largest);
  PetscCheck(g.On() && g.Fits(largest) && g.Fits(0.75 * largest) == (std::ldexp(1.0, -1) * 2 * largest > 0) && !g.Fits(4 * largest), PETSC_COMM_SELF,
             PETSC_ERR_PLIB, "ForceGrain: Fits disagrees with SetFor");
  int e;
  (void)std::frexp(largest, &e);
  PetscCheck(g.Quantum() == std::ldexp(1.0, e - 43), PETSC_COMM_SELF, PETSC_ERR_PLIB, "ForceGrain: grain %g, expected 2^%d", (double)g.Quantum(), e - 43);
  { /* a power of two is above every share below it: 2^e itself needs the next grain */
    ForceGrain a, b;
    a.SetFor(std::nextafter(1.0, 0.0));
    b.SetFor(1.0);
    PetscCheck(a.Quantum() == std::ldexp(1.0, -43) && b.Quantum() == std::ldexp(1.0, -42), PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "ForceGrain: grains %g and %g around 1", (double)a.Quantum(), (double)b.Quantum());
  }
  std::vector<PetscReal> r(s.size());
  long double            exact = 0;
  for (size_t k = 0; k < s.size(); k++) {
    r[k] = g(s[k]);
    PetscCheck(std::fabs(r[k] - s[k]) <= 0.5 * g.Quantum() && std::fmod(r[k], g.Quantum()) == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "ForceGrain: share %.17g rounded to %.17g, not the nearest multiple of %g", s[k], r[k], (double)g.Quantum());
    exact += (long double)s[k];
  }
  PetscCheck(g.Largest() == largest, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ForceGrain: largest share %g, expected %g", (double)g.Largest(), (double)largest);
  PetscReal first = 0;
  for (int order = 0; order < 20; order++) {
    std::shuffle(r.begin(), r.end(), rng);
    PetscReal sum = 0;
    for (PetscReal x : r) sum += x;
    if (order == 0) first = sum;
    PetscCheck(sum == first, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ForceGrain: order %d sums to %.17g, the first to %.17g", order, sum, first);
  }
  PetscCheck(std::fabs((long double)first - exact) <= 0.5 * s.size() * g.Quantum(), PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "ForceGrain: the sum %.17g is %g from the exact one, more than N q/2", first, (double)std::fabs((long double)first - exact));
  { /* off: every value passes unchanged, and nothing is recorded */
    ForceGrain off;
    PetscCheck(off(s[3]) == s[3] && off.Largest() == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "ForceGrain: an off grain changed a share");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckExactSum(MPI_Comm comm)
{
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCall(RankAndSize(comm, &rank, &size));
  /* the same 5000 terms on every rank count: kinetic-energy-like, over 12 decades */
  const PetscInt         N = 5000;
  std::vector<PetscReal> all(N);
  std::mt19937_64        rng(11);
  for (PetscInt i = 0; i < N; i++) all[i] = std::ldexp(std::uniform_real_distribution<double>(0.5, 1)(rng), (int)(rng() % 40) - 20);
  long double exact = 0;
  for (PetscReal t : all) exact += (long double)t;
  /* this rank's share: ranks 0..size-2 split the terms, the last rank holds none (with 2+ ranks) */
  const PetscMPIInt      holders = size > 1 ? size - 1 : 1;
  const PetscInt         lo = rank < holders ? N * rank / holders : N, hi = rank < holders ? N * (rank + 1) / holders : N;
  std::vector<PetscReal> mine(all.begin() + lo, all.begin() + hi);
  PetscReal              first = 0;
  for (int order = 0; order < 5; order++) {
    std::shuffle(mine.begin(), mine.end(), rng);
    PetscReal sum;
    PetscCall(ExactSumOverRanks(
      comm, (PetscInt)mine.size(), [&mine](PetscInt i) { return mine[i]; }, &sum));
    if (order == 0) first = sum;
    PetscCheck(sum == first, comm, PETSC_ERR_PLIB, "ExactSumOverRanks: order %d gives %.17g, the first %.17g", order, sum, first);
  }
  PetscReal serial;
  PetscCall(ExactSumOverRanks(
    PETSC_COMM_SELF, N, [&all](PetscInt i) { return all[i]; }, &serial));
  int e, k;
  (void)std::frexp(*std::max_element(all.begin(), all.end()), &e);
  (void)std::frexp((double)N, &k);
  PetscCheck(first == serial, comm, PETSC_ERR_PLIB, "ExactSumOverRanks: %.17g on %d ranks, %.17g on one", first, (int)size, serial);
  const long double bound = std::ldexp(1.0, e + 3 * k - 105) + 0.5 * (std::nextafter(first, HUGE_VAL) - first); /* and the result's own rounding */
  PetscCheck(std::fabs((long double)first - exact) <= bound, comm, PETSC_ERR_PLIB, "ExactSumOverRanks: %.17g is %g from the exact sum, above its bound", first,
             (double)std::fabs((long double)first - exact));
  { /* no terms anywhere, and a NaN that must show */
    PetscReal none = 1, bad = 0;
    PetscCall(ExactSumOverRanks(
      comm, 0, [](PetscInt) { return 0.0; }, &none));
    PetscCall(ExactSumOverRanks(
      comm, rank == 0 ? 1 : 0, [](PetscInt) { return std::nan(""); }, &bad));
    PetscCheck(none == 0 && std::isnan(bad), comm, PETSC_ERR_PLIB, "ExactSumOverRanks: empty sum %g, NaN sum %g", (double)none, (double)bad);
  }
  std::uint64_t bits;
  std::memcpy(&bits, &first, sizeof bits);
  PetscCall(PetscPrintf(comm, "exact sum on %d ranks: %.17g (bits %016" PRIx64 "), %g from the long-double sum\n", (int)size, first, bits,
                        (double)std::fabs((long double)first - exact)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckAllFinite()
{
  const PetscReal bad[3] = {NAN, INFINITY, -INFINITY};
  PetscFunctionBeginUser;
  for (PetscInt n = 0; n <= 40; n++) {
    std::vector<PetscReal> u((size_t)n);
    for (PetscInt k = 0; k < n; k++) u[k] = (k % 3 ? -1 : 1) * std::ldexp(1.0 + 0.1 * k, (int)(k * 97 % 2000) - 1000); /* 2^-1000 .. 2^999 */
    const PetscReal edge[4] = {DBL_MAX, -DBL_MAX, -std::numeric_limits<PetscReal>::denorm_min(), -0.0};                /* the largest, a subnormal, a zero */
    for (PetscInt k = 0; k < n && k < 4; k++) u[(size_t)(n - 1 - k)] = edge[k];
    PetscCheck(AllFinite(u.data(), n), PETSC_COMM_SELF, PETSC_ERR_PLIB, "AllFinite: %" PetscInt_FMT " finite values were refused", n);
    for (PetscInt k = 0; k < n; k++)
      for (PetscReal b : bad) {
        const PetscReal keep = u[k];
        u[k]                 = b;
        PetscCheck(!AllFinite(u.data(), n), PETSC_COMM_SELF, PETSC_ERR_PLIB, "AllFinite: %g at place %" PetscInt_FMT " of %" PetscInt_FMT " not found",
                   (double)b, k, n);
        u[k] = keep;
      }
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "AllFinite: every non-finite value found in arrays of 0 to 40 values\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(CheckGrain());
  PetscCall(CheckAllFinite());
  PetscCall(CheckExactSum(PETSC_COMM_WORLD));
  PetscCall(PetscFinalize());
  return 0;
}
