/* -tissue_type voronoi: Voronoi / Laguerre cells in a box, reproducible from -tissue_seed.

   Every cell is built on its own: the box, clipped by the power bisector of each nearby seed (a
   convex polygon stays convex under clipping, so the construction cannot tangle), nearby seeds
   visited on a grid ring by ring until the security radius says no farther seed can cut the cell.
   Only +, -, *, / and sqrt are used from the random numbers to the nodes, so the same seed gives
   the same tissue bit for bit wherever IEEE doubles are (std::mt19937_64 is fully specified; the
   uniform mapping is our own, std::uniform_real_distribution is not portable). */
#include <turgor/tissue/voronoi.h>
#include <turgor/core/errors.h>
#include <turgor/core/options.h>
#include <turgor/core/uniform_random.h>
#include <turgor/parallel/rank_reductions.h>
#include <algorithm>
#include <cmath>
#include <random>

namespace turgor {

PetscErrorCode VoronoiSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  BoxOption b(box);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_", "Voronoi / Laguerre tissue (-tissue_type voronoi; µm)", "turgor");
  PetscCall(TurgorOptionsInt(params, "-voronoi_cells", "Cells (seeds)", "VoronoiSpec", cells, &cells, NULL));
  PetscCall(TurgorOptionsRealArray(params, "-box", "Box xmin,ymin,xmax,ymax [µm] (default 0,0,400,400)", "VoronoiSpec", b.value, &b.n, &b.set));
  PetscCall(TurgorOptionsInt(params, "-seed", "Seed of the random seeds (same seed: same tissue, bit for bit)", "VoronoiSpec", seed, &seed, NULL));
  PetscCall(
    TurgorOptionsInt(params, "-lloyd_steps", "Lloyd relaxations: each seed moved to its cell's centroid", "VoronoiSpec", lloyd_steps, &lloyd_steps, NULL));
  PetscCall(TurgorOptionsReal(params, "-size_cv", "Coefficient of variation of the cell areas, 0 <= c <= 0.5 (Laguerre weights; 0: Voronoi)", "VoronoiSpec",
                              size_cv, &size_cv, NULL));
  PetscCall(TurgorOptionsReal(params, "-gap", "Gap [µm] between neighbouring cells' bar surfaces (a middle lamella; 0: touching at 2 r)", "VoronoiSpec", gap,
                              &gap, NULL));
  PetscOptionsEnd();
  PetscCall(b.Take(comm, "-tissue_box", BoxShape::HasArea, box, NULL));
  PetscCheck(cells >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_voronoi_cells = %" PetscInt_FMT ": must be >= 1", cells);
  PetscCheck(lloyd_steps >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_lloyd_steps = %" PetscInt_FMT ": must be >= 0", lloyd_steps);
  /* the areas are drawn uniform in [1 - sqrt(3) c, 1 + sqrt(3) c] (arithmetic only, see above);
     c <= 0.5 keeps the smallest cell at 13% of the mean */
  PetscCheck(std::isfinite(size_cv) && size_cv >= 0 && size_cv <= 0.5, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_size_cv = %g: must be in [0, 0.5]",
             (double)size_cv);
  PetscCheck(std::isfinite(gap) && gap >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_gap = %g: must be finite and >= 0", (double)gap);
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* Clip the convex ring (counter-clockwise, labelled edges) by {y : a . y <= b}; new edges along the
   line get `label`. A vertex on the line counts as inside and is not doubled. */
void Clip(PowerCell &c, PetscReal ax, PetscReal ay, PetscReal b, PetscInt label, PowerCell &out)
{
  const size_t n = c.v.size();
  out.v.clear();
  out.label.clear();
  for (size_t k = 0; k < n; k++) {
    const Point2   &P = c.v[k], &Q = c.v[(k + 1) % n];
    const PetscReal sP = ax * P[0] + ay * P[1] - b, sQ = ax * Q[0] + ay * Q[1] - b;
    if (sP <= 0) {
      out.v.push_back(P);
      out.label.push_back(sP == 0 && sQ > 0 ? label : c.label[k]);
      if (sP < 0 && sQ > 0) {
        const PetscReal t = sP / (sP - sQ);
        out.v.push_back({P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])});
        out.label.push_back(label);
      }
    } else if (sQ < 0) {
      const PetscReal t = sP / (sP - sQ);
      out.v.push_back({P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])});
      out.label.push_back(c.label[k]);
    }
  }
  std::swap(c, out);
  if (c.v.size() < 3) {
    c.v.clear();
    c.label.clear();
  }
}

