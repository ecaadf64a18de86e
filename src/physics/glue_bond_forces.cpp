#include <turgor/core/vector_clones.h>
#include <turgor/physics/glue_bond_forces.h>
#include <algorithm>
#include <cmath>

/* Compiled with -fno-math-errno (CMakeLists.txt): sqrt's errno branch would keep the loop from
   vectorising; nothing here reads errno. */
namespace turgor {

namespace {
/* CLOSING: the normal force on a closing bond too (-glue_compression); a template argument, since a
   selection on a run-time flag inside the loop keeps GCC from vectorising it */
template <bool CLOSING>
TURGOR_VECTOR_CLONES void Loop(size_t n, const PetscInt *__restrict p, const PetscInt *__restrict a, const PetscInt *__restrict b,
                               const PetscReal *__restrict lam, const PetscReal *__restrict sign, const PetscReal *__restrict gn0,
                               const PetscReal *__restrict gt0, const PetscReal *__restrict L, const PetscReal *__restrict x, PetscReal kn, PetscReal kt,
                               PetscReal *__restrict force, PetscReal *__restrict dnp_out, PetscReal *__restrict dt_out)
{
  for (size_t k = 0; k < n; k++) {
    const GlueBondOpening o = GlueOpeningAt(x, p[k], a[k], b[k], lam[k], sign[k], gn0[k], gt0[k]);
    GlueForceOf(o, L[k], kn, kt, CLOSING ? o.dn : o.dnp, force + 4 * k); /* s = (1 - D) L = L exactly at D = 0 */
    dnp_out[k] = o.dnp;
    dt_out[k]  = o.dt;
  }
}
} // namespace

void GlueUndamagedForces(const GlueBondGeometry &G, size_t lo, size_t hi, const PetscReal *x, PetscReal kn, PetscReal kt, bool closing, PetscReal *force,
                         PetscReal *dnp, PetscReal *dt)
{
  const size_t n = hi - lo;
  if (closing)
    Loop<true>(n, G.p.data() + lo, G.a.data() + lo, G.b.data() + lo, G.lam.data() + lo, G.sign.data() + lo, G.gn0.data() + lo, G.gt0.data() + lo,
               G.L.data() + lo, x, kn, kt, force, dnp, dt);
  else
    Loop<false>(n, G.p.data() + lo, G.a.data() + lo, G.b.data() + lo, G.lam.data() + lo, G.sign.data() + lo, G.gn0.data() + lo, G.gt0.data() + lo,
                G.L.data() + lo, x, kn, kt, force, dnp, dt);
}

} // namespace turgor
