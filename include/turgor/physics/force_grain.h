#pragma once
/* Force sums whose bits do not depend on the order of their terms (-fine_reproducible_sums).

   A particle's force is a sum of interaction shares that a distributed run adds in another order
   than a serial one (each rank its own interactions, then the halo's shares returned by its
   neighbours), so its last bits depend on the number of ranks. With a grain, every share is
   rounded to a multiple of one power of two q before it is added: a sum of such multiples is exact
   while it stays below 2^53 q, so it is the same in any order, on any number of ranks. The grain is
   chosen from the largest share of the evaluation itself (FineEquations: q = 2^-43 of the next
   power of two above it, which leaves room for 1024 shares of that size in one sum) and the
   evaluation is repeated when it was made with another grain; so the grain, like the forces, is a
   function of the state alone, and a restart on any number of ranks continues the same bits.
   The rounding costs about 13 of double's 53 bits of the largest share (2.3e-13 of it), an error
   far below any integrator's. Off (the default), every share passes unchanged. */
#include <petscsys.h>
#include <algorithm>
#include <cmath>

namespace turgor {

class ForceGrain {
public:
  /* off */
  void Clear() { c_ = 0, q_ = 0; }
  /* the grain for shares of at most `largest` in magnitude (> 0) */
  void SetFor(PetscReal largest)
  {
    int e;
    (void)std::frexp(largest, &e); /* largest < 2^e */
    q_ = std::ldexp(1.0, e - 43);
    c_ = 1.5 * std::ldexp(1.0, e + 9); /* x + c_ lies in [2^(e+9), 2^(e+10)), whose spacing is q_ */
  }
  /* would SetFor(largest) choose this grain? (no shares, or only zeros: any grain, or none, adds
     the same zeros) */
  bool Fits(PetscReal largest) const
  {
    if (largest == 0) return true;
    ForceGrain g;
    g.SetFor(largest);
    return g.q_ == q_;
  }
  bool      On() const { return c_ != 0; }
  PetscReal Quantum() const { return q_; }
  /* the largest |share| rounded since the last ResetLargest */
  PetscReal Largest() const { return largest_; }
  void      ResetLargest() { largest_ = 0; }

  /* a share, rounded to the grain (unchanged when off) */
  PetscReal operator()(PetscReal x) const
  {
    if (!c_) return x;
    largest_ = std::max(largest_, std::fabs(x));
    return (x + c_) - c_;
  }
  /* both components of a share */
  void operator()(PetscReal &x, PetscReal &y) const
  {
    if (!c_) return;
    largest_ = std::max(largest_, std::max(std::fabs(x), std::fabs(y)));
    x        = (x + c_) - c_;
    y        = (y + c_) - c_;
  }

  /* the grain that rounds nothing (inputs made without a model's grain) */
  static const ForceGrain &Off()
  {
    static const ForceGrain off; /* never written: an off grain keeps no largest share */
    return off;
  }

private:
  PetscReal         c_ = 0, q_ = 0;
  mutable PetscReal largest_ = 0; /* a kernel reads the grain through its const input */
};

} // namespace turgor
