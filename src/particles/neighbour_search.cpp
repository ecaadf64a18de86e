#include <turgor/particles/neighbour_search.h>
#include <turgor/core/geometry.h>
#include <turgor/core/vector_clones.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace turgor {

namespace {
/* The largest |x_i - r_i|^2 over n particles, as the largest bit pattern of the squares: they are
   non-negative, so their patterns as signed integers order as they do, and an integer max
   vectorises where GCC keeps a floating-point max reduction scalar (the same value; a NaN move,
   which fails the step anyway, may come out as the largest). */
TURGOR_VECTOR_CLONES std::int64_t LargestMove2(PetscInt n, const PetscReal *__restrict x, const PetscReal *__restrict r)
{
  std::int64_t m = 0;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal dx = x[2 * i] - r[2 * i], dy = x[2 * i + 1] - r[2 * i + 1], d2 = dx * dx + dy * dy;
    std::int64_t    b;
    std::memcpy(&b, &d2, sizeof b);
    m = std::max(m, b);
  }
  return m;
}
/* ... against two references at once (x read once) */
TURGOR_VECTOR_CLONES void LargestMoves2(PetscInt      n, const PetscReal *__restrict x, const PetscReal *__restrict r, const PetscReal *__restrict q,
                                        std::int64_t *mr, std::int64_t *mq)
{
  std::int64_t a = 0, b = 0;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal dx = x[2 * i] - r[2 * i], dy = x[2 * i + 1] - r[2 * i + 1], d2 = dx * dx + dy * dy;
    const PetscReal ex = x[2 * i] - q[2 * i], ey = x[2 * i + 1] - q[2 * i + 1], e2 = ex * ex + ey * ey;
    std::int64_t    u, w;
    std::memcpy(&u, &d2, sizeof u);
    std::memcpy(&w, &e2, sizeof w);
    a = std::max(a, u), b = std::max(b, w);
  }
  *mr = a, *mq = b;
}
PetscReal AsReal(std::int64_t b)
{
  PetscReal v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}
} // namespace

void NeighbourSearch::RequestFluidPairs(PetscReal cutoff)
{
  fluid_cutoff_ = std::max(fluid_cutoff_, cutoff);
}
void NeighbourSearch::RequestParticleSpringPairs(PetscReal cutoff)
{
  spring_cutoff_ = std::max(spring_cutoff_, cutoff);
}

void NeighbourSearch::Mark(const PetscReal *x, PetscInt n) const
{
  x_mark_.assign(x, x + 2 * n);
  mark_move2_ = 0;
}

void NeighbourSearch::Reset()
{
  x_ref_.clear();
  x_mark_.clear();
  fluid_pairs_     = PairList();
  particle_spring_ = PointSegmentList();
}

