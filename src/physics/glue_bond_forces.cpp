#include <turgor/core/vector_clones.h>
#include <turgor/physics/glue_bond_forces.h>
#include <algorithm>
#include <cmath>
#include <type_traits>

/* Compiled with -fno-math-errno and -fno-trapping-math (CMakeLists.txt): sqrt's errno branch, and
   the marks' comparisons (which may trap, for the compiler), would keep the loop from vectorising;
   nothing here reads errno or enables an FP exception. */
namespace turgor {

namespace {
/* CLOSING: the normal force on a closing bond too (-glue_compression); LAW: Glue::Law. Template
   arguments, since a selection on a run-time flag inside the loop keeps GCC from vectorising it. The
   mark's tests are combined with & (no short circuit: a branch would not vectorise). */
template <bool CLOSING, int LAW>
TURGOR_VECTOR_CLONES void Loop(size_t n, const PetscInt *__restrict p, const PetscInt *__restrict a, const PetscInt *__restrict b,
                               const PetscReal *__restrict lam, const PetscReal *__restrict sign, const PetscReal *__restrict gn0,
                               const PetscReal *__restrict gt0, const PetscReal *__restrict L, const PetscReal *__restrict intact,
                               const PetscReal *__restrict lmax, const PetscReal *__restrict x, const GlueLawParameters law, PetscReal *__restrict force,
                               PetscReal *__restrict dnp_out, PetscReal *__restrict dt_out, PetscReal *__restrict mark)
{
  const PetscReal kn = law.kn, kt = law.kt, beta2 = law.beta2, l0 = law.l0, l02 = law.l02, Gc = law.Gc, sigma = law.sigma, tau = law.tau;
  for (size_t k = 0; k < n; k++) {
    const GlueBondOpening o = GlueOpeningAt(x, p[k], a[k], b[k], lam[k], sign[k], gn0[k], gt0[k]);
    GlueForceOf(o, L[k], kn, kt, CLOSING ? o.dn : o.dnp, force + 4 * k); /* s = (1 - D) L = L exactly at D = 0 */
    dnp_out[k]              = o.dnp;
    dt_out[k]               = o.dt;
    const PetscReal l2      = GlueOpening2(o.dnp, o.dt, beta2);
    const bool      changes = LAW == 2 ? !GlueBeforePeak(true, lmax[k], l2, l0, l02) : GlueBrittleBreaks(LAW == 0, kn, kt, Gc, sigma, tau, l2, o.dnp, o.dt);
    mark[k]                 = (intact[k] != 0) & changes ? 1 : 0;
  }
}

template <bool CLOSING>
void LoopOfLaw(const GlueBondGeometry &G, size_t lo, size_t hi, const PetscReal *x, const GlueLawParameters &law, PetscReal *force, PetscReal *dnp,
               PetscReal *dt, PetscReal *mark)
{
  const size_t n   = hi - lo;
  auto         run = [&](auto LAW) {
    Loop<CLOSING, decltype(LAW)::value>(n, G.p.data() + lo, G.a.data() + lo, G.b.data() + lo, G.lam.data() + lo, G.sign.data() + lo, G.gn0.data() + lo,
                                        G.gt0.data() + lo, G.L.data() + lo, G.intact.data() + lo, G.lmax.data() + lo, x, law, force, dnp, dt, mark);
  };
  if (law.law == 0) run(std::integral_constant<int, 0>());
  else if (law.law == 1) run(std::integral_constant<int, 1>());
  else run(std::integral_constant<int, 2>());
}
} // namespace

void GlueUndamagedForces(const GlueBondGeometry &G, size_t lo, size_t hi, const PetscReal *x, const GlueLawParameters &law, PetscReal *force, PetscReal *dnp,
                         PetscReal *dt, PetscReal *mark)
{
  if (law.closing) LoopOfLaw<true>(G, lo, hi, x, law, force, dnp, dt, mark);
  else LoopOfLaw<false>(G, lo, hi, x, law, force, dnp, dt, mark);
}

} // namespace turgor