PetscReal Radius(const PowerCell &c) /* farthest vertex from the origin (the seed, in relative coordinates) */
{
  PetscReal r2 = 0;
  for (const Point2 &p : c.v) r2 = std::max(r2, p[0] * p[0] + p[1] * p[1]);
  return std::sqrt(r2);
}

} // namespace

PowerCells::PowerCells(const PetscReal box[4], std::vector<Point2> seeds, std::vector<PetscReal> weights) :
    seeds_(std::move(seeds)), weights_(std::move(weights))
{
  const size_t    N = seeds_.size();
  const PetscReal W = box[2] - box[0], H = box[3] - box[1], hg = std::sqrt(W * H / (PetscReal)std::max(N, (size_t)1));
  for (int d = 0; d < 4; d++) box_[d] = box[d];
  gx_   = std::max((PetscInt)1, (PetscInt)(W / hg));
  gy_   = std::max((PetscInt)1, (PetscInt)(H / hg));
  cw_   = W / (PetscReal)gx_;
  ch_   = H / (PetscReal)gy_;
  hmin_ = std::min(cw_, ch_);
  wmax_ = weights_.empty() ? 0 : *std::max_element(weights_.begin(), weights_.end());
  start_.assign((size_t)(gx_ * gy_ + 1), 0);
  bin_.resize(N);
  for (size_t i = 0; i < N; i++) {
    PetscInt ix, iy;
    BinOf(seeds_[i], &ix, &iy);
    start_[(size_t)(iy * gx_ + ix) + 1]++;
  }
  for (size_t b = 0; b < (size_t)(gx_ * gy_); b++) start_[b + 1] += start_[b];
  std::vector<PetscInt> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < N; i++) {
    PetscInt ix, iy;
    BinOf(seeds_[i], &ix, &iy);
    bin_[(size_t)fill[(size_t)(iy * gx_ + ix)]++] = (PetscInt)i;
  }
}

void PowerCells::BinOf(const Point2 &p, PetscInt *ix, PetscInt *iy) const
{
  *ix = std::min(gx_ - 1, std::max((PetscInt)0, (PetscInt)((p[0] - box_[0]) / cw_)));
  *iy = std::min(gy_ - 1, std::max((PetscInt)0, (PetscInt)((p[1] - box_[1]) / ch_)));
}