PetscErrorCode NeighbourSearch::Update(const ParticleSet &P, const PetscReal *x, const PeriodicImages &images)
{
  PetscFunctionBeginUser;
  if (!WantsFluidPairs() && !WantsParticleSpringPairs()) PetscFunctionReturn(PETSC_SUCCESS);
  bool rebuild = x_ref_.size() != (size_t)(2 * P.n);
  mark_move2_  = PETSC_MAX_REAL;
  if (!rebuild) {
    /* a lattice change moves every image shift by at most |da1| + |da2| */
    PetscReal da = 0;
    if (images.periodic)
      da = std::hypot(images.a[0][0] - a_ref_[0][0], images.a[0][1] - a_ref_[0][1]) + std::hypot(images.a[1][0] - a_ref_[1][0], images.a[1][1] - a_ref_[1][1]);
    const PetscReal lim = 0.5 * (skin_ - da), lim2 = lim * lim;
    /* the largest move since the build and since the mark (no early exit, vectorised) */
    std::int64_t mr, mq;
    if (x_mark_.size() == x_ref_.size()) {
      LargestMoves2(P.n, x, x_ref_.data(), x_mark_.data(), &mr, &mq);
      mark_move2_ = AsReal(mq);
    } else mr = LargestMove2(P.n, x, x_ref_.data());
    rebuild = lim <= 0 || AsReal(mr) > lim2;
  }
  if (rebuild) {
    if (images.periodic) PetscCall(BuildPeriodic(P, x, images));
    else PetscCall(Build(P, x));
    for (int r = 0; r < 2; r++)
      for (int d = 0; d < 2; d++) a_ref_[r][d] = images.a[r][d];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rows come out by i (the outer loop); sort each row's j in place: no permutation and no
   second copy of the list (the rebuild's memory peak). */
void NeighbourSearch::SortFluidPairs()
{
  std::vector<PetscInt> &J = fluid_pairs_.j;
  for (PetscInt i = 0; i < fluid_pairs_.Rows(); i++) std::sort(J.begin() + fluid_pairs_.start[i], J.begin() + fluid_pairs_.start[i + 1]);
}

void NeighbourSearch::BinParticles(const ParticleSet &P, const PetscReal *x, PetscReal bin)
{
  PetscReal xmin = x[0], xmax = x[0], ymin = x[1], ymax = x[1];
  for (PetscInt k = 1; k < P.n; k++) {
    xmin = std::min(xmin, x[2 * k]);
    xmax = std::max(xmax, x[2 * k]);
    ymin = std::min(ymin, x[2 * k + 1]);
    ymax = std::max(ymax, x[2 * k + 1]);
  }
  /* Bins at least `bin` wide; coarser if particles spread far (keeps the grid O(n)). */
  bin_ = bin;
  while (((xmax - xmin) / bin_ + 1) * ((ymax - ymin) / bin_ + 1) > 4.0 * P.n + 64) bin_ *= 2;
  x0_  = xmin;
  y0_  = ymin;
  nbx_ = (PetscInt)((xmax - xmin) / bin_) + 1;
  nby_ = (PetscInt)((ymax - ymin) / bin_) + 1;
  bin_start_.assign((size_t)nbx_ * nby_ + 1, 0);
  for (PetscInt k = 0; k < P.n; k++) bin_start_[BinOf(x, k) + 1]++;
  for (size_t b = 0; b + 1 < bin_start_.size(); b++) bin_start_[b + 1] += bin_start_[b];
  bin_items_.resize(P.n);
  std::vector<PetscInt> fill(bin_start_.begin(), bin_start_.end() - 1);
  for (PetscInt k = 0; k < P.n; k++) bin_items_[fill[BinOf(x, k)]++] = k;
}

/* What every build starts with: count it, keep the positions it is built at, and empty the lists
   but keep their storage (a rebuild of about the same size then allocates nothing: no old list
   plus a growing new one at the same time); a non-finite position is an error. */
PetscErrorCode NeighbourSearch::StartBuild(const ParticleSet &P, const PetscReal *x)
{
  PetscFunctionBeginUser;
  rebuilds_++;
  x_ref_.assign(x, x + 2 * P.n);
  fluid_pairs_.start.clear();
  fluid_pairs_.j.clear();
  particle_spring_.p.clear();
  particle_spring_.s.clear();
  particle_spring_.img.clear();
  for (PetscInt k = 0; k < 2 * P.n; k++)
    PetscCheck(std::isfinite(x[k]), PETSC_COMM_SELF, PETSC_ERR_FP, "Neighbour search: particle %" PetscInt_FMT " has a non-finite position", k / 2);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourSearch::Build(const ParticleSet &P, const PetscReal *x)
{
  PetscFunctionBeginUser;
  PetscCall(StartBuild(P, x));

  const PetscReal rf = fluid_cutoff_ + skin_, rs = spring_cutoff_ + skin_;
  BinParticles(P, x, std::max(WantsFluidPairs() ? rf : 0, WantsParticleSpringPairs() ? rs : 0));

  if (WantsFluidPairs()) {
    const PetscReal rf2 = rf * rf;
    fluid_pairs_.start.assign(P.n + 1, 0);
    for (PetscInt i = 0; i < P.n; i++) {
      fluid_pairs_.start[i] = (PetscInt)fluid_pairs_.j.size();
      if (P.kind[i] != KIND_FLUID) continue;
      const PetscInt bi = BinOf(x, i), bx = bi % nbx_, by = bi / nbx_;
      for (PetscInt jy = std::max<PetscInt>(0, by - 1); jy <= std::min(nby_ - 1, by + 1); jy++)
        for (PetscInt jx = std::max<PetscInt>(0, bx - 1); jx <= std::min(nbx_ - 1, bx + 1); jx++) {
          const PetscInt b = jy * nbx_ + jx;
          for (PetscInt t = bin_start_[b]; t < bin_start_[b + 1]; t++) {
            const PetscInt j = bin_items_[t];
            if (j <= i || P.kind[j] != KIND_FLUID || P.cell[j] != P.cell[i]) continue;
            const PetscReal dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
            if (dx * dx + dy * dy < rf2) fluid_pairs_.j.push_back(j);
          }
        }
    }
    fluid_pairs_.start[P.n] = (PetscInt)fluid_pairs_.j.size();
    SortFluidPairs(); /* pairs were found bin by bin: sort each row by j for the SPH passes */
  }

  if (WantsParticleSpringPairs()) {
    const PetscReal rs2     = rs * rs;
    const PetscInt  n_owned = P.NumOwned();
    for (size_t s = 0; s < P.springs.size(); s++) {
      const PetscInt   a = P.springs[s].i, b = P.springs[s].j;
      const PetscReal *xa = &x[2 * a], *xb = &x[2 * b];
      const PetscInt   bx0 = std::max<PetscInt>(0, (PetscInt)std::floor((std::min(xa[0], xb[0]) - rs - x0_) / bin_));
      const PetscInt   bx1 = std::min<PetscInt>(nbx_ - 1, (PetscInt)std::floor((std::max(xa[0], xb[0]) + rs - x0_) / bin_));
      const PetscInt   by0 = std::max<PetscInt>(0, (PetscInt)std::floor((std::min(xa[1], xb[1]) - rs - y0_) / bin_));
      const PetscInt   by1 = std::min<PetscInt>(nby_ - 1, (PetscInt)std::floor((std::max(xa[1], xb[1]) + rs - y0_) / bin_));
      for (PetscInt jy = by0; jy <= by1; jy++)
        for (PetscInt jx = bx0; jx <= bx1; jx++) {
          const PetscInt bb = jy * nbx_ + jx;
          for (PetscInt t = bin_start_[bb]; t < bin_start_[bb + 1]; t++) {
            const PetscInt p = bin_items_[t];
            if (p == a || p == b || p >= n_owned) continue; /* a halo particle's pairs are its owner's */
            if (PointSegmentDistance2(&x[2 * p], xa, xb) < rs2) {
              particle_spring_.p.push_back(p);
              particle_spring_.s.push_back((PetscInt)s);
            }
          }
        }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Direct search for small periodic cells (RVEs of a few cells): all same-cell fluid pairs without
   images, and every (particle, spring image) within the cutoff. O(n^2) and O(9 n n_springs), which
   is what a one-cell RVE (19 particles) or a 4 x 4-cell RVE (304 particles) needs. */
PetscErrorCode NeighbourSearch::BuildPeriodic(const ParticleSet &P, const PetscReal *x, const PeriodicImages &images)
{
  PetscFunctionBeginUser;
  PetscCall(StartBuild(P, x));
  if (WantsFluidPairs()) {
    const PetscReal rf = fluid_cutoff_ + skin_, rf2 = rf * rf;
    fluid_pairs_.start.assign(P.n + 1, 0);
    for (PetscInt i = 0; i < P.n; i++) {
      fluid_pairs_.start[i] = (PetscInt)fluid_pairs_.j.size();
      if (P.kind[i] != KIND_FLUID) continue;
      for (PetscInt j = i + 1; j < P.n; j++) {
        if (P.kind[j] != KIND_FLUID || P.cell[j] != P.cell[i]) continue;
        const PetscReal dx = x[2 * j] - x[2 * i], dy = x[2 * j + 1] - x[2 * i + 1];
        if (dx * dx + dy * dy < rf2) fluid_pairs_.j.push_back(j);
      }
    }
    fluid_pairs_.start[P.n] = (PetscInt)fluid_pairs_.j.size();
  }
  if (WantsParticleSpringPairs()) {
    const PetscReal rs = spring_cutoff_ + skin_, rs2 = rs * rs;
    for (size_t s = 0; s < P.springs.size(); s++) {
      const Spring    &sp = P.springs[s];
      const PetscReal *se = images.x[sp.image];
      for (int k = 0; k < 9; k++) {
        const PetscReal *sk    = images.x[k];
        const PetscReal  xa[2] = {x[2 * sp.i] + sk[0], x[2 * sp.i + 1] + sk[1]};
        const PetscReal  xb[2] = {x[2 * sp.j] + se[0] + sk[0], x[2 * sp.j + 1] + se[1] + sk[1]};
        for (PetscInt p = 0; p < P.n; p++) {
          if (p == sp.i || p == sp.j) continue;
          if (PointSegmentDistance2(&x[2 * p], xa, xb) < rs2) {
            particle_spring_.p.push_back(p);
            particle_spring_.s.push_back((PetscInt)s);
            particle_spring_.img.push_back(k);
          }
        }
      }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeighbourSearch::Restore(const ParticleSet &P, const std::vector<PetscReal> &x_ref, PetscInt rebuilds, const PeriodicImages &images)
{
  PetscFunctionBeginUser;
  Reset();
  if (!x_ref.empty() && (WantsFluidPairs() || WantsParticleSpringPairs())) {
    PetscCheck(x_ref.size() == (size_t)(2 * P.n), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "neighbour search: the checkpoint's list positions are for %zu particles, the scene has %" PetscInt_FMT, x_ref.size() / 2, P.n);
    if (images.periodic) PetscCall(BuildPeriodic(P, x_ref.data(), images));
    else PetscCall(Build(P, x_ref.data()));
    for (int r = 0; r < 2; r++)
      for (int d = 0; d < 2; d++) a_ref_[r][d] = images.a[r][d];
  }
  rebuilds_ = rebuilds;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
