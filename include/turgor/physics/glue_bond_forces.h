#pragma once
/* The glue bonds' forces as if undamaged, in one loop over arrays that the compiler vectorises (the
   glue term's cost: a square root, a division and some 60 operations a bond). Glue keeps its bonds
   as records (what its state declares); their fixed geometry is copied here, by field, when they are
   made or read back, and the loop writes each bond's own entries only. Element by element the
   arithmetic is Glue's scalar code's, in the same order and without fused multiply-adds, so a vector
   build (AVX2, chosen at run time where the CPU has it) gives the same bits as a scalar one. */
#include <petscsys.h>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace turgor {

struct GlueBondGeometry {
  std::vector<PetscInt>  p, a, b;                /* node, bar ends */
  std::vector<PetscReal> lam, sign, gn0, gt0, L; /* bond point, side of the normal, reference opening, length share */
  /* the two fields an accepted step changes, mirrored from the records where they change: 1 while
     intact, 0 broken; the softening law's committed largest opening */
  std::vector<PetscReal> intact, lmax;
  size_t                 Size() const { return p.size(); }
  void                   Resize(size_t n)
  {
    for (auto *v : {&p, &a, &b}) v->resize(n);
    for (auto *v : {&lam, &sign, &gn0, &gt0, &L, &intact, &lmax}) v->resize(n);
  }
};

/* The law's parameters as the force loops read them (locals: stores could alias a term's members). */
struct GlueLawParameters {
  int       law;                    /* Glue::Law: 0 energy, 1 strength, 2 softening */
  bool      closing;                /* -glue_compression: the normal force on a closing bond too */
  PetscReal kn, kt, beta2, l0, l02; /* stiffnesses, k_t / k_n, the softening law's peak opening and its square */
  PetscReal Gc, sigma, tau;         /* fracture energy, strengths */
};

/* The squared equivalent opening <delta_n>^2 + (k_t/k_n) delta_t^2. */
inline PetscReal GlueOpening2(PetscReal dnp, PetscReal dt, PetscReal beta2)
{
  return dnp * dnp + beta2 * dt * dt;
}
/* A softening bond still below its peak (no damage, nothing to commit; lmax is recorded from the peak
   on): tested without a square root, and with & (no short circuit: a branch would not vectorise). */
inline bool GlueBeforePeak(bool softening, PetscReal lmax, PetscReal l2, PetscReal l0, PetscReal l02)
{
  return softening & (lmax <= l0) & (l2 <= l02);
}
/* A brittle law's break at the opening (<delta_n>, delta_t), l2 = GlueOpening2: the energy law's
   stored energy k_n l2 / 2 >= G_c, the strength law's (k_n <delta_n> / sigma_c)^2 + (k_t delta_t /
   tau_c)^2 >= 1 (Glue::Commit's test, and the force loop's mark of the bonds the accepted step breaks). */
inline bool GlueBrittleBreaks(bool energy_law, PetscReal kn, PetscReal kt, PetscReal Gc, PetscReal sigma, PetscReal tau, PetscReal l2, PetscReal dnp,
                              PetscReal dt)
{
  return energy_law ? 0.5 * kn * l2 >= Gc : (kn * dnp / sigma) * (kn * dnp / sigma) + (kt * dt / tau) * (kt * dt / tau) >= 1;
}

/* One bond at x (node p, bar a-b, bond point lambda, side `sign`, reference opening gn0, gt0): the
   bar's frame and the opening, the one formula of Glue's scalar code and of the vectorised loop. */
struct GlueBondOpening {
  PetscReal tx, ty, nx, ny, il, l1, gt, gn, dn, dt, dnp; /* unit tangent and normal, 1/|e|, 1 - lambda, gap in the frame, opening, <delta_n> */
};
inline GlueBondOpening GlueOpeningAt(const PetscReal *x, PetscInt p, PetscInt a, PetscInt b, PetscReal lam, PetscReal sign, PetscReal gn0, PetscReal gt0)
{
  GlueBondOpening o;
  const PetscReal ex = x[2 * b] - x[2 * a], ey = x[2 * b + 1] - x[2 * a + 1];
  o.il = 1 / std::sqrt(ex * ex + ey * ey), o.tx = ex * o.il, o.ty = ey * o.il, o.nx = -sign * o.ty, o.ny = sign * o.tx;
  o.l1               = 1 - lam;
  const PetscReal gx = x[2 * p] - o.l1 * x[2 * a] - lam * x[2 * b], gy = x[2 * p + 1] - o.l1 * x[2 * a + 1] - lam * x[2 * b + 1];
  o.gt = gx * o.tx + gy * o.ty, o.gn = gx * o.nx + gy * o.ny;
  o.dn = o.gn - gn0, o.dt = o.gt - gt0, o.dnp = std::max(o.dn, (PetscReal)0); /* branch-free: at rest dn jitters about 0 */
  return o;
}
/* Its force with s = (1 - D) L and the normal opening dnf (<delta_n>, or delta_n where closing bonds
   push too): F[0..1] the force on the bar (minus: on the node), F[2..3] the share of bar end a
   (q = (F_t g.n - F_n g.t) / |e|, the couple that makes the torque zero). */
inline void GlueForceOf(const GlueBondOpening &o, PetscReal s, PetscReal kn, PetscReal kt, PetscReal dnf, PetscReal *F)
{
  const PetscReal Fn = s * kn * dnf, Ft = s * kt * o.dt;
  const PetscReal Fx = Fn * o.nx + Ft * o.tx, Fy = Fn * o.ny + Ft * o.ty, q = (Ft * o.gn - Fn * o.gt) * o.il;
  F[0] = Fx, F[1] = Fy, F[2] = o.l1 * Fx + q * o.nx, F[3] = o.l1 * Fy + q * o.ny;
}

/* Per bond k of [lo, hi): F = L (k_n d_n n + k_t d_t t) with d_n = <opening> (closing: the signed one
   too) into force[4 (k - lo) .. 4 (k - lo) + 3] = (F_x, F_y, share of bar end a), the opening's
   <delta_n>, delta_t into dnp[k - lo], dt[k - lo], and mark[k - lo] = 1 for an intact bond that the
   accepted step may change (softening: past its peak, whose force must be redone with its damage;
   brittle: breaking), else 0; every bond, intact or not (the caller skips the broken ones). */
void GlueUndamagedForces(const GlueBondGeometry &G, size_t lo, size_t hi, const PetscReal *x, const GlueLawParameters &law, PetscReal *force, PetscReal *dnp,
                         PetscReal *dt, PetscReal *mark);

} // namespace turgor
