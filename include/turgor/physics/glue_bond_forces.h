#pragma once
/* The glue bonds' forces as if undamaged, in one loop over arrays that the compiler vectorises (the
   glue term's cost: a square root, a division and some 60 operations a bond). Glue keeps its bonds
   as records (what its state declares); their fixed geometry is copied here, by field, when they are
   made or read back, and the loop writes each bond's own entries only. Element by element the
   arithmetic is Glue's scalar code's, in the same order and without fused multiply-adds, so a vector
   build (AVX2, chosen at run time where the CPU has it) gives the same bits as a scalar one. */
#include <petscsys.h>
#include <cstddef>
#include <vector>

namespace turgor {

struct GlueBondGeometry {
  std::vector<PetscInt>  p, a, b;                /* node, bar ends */
  std::vector<PetscReal> lam, sign, gn0, gt0, L; /* bond point, side of the normal, reference opening, length share */
  size_t                 Size() const { return p.size(); }
  void                   Resize(size_t n)
  {
    for (auto *v : {&p, &a, &b}) v->resize(n);
    for (auto *v : {&lam, &sign, &gn0, &gt0, &L}) v->resize(n);
  }
};

/* Per bond k: F = L (k_n d_n n + k_t d_t t) with d_n = <opening> (closing: the signed one too) into
   force[4 k .. 4 k + 3] = (F_x, F_y, share of bar end a), and the opening's <delta_n>, delta_t into
   dnp[k], dt[k]; every bond, intact or not (the caller skips the broken ones, and redoes the damaged). */
void GlueUndamagedForces(const GlueBondGeometry &G, const PetscReal *x, PetscReal kn, PetscReal kt, bool closing, PetscReal *force, PetscReal *dnp,
                         PetscReal *dt);

} // namespace turgor