PetscErrorCode PowerCells::Cell(size_t i, PowerCell *cell, PowerCell *scratch) const
{
  PowerCell   &c = *cell;
  const Point2 s = seeds_[i];
  PetscFunctionBeginUser;
  c.v = {
    {box_[0] - s[0], box_[1] - s[1]},
    {box_[2] - s[0], box_[1] - s[1]},
    {box_[2] - s[0], box_[3] - s[1]},
    {box_[0] - s[0], box_[3] - s[1]}
  };
  c.label = {-1, -2, -3, -4};
  PetscInt ix, iy;
  BinOf(s, &ix, &iy);
  for (PetscInt k = 0; !c.v.empty(); k++) {
    for (PetscInt jy = iy - k; jy <= iy + k; jy++) {
      if (jy < 0 || jy >= gy_) continue;
      const bool edge_row = (jy == iy - k || jy == iy + k);
      for (PetscInt jx = ix - k; jx <= ix + k; jx += (edge_row || k == 0) ? 1 : 2 * k) {
        if (jx < 0 || jx >= gx_) continue;
        for (PetscInt t = start_[(size_t)(jy * gx_ + jx)]; t < start_[(size_t)(jy * gx_ + jx) + 1] && !c.v.empty(); t++) {
          const size_t j = (size_t)bin_[(size_t)t];
          if (j == i) continue;
          const PetscReal dx = seeds_[j][0] - s[0], dy = seeds_[j][1] - s[1], d2 = dx * dx + dy * dy;
          PetscCheck(d2 > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Voronoi seeds %zu and %zu coincide at (%g, %g)", i, j, (double)s[0], (double)s[1]);
          /* power bisector in coordinates relative to seed i: 2 y . d <= |d|^2 + w_i - w_j */
          Clip(c, dx, dy, 0.5 * (d2 + Weight(i) - Weight(j)), (PetscInt)j, *scratch);
        }
      }
    }
    /* every seed not yet visited is at least D = k hmin away; it can cut the cell only if its
       bisector, at distance (D^2 + w_i - w_j) / (2 D) >= (D^2 + w_i - wmax) / (2 D), is nearer than
       the cell's farthest vertex R (the bound grows with D, so the first D that passes ends it) */
    const PetscReal D = (PetscReal)k * hmin_, R = Radius(c);
    if ((D > 0 && D * D + Weight(i) - wmax_ >= 2 * R * D) || (k > gx_ && k > gy_)) break;
  }
  for (Point2 &p : c.v) {
    p[0] += s[0];
    p[1] += s[1];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ComputePowerDiagram(const PetscReal box[4], const std::vector<Point2> &seeds, const std::vector<PetscReal> &weights,
                                   std::vector<PowerCell> *cells)
{
  const PowerCells diagram(box, seeds, weights);
  PowerCell        scratch;
  PetscFunctionBeginUser;
  cells->assign(seeds.size(), PowerCell());
  for (size_t i = 0; i < seeds.size(); i++) PetscCall(diagram.Cell(i, &(*cells)[i], &scratch));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void CellAreas(const std::vector<PowerCell> &cells, std::vector<PetscReal> *A)
{
  A->resize(cells.size());
  for (size_t i = 0; i < cells.size(); i++) (*A)[i] = cells[i].v.empty() ? 0 : RingSignedArea(cells[i].v);
}

static PetscReal MaxAreaError(const std::vector<PowerCell> &cells, const std::vector<PetscReal> &targets)
{
  std::vector<PetscReal> A;
  PetscReal              err = 0;
  CellAreas(cells, &A);
  for (size_t i = 0; i < A.size(); i++) err = std::max(err, std::fabs(A[i] - targets[i]) / targets[i]);
  return err;
}

/* Laguerre weights for the target areas by Newton's method on A(w) = T: dA_i/dw_j = -l_ij / (2 d_ij)
   (l_ij the shared edge, d_ij the seed distance), dA_i/dw_i = sum_j l_ij / (2 d_ij), a weighted graph
   Laplacian (singular: adding a constant to every weight changes nothing; T - A sums to zero, so the
   system is consistent). Each Newton step is solved by Jacobi-preconditioned CG, then damped until no
   cell is empty and the largest area error falls. CG is hand-written (not PETSc's KSP) so that the
   tissue does not depend on the machine's BLAS kernels: same seed, same bits. */
static PetscErrorCode AdaptWeights(MPI_Comm comm, const PetscReal box[4], VoronoiDiagram &D)
{
  const size_t                        N       = D.seeds.size();
  const PetscInt                      max_its = 100;
  const PetscReal                     tol     = 1e-6;
  std::vector<PetscReal>              A, b(N), x(N), r(N), z(N), p(N), q(N), diag(N), w0;
  std::vector<std::vector<PetscInt>>  nbr(N);
  std::vector<std::vector<PetscReal>> coef(N);
  auto                                any_empty = [&]() {
    for (const PowerCell &c : D.cells)
      if (c.v.empty()) return true;
    return false;
  };
  auto apply = [&](const std::vector<PetscReal> &v, std::vector<PetscReal> &out) {
    for (size_t i = 0; i < N; i++) {
      PetscReal s = 0;
      for (size_t t = 0; t < nbr[i].size(); t++) s += coef[i][t] * (v[i] - v[(size_t)nbr[i][t]]);
      out[i] = s;
    }
  };
  auto dot = [&](const std::vector<PetscReal> &u, const std::vector<PetscReal> &v) {
    PetscReal s = 0;
    for (size_t i = 0; i < N; i++) s += u[i] * v[i];
    return s;
  };
  PetscFunctionBeginUser;
  /* after a Lloyd step the old weights may empty a cell: pull them toward 0 (Voronoi, where no cell is empty) */
  PetscCall(ComputePowerDiagram(box, D.seeds, D.weights, &D.cells));
  for (int k = 0; any_empty(); k++) {
    PetscCall(StopIfInterrupted(comm, "set-up: the Laguerre weights of the Voronoi tissue (-tissue_size_cv)"));
    for (PetscReal &w : D.weights) w = k < 60 ? 0.5 * w : 0;
    PetscCall(ComputePowerDiagram(box, D.seeds, D.weights, &D.cells));
  }
  D.max_area_error = MaxAreaError(D.cells, D.targets);
  for (PetscInt it = 0; it < max_its && D.max_area_error >= tol; it++) {
    PetscCall(StopIfInterrupted(comm, "set-up: the Laguerre weights of the Voronoi tissue (-tissue_size_cv)")); /* every rank iterates alike */
    CellAreas(D.cells, &A);
    for (size_t i = 0; i < N; i++) {
      const PowerCell &c = D.cells[i];
      nbr[i].clear();
      coef[i].clear();
      diag[i] = 0;
      for (size_t k = 0; k < c.v.size(); k++) {
        const PetscInt j = c.label[k];
        if (j < 0) continue;
        const Point2   &u = c.v[k], &v = c.v[(k + 1) % c.v.size()];
        const PetscReal cij = std::hypot(v[0] - u[0], v[1] - u[1]) / (2 * std::hypot(D.seeds[j][0] - D.seeds[i][0], D.seeds[j][1] - D.seeds[i][1]));
        nbr[i].push_back(j);
        coef[i].push_back(cij);
        diag[i] += cij;
      }
      b[i] = D.targets[i] - A[i];
    }
    /* CG from 0 to a relative residual of 1e-8, on the range of the Laplacian: b's mean (rounding)
       is removed, else CG chases it and the weights drift by a constant until the bisectors lose
       their digits; the step is made mean-free for the same reason */
    PetscReal bmean = 0;
    for (size_t i = 0; i < N; i++) bmean += b[i];
    bmean /= (PetscReal)N;
    for (size_t i = 0; i < N; i++) b[i] -= bmean;
    const PetscReal bb = dot(b, b);
    std::fill(x.begin(), x.end(), 0);
    r = b;
    for (size_t i = 0; i < N; i++) z[i] = diag[i] > 0 ? r[i] / diag[i] : 0;
    p            = z;
    PetscReal rz = dot(r, z);
    for (PetscInt k = 0; k < 2000 && dot(r, r) > 1e-16 * bb; k++) {
      apply(p, q);
      const PetscReal pq = dot(p, q);
      if (!(pq > 0)) break;
      const PetscReal alpha = rz / pq;
      for (size_t i = 0; i < N; i++) {
        x[i] += alpha * p[i];
        r[i] -= alpha * q[i];
        z[i] = diag[i] > 0 ? r[i] / diag[i] : 0;
      }
      const PetscReal rz1 = dot(r, z), beta = rz1 / rz;
      rz = rz1;
      for (size_t i = 0; i < N; i++) p[i] = z[i] + beta * p[i];
    }
    PetscReal xmean = 0;
    for (size_t i = 0; i < N; i++) xmean += x[i];
    xmean /= (PetscReal)N;
    for (size_t i = 0; i < N; i++) x[i] -= xmean;
    /* damped: no empty cell, and the largest area error must fall */
    w0             = D.weights;
    PetscReal step = 1, err = PETSC_MAX_REAL;
    for (int halve = 0;; halve++) {
      for (size_t i = 0; i < N; i++) D.weights[i] = w0[i] + step * x[i];
      PetscCall(StopIfInterrupted(comm, "set-up: the Laguerre weights of the Voronoi tissue (-tissue_size_cv)")); /* a diagram of many cells takes long */
      PetscCall(ComputePowerDiagram(box, D.seeds, D.weights, &D.cells));
      if (!any_empty()) {
        err = MaxAreaError(D.cells, D.targets);
        if (err < D.max_area_error || halve >= 30) break;
      }
      PetscCheck(halve < 40, comm, PETSC_ERR_NOT_CONVERGED, "Option -tissue_size_cv: Laguerre weights: a cell stays empty however short the Newton step");
      step *= 0.5;
    }
    D.max_area_error    = err;
    D.weight_iterations = it + 1;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The seeds before any Lloyd step: uniform in the box, x then y from the stream */
static void DrawSeeds(const VoronoiSpec &spec, UniformRandom &u, std::vector<Point2> *seeds)
{
  const PetscReal W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  seeds->resize((size_t)spec.cells);
  for (Point2 &s : *seeds) {
    const PetscReal x = u(), y = u();
    s = {spec.box[0] + W * x, spec.box[1] + H * y};
  }
}

/* A Lloyd step's new seed: the centroid of its cell (kept inside the box), the old seed for an empty cell */
static Point2 LloydMove(const VoronoiSpec &spec, const Point2 &seed, const PowerCell &cell)
{
  if (cell.v.empty()) return seed;
  const Point2 c = RingCentroid(cell.v);
  return {std::min(spec.box[2], std::max(spec.box[0], c[0])), std::min(spec.box[3], std::max(spec.box[1], c[1]))};
}

/* The seeds (with their weights and target areas) renumbered along the Hilbert curve through them,
   so that a cell's neighbours are near it in the numbering and their nodes near in memory: the
   random draw leaves neighbouring cells anywhere in the arrays, and a large tissue's forces then
   gather from all over memory. The order depends only on the seeds: the same on any number of ranks. */
static void SeedsInSpaceOrder(const PetscReal box[4], std::vector<Point2> *seeds, std::vector<PetscReal> *weights, std::vector<PetscReal> *targets)
{
  std::vector<PetscInt> place;
  HilbertPlaces(*seeds, box, &place);
  auto permute = [&](auto *v) {
    if (!v || v->empty()) return;
    auto old = *v;
    for (size_t i = 0; i < old.size(); i++) (*v)[(size_t)place[i]] = old[i];
  };
  permute(seeds);
  permute(weights);
  permute(targets);
}

PetscErrorCode BuildVoronoiDiagram(MPI_Comm comm, const VoronoiSpec &spec, VoronoiDiagram *diagram)
{
  VoronoiDiagram &D = *diagram;
  const size_t    N = (size_t)spec.cells;
  const PetscReal W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  UniformRandom   u(spec.seed);
  PetscFunctionBeginUser;
  D = VoronoiDiagram();
  DrawSeeds(spec, u, &D.seeds);
  D.weights.assign(N, 0);
  if (spec.size_cv > 0) {
    /* areas uniform with the requested cv, stratified so that the sample has that cv (to a factor
       sqrt(1 - 1/N^2)) rather than the request plus sampling noise: a_k = 1 + sqrt(3) c (2 (k + 1/2)/N - 1)
       dealt to the cells in a random order (Fisher-Yates), scaled to fill the box */
    D.targets.resize(N);
    for (size_t k = 0; k < N; k++) D.targets[k] = (1 + std::sqrt(3.0) * spec.size_cv * (2 * ((PetscReal)k + 0.5) / (PetscReal)N - 1)) * W * H / (PetscReal)N;
    for (size_t k = N; k > 1; k--) std::swap(D.targets[k - 1], D.targets[(size_t)(u() * (PetscReal)k)]);
  }
  for (PetscInt step = 0;; step++) {
    PetscCall(StopIfInterrupted(comm, "set-up: the Voronoi tissue (-tissue_voronoi_cells, -tissue_lloyd_steps)")); /* every rank builds it alike */
    if (step == spec.lloyd_steps) SeedsInSpaceOrder(spec.box, &D.seeds, &D.weights, &D.targets); /* the final seeds: the last diagram is built in their order */
    if (spec.size_cv > 0) PetscCall(AdaptWeights(comm, spec.box, D));
    else PetscCall(ComputePowerDiagram(spec.box, D.seeds, D.weights, &D.cells));
    if (step == spec.lloyd_steps) break;
    for (size_t i = 0; i < N; i++) D.seeds[i] = LloydMove(spec, D.seeds[i], D.cells[i]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void ShrinkPowerCell(const PowerCell &cell, PetscReal r, PetscReal min_edge, std::vector<Point2> *out)
{
  const size_t n = cell.v.size();
  out->clear();
  if (n < 3) return;
  /* relative to the centroid, then each edge's inward offset half-plane n_in . (y - a) >= r clips
     the cell itself: the intersection of convex sets is the exact offset of a convex polygon, and
     edges that the offset swallows disappear on their own */
  const Point2 c = RingCentroid(cell.v);
  PowerCell    p, scratch;
  for (const Point2 &q : cell.v) p.v.push_back({q[0] - c[0], q[1] - c[1]});
  p.label.assign(n, 0);
  const std::vector<Point2> orig = p.v;
  for (size_t k = 0; k < n && !p.v.empty(); k++) {
    const Point2   &a = orig[k], &b = orig[(k + 1) % n];
    const PetscReal L = std::hypot(b[0] - a[0], b[1] - a[1]);
    if (!(L > 0)) continue;
    const PetscReal nx = -(b[1] - a[1]) / L, ny = (b[0] - a[0]) / L; /* inward normal of a counter-clockwise ring */
    Clip(p, -nx, -ny, -(nx * a[0] + ny * a[1]) - r, 0, scratch);
  }
  /* an edge shorter than min_edge: its two corners become one at its midpoint (the midpoint lies on
     the edge, so the polygon only loses area and stays convex) */
  std::vector<Point2> &v = p.v;
  for (bool merged = true; merged && v.size() > 3;) {
    merged = false;
    for (size_t k = 0; k < v.size() && v.size() > 3; k++) {
      const size_t l = (k + 1) % v.size();
      if (std::hypot(v[l][0] - v[k][0], v[l][1] - v[k][1]) < min_edge) {
        v[k] = {0.5 * (v[k][0] + v[l][0]), 0.5 * (v[k][1] + v[l][1])};
        v.erase(v.begin() + (std::ptrdiff_t)l);
        merged = true;
      }
    }
  }
  if (v.size() < 3 || RingSignedArea(v) <= 0) return;
  for (Point2 &q : v) out->push_back({q[0] + c[0], q[1] + c[1]});
}

/* A cell's ring: its power cell shrunk by the bar radius and half the gap, edges shorter than the
   bar radius merged (and at least 1e-9 of the mean cell size) */
static void ShrinkVoronoiCell(const VoronoiSpec &spec, const PolygonTissueSpec &poly, const PowerCell &cell, PolygonRing *ring)
{
  const PetscReal W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  const PetscReal min_edge = std::max(poly.bar_radius, 1e-9 * std::sqrt(W * H / (PetscReal)spec.cells));
  *ring                    = PolygonRing();
  ShrinkPowerCell(cell, poly.bar_radius + 0.5 * spec.gap, min_edge, &ring->points);
}

/* The error for cell i that vanished when shrunk (area: its power cell's) */
static PetscErrorCode VanishedCell(MPI_Comm comm, const VoronoiSpec &spec, const PolygonTissueSpec &poly, size_t i, const PowerCell &cell)
{
  const PetscReal W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  return PetscError(comm, __LINE__, PETSC_FUNCTION_NAME, __FILE__, PETSC_ERR_ARG_OUTOFRANGE, PETSC_ERROR_INITIAL,
                    "Options -tissue_bar_radius = %g, -tissue_gap = %g: Voronoi cell %zu (area %g µm^2) vanishes when shrunk by the bar radius and half "
                    "the gap (-tissue_voronoi_cells %" PetscInt_FMT " in a %g x %g box: cells of about %g µm); use a smaller radius or gap, or fewer cells",
                    (double)poly.bar_radius, (double)spec.gap, i, cell.v.empty() ? 0.0 : (double)RingSignedArea(cell.v), spec.cells, (double)W, (double)H,
                    (double)std::sqrt(W * H / (PetscReal)spec.cells));
}

PetscErrorCode GenerateVoronoiTissue(MPI_Comm comm, const VoronoiSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue, VoronoiDiagram *diagram)
{
  VoronoiDiagram local, &D = diagram ? *diagram : local;
  PetscLogEvent  ev;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgVoronoi", PETSC_OBJECT_CLASSID, &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCall(BuildVoronoiDiagram(comm, spec, &D));
  std::vector<PolygonRing> rings(D.cells.size());
  for (size_t i = 0; i < D.cells.size(); i++) {
    ShrinkVoronoiCell(spec, poly, D.cells[i], &rings[i]);
    if (rings[i].points.size() < 3) PetscCall(VanishedCell(comm, spec, poly, i, D.cells[i]));
  }
  PetscCall(BuildPolygonTissue(comm, rings, poly, true, tissue));
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Six corners per cell, plus the subdivision of the perimeters: a hexagon of area a has perimeter
   3.72 sqrt(a), so N cells about 3.8 sqrt(A N) in all. */
PetscErrorCode VoronoiGenerator::Estimate(PetscReal *particles, PetscReal *springs) const
{
  const PetscReal N = (PetscReal)spec.cells, A = (spec.box[2] - spec.box[0]) * (spec.box[3] - spec.box[1]);
  PetscFunctionBeginUser;
  *particles = 6 * N + (poly.bar_length > 0 ? 3.8 * std::sqrt(A * N) / poly.bar_length : 0);
  *springs   = *particles;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string VoronoiGenerator::SizeOptions() const
{
  return "-tissue_voronoi_cells " + std::to_string((long long)spec.cells) + BarLengthOption();
}

PetscErrorCode VoronoiGenerator::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "tissue voronoi: %" PetscInt_FMT " cells in [%g, %g] x [%g, %g], seed %" PetscInt_FMT ", %" PetscInt_FMT
                                   " Lloyd steps, size cv %g, gap %g µm, %s\n",
                                   spec.cells, (double)spec.box[0], (double)spec.box[2], (double)spec.box[1], (double)spec.box[3], spec.seed, spec.lloyd_steps,
                                   (double)spec.size_cv, (double)spec.gap, PolygonDescription().c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt VoronoiGenerator::NumCellsOfParts() const
{
  return poly.plates.Any() || poly.has_cut_box ? -1 : spec.cells;
}

std::string VoronoiGenerator::PartsRefused() const
{
  return "with -tissue_plates or -tissue_cut_box numbers its cells only once the whole tissue is built";
}

PetscErrorCode VoronoiGenerator::Ring(size_t i, PolygonRing *ring, PowerCell *cell, PowerCell *scratch) const
{
  PetscFunctionBeginUser;
  PetscCall(cells_.Cell(i, cell, scratch));
  ShrinkVoronoiCell(spec, poly, *cell, ring);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode VoronoiGenerator::PrepareParts(MPI_Comm comm)
{
  PetscMPIInt   rank, size;
  const size_t  N = (size_t)spec.cells;
  PetscLogEvent ev;
  PowerCell     cell, scratch;
  PolygonRing   ring;
  PetscFunctionBeginUser;
  PetscCheck(NumCellsOfParts() >= 0, comm, PETSC_ERR_ARG_INCOMP, "-tissue_type voronoi %s", PartsRefused().c_str());
  PetscCall(PetscLogEventRegister("TgVoronoiParts", PETSC_OBJECT_CLASSID, &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  /* each rank's range of seeds (by index: any range will do, every rank has every seed) */
  std::vector<PetscMPIInt> count(size), displ(size);
  for (PetscMPIInt r = 0; r < size; r++) {
    displ[r] = (PetscMPIInt)(N * (size_t)r / (size_t)size);
    count[r] = (PetscMPIInt)(N * (size_t)(r + 1) / (size_t)size) - displ[r];
  }
  const size_t i0 = (size_t)displ[rank], i1 = i0 + (size_t)count[rank];
  if (spec.size_cv > 0) {
    VoronoiDiagram D; /* the weights: a Newton solve over the whole diagram, on every rank alike */
    PetscCall(BuildVoronoiDiagram(comm, spec, &D));
    cells_ = PowerCells(spec.box, std::move(D.seeds), std::move(D.weights));
  } else {
    UniformRandom            u(spec.seed);
    std::vector<Point2>      seeds, moved(i1 - i0);
    std::vector<PetscMPIInt> count2(size), displ2(size); /* in reals */
    for (PetscMPIInt r = 0; r < size; r++) count2[r] = 2 * count[r], displ2[r] = 2 * displ[r];
    DrawSeeds(spec, u, &seeds);
    for (PetscInt step = 0; step < spec.lloyd_steps; step++) {
      PetscCall(StopIfInterrupted(comm, "set-up: the Voronoi tissue (-tissue_voronoi_cells, -tissue_lloyd_steps)"));
      const PowerCells diagram(spec.box, seeds, {});
      PetscErrorCode   e = PETSC_SUCCESS; /* (two seeds at one point: this rank's error, every rank's failure) */
      for (size_t i = i0; i < i1 && !e; i++) {
        e             = diagram.Cell(i, &cell, &scratch);
        moved[i - i0] = LloydMove(spec, seeds[i], cell);
      }
      PetscCall(AgreeOnError(comm, e, "a Lloyd step of the Voronoi tissue"));
      PetscCallMPI(MPI_Allgatherv(moved.data(), count2[rank], MPIU_REAL, seeds.data(), count2.data(), displ2.data(), MPIU_REAL, comm));
    }
    SeedsInSpaceOrder(spec.box, &seeds, nullptr, nullptr);
    cells_ = PowerCells(spec.box, std::move(seeds), {});
  }
  PetscCall(StopIfInterrupted(comm, "set-up: the Voronoi tissue's cells (-tissue_voronoi_cells)"));
  /* the range's cells: their nodes, the whole tissue's box, the farthest corner from a seed */
  std::vector<PetscInt> nodes(i1 - i0);
  PetscReal             ext[5]   = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL, 0}; /* -lo, hi, radius */
  PetscInt              vanished = (PetscInt)N;
  PetscErrorCode        e        = PETSC_SUCCESS;
  for (size_t i = i0; i < i1 && !e; i++) {
    if ((e = Ring(i, &ring, &cell, &scratch))) break;
    const Point2 &s = cells_.Seeds()[i];
    for (const Point2 &p : cell.v) ext[4] = std::max(ext[4], std::hypot(p[0] - s[0], p[1] - s[1]));
    if (ring.points.size() < 3) {
      vanished = std::min(vanished, (PetscInt)i);
      continue;
    }
    ForEachRingNode(ring, poly.bar_length, [&](PetscReal x, PetscReal y) {
      nodes[i - i0]++;
      ext[0] = std::max(ext[0], -x), ext[1] = std::max(ext[1], -y), ext[2] = std::max(ext[2], x), ext[3] = std::max(ext[3], y);
    });
  }
  PetscCall(AgreeOnError(comm, e, "building the Voronoi tissue's cells"));
  PetscCall(MinOverRanks(comm, &vanished));
  if (vanished < (PetscInt)N) { /* the first cell that vanished, named alike on every rank */
    PetscCall(cells_.Cell((size_t)vanished, &cell, &scratch));
    PetscCall(VanishedCell(comm, spec, poly, (size_t)vanished, cell));
  }
  PetscCall(MaxOverRanks(comm, ext, 5));
  lo_[0] = -ext[0], lo_[1] = -ext[1], hi_[0] = ext[2], hi_[1] = ext[3];
  radius_ = ext[4];
  node_start_.assign(N + 1, 0);
  PetscCallMPI(MPI_Allgatherv(nodes.data(), count[rank], MPIU_INT, node_start_.data() + 1, count.data(), displ.data(), MPIU_INT, comm));
  for (size_t i = 0; i < N; i++) node_start_[i + 1] += node_start_[i];
  HilbertPlaces(cells_.Seeds(), spec.box, &place_); /* the space order: the Hilbert curve through the seeds */
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode VoronoiGenerator::GeneratePart(MPI_Comm comm, PetscInt c0, PetscInt c1, PetscReal distance, Tissue *part) const
{
  const size_t N = cells_.Size();
  PowerCell    cell, scratch;
  PolygonRing  ring;
  PetscFunctionBeginUser;
  PetscCheck(N == (size_t)spec.cells && node_start_.size() == N + 1 && place_.size() == N, comm, PETSC_ERR_ORDER,
             "VoronoiGenerator::PrepareParts() must come before GeneratePart()");
  PetscCheck(0 <= c0 && c0 <= c1 && c1 <= (PetscInt)N, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "places [%" PetscInt_FMT ", %" PetscInt_FMT ") of a Voronoi tissue of %zu cells", c0, c1, N);
  PetscCheck(distance >= 0 && std::isfinite(distance), comm, PETSC_ERR_ARG_OUTOFRANGE, "a part's distance must be finite and >= 0 (got %g)", (double)distance);
  PolygonPart T(part, poly.bar_radius);
  if (c0 < c1) {
    /* the box of the part's own rings, grown by the distance and the farthest corner of any power
       cell from its seed: a cell whose ring's box comes within the distance of it has its seed inside
       (the ring lies in its power cell), so the seeds inside are every cell the part needs (and some
       more: the halo takes those within the distance of one of the rank's cells) */
    PetscReal box[4] = {PETSC_MAX_REAL, PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
    for (size_t i = 0; i < N; i++) {
      if (place_[i] < c0 || place_[i] >= c1) continue;
      PetscCall(Ring(i, &ring, &cell, &scratch));
      for (const Point2 &p : ring.points)
        box[0] = std::min(box[0], p[0]), box[1] = std::min(box[1], p[1]), box[2] = std::max(box[2], p[0]), box[3] = std::max(box[3], p[1]);
    }
    const PetscReal grow = distance + radius_ + 1e-9 * (hi_[0] - lo_[0] + hi_[1] - lo_[1]); /* and the rounding of the nodes between corners */
    for (size_t i = 0; i < N; i++) {
      const Point2 &s = cells_.Seeds()[i];
      if (!(place_[i] >= c0 && place_[i] < c1) && !(s[0] >= box[0] - grow && s[0] <= box[2] + grow && s[1] >= box[1] - grow && s[1] <= box[3] + grow)) continue;
      PetscCall(Ring(i, &ring, &cell, &scratch));
      const PetscInt nodes = node_start_[i + 1] - node_start_[i]; /* closed rings: a bar a node */
      PetscCheck(T.Add(ring, poly.node_mass, poly.bar_length, (PetscInt)i, node_start_[i], nodes, node_start_[i], nodes), PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "Voronoi cell %zu: not the %" PetscInt_FMT " nodes counted", i, nodes);
    }
  }
  T.Finish(lo_, hi_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
