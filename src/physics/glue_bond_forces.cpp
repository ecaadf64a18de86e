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
    /* Glue::BondRange's expressions, with D = 0 */
    const PetscReal ex = x[2 * b[k]] - x[2 * a[k]], ey = x[2 * b[k] + 1] - x[2 * a[k] + 1];
    const PetscReal il = 1 / std::sqrt(ex * ex + ey * ey), tx = ex * il, ty = ey * il, nx = -sign[k] * ty, ny = sign[k] * tx;
    const PetscReal l1 = 1 - lam[k];
    const PetscReal gx = x[2 * p[k]] - l1 * x[2 * a[k]] - lam[k] * x[2 * b[k]], gy = x[2 * p[k] + 1] - l1 * x[2 * a[k] + 1] - lam[k] * x[2 * b[k] + 1];
    const PetscReal gt = gx * tx + gy * ty, gn = gx * nx + gy * ny;
    const PetscReal dn = gn - gn0[k], dt = gt - gt0[k], dnp = std::max(dn, (PetscReal)0);
    const PetscReal dnf = CLOSING ? dn : dnp;
    const PetscReal s = L[k], Fn = s * kn * dnf, Ft = s * kt * dt; /* s = (1 - D) L = L exactly at D = 0 */
    const PetscReal Fx = Fn * nx + Ft * tx, Fy = Fn * ny + Ft * ty, q = (Ft * gn - Fn * gt) * il;
    force[4 * k]     = Fx;
    force[4 * k + 1] = Fy;
    force[4 * k + 2] = l1 * Fx + q * nx;
    force[4 * k + 3] = l1 * Fy + q * ny;
    dnp_out[k]       = dnp;
    dt_out[k]        = dt;
  }
}
} // namespace

void GlueUndamagedForces(const GlueBondGeometry &G, const PetscReal *x, PetscReal kn, PetscReal kt, bool closing, PetscReal *force, PetscReal *dnp,
                         PetscReal *dt)
{
  if (closing)
    Loop<true>(G.Size(), G.p.data(), G.a.data(), G.b.data(), G.lam.data(), G.sign.data(), G.gn0.data(), G.gt0.data(), G.L.data(), x, kn, kt, force, dnp, dt);
  else
    Loop<false>(G.Size(), G.p.data(), G.a.data(), G.b.data(), G.lam.data(), G.sign.data(), G.gn0.data(), G.gt0.data(), G.L.data(), x, kn, kt, force, dnp, dt);
}

} // namespace turgor
