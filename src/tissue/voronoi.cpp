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

PetscErrorCode ComputePowerDiagram(const PetscReal box[4], const std::vector<Point2> &seeds, const std::vector<PetscReal> &weights,
                                   std::vector<PowerCell> *cells)
{
  const size_t    N = seeds.size();
  const PetscReal W = box[2] - box[0], H = box[3] - box[1], hg = std::sqrt(W * H / (PetscReal)N);
  const PetscInt  gx = std::max((PetscInt)1, (PetscInt)(W / hg)), gy = std::max((PetscInt)1, (PetscInt)(H / hg));
  const PetscReal cw = W / (PetscReal)gx, ch = H / (PetscReal)gy, hmin = std::min(cw, ch);
  const PetscReal wmax    = weights.empty() ? 0 : *std::max_element(weights.begin(), weights.end());
  auto            w       = [&](size_t i) { return weights.empty() ? (PetscReal)0 : weights[i]; };
  auto            cell_of = [&](const Point2 &p, PetscInt *ix, PetscInt *iy) {
    *ix = std::min(gx - 1, std::max((PetscInt)0, (PetscInt)((p[0] - box[0]) / cw)));
    *iy = std::min(gy - 1, std::max((PetscInt)0, (PetscInt)((p[1] - box[1]) / ch)));
  };
  PetscFunctionBeginUser;
  /* seeds binned on the grid (counting sort: a seed's order in its bin is its index order) */
  std::vector<PetscInt> start((size_t)(gx * gy + 1), 0), bin(N);
  for (size_t i = 0; i < N; i++) {
    PetscInt ix, iy;
    cell_of(seeds[i], &ix, &iy);
    start[(size_t)(iy * gx + ix) + 1]++;
  }
  for (size_t b = 0; b < (size_t)(gx * gy); b++) start[b + 1] += start[b];
  {
    std::vector<PetscInt> fill(start.begin(), start.end() - 1);
    for (size_t i = 0; i < N; i++) {
      PetscInt ix, iy;
      cell_of(seeds[i], &ix, &iy);
      bin[(size_t)fill[(size_t)(iy * gx + ix)]++] = (PetscInt)i;
    }
  }
  cells->assign(N, PowerCell());
  PowerCell c, scratch;
  for (size_t i = 0; i < N; i++) {
    const Point2 s = seeds[i];
    c.v            = {
                 {box[0] - s[0], box[1] - s[1]},
                 {box[2] - s[0], box[1] - s[1]},
                 {box[2] - s[0], box[3] - s[1]},
                 {box[0] - s[0], box[3] - s[1]}
    };
    c.label = {-1, -2, -3, -4};
    PetscInt ix, iy;
    cell_of(s, &ix, &iy);
    for (PetscInt k = 0; !c.v.empty(); k++) {
      for (PetscInt jy = iy - k; jy <= iy + k; jy++) {
        if (jy < 0 || jy >= gy) continue;
        const bool edge_row = (jy == iy - k || jy == iy + k);
        for (PetscInt jx = ix - k; jx <= ix + k; jx += (edge_row || k == 0) ? 1 : 2 * k) {
          if (jx < 0 || jx >= gx) continue;
          for (PetscInt t = start[(size_t)(jy * gx + jx)]; t < start[(size_t)(jy * gx + jx) + 1] && !c.v.empty(); t++) {
            const size_t j = (size_t)bin[(size_t)t];
            if (j == i) continue;
            const PetscReal dx = seeds[j][0] - s[0], dy = seeds[j][1] - s[1], d2 = dx * dx + dy * dy;
            PetscCheck(d2 > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Voronoi seeds %zu and %zu coincide at (%g, %g)", i, j, (double)s[0], (double)s[1]);
            /* power bisector in coordinates relative to seed i: 2 y . d <= |d|^2 + w_i - w_j */
            Clip(c, dx, dy, 0.5 * (d2 + w(i) - w(j)), (PetscInt)j, scratch);
          }
        }
      }
      /* every seed not yet visited is at least D = k hmin away; it can cut the cell only if its
         bisector, at distance (D^2 + w_i - w_j) / (2 D) >= (D^2 + w_i - wmax) / (2 D), is nearer than
         the cell's farthest vertex R (the bound grows with D, so the first D that passes ends it) */
      const PetscReal D = (PetscReal)k * hmin, R = Radius(c);
      if ((D > 0 && D * D + w(i) - wmax >= 2 * R * D) || (k > gx && k > gy)) break;
    }
    for (Point2 &p : c.v) {
      p[0] += s[0];
      p[1] += s[1];
    }
    (*cells)[i] = c;
  }
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

PetscErrorCode BuildVoronoiDiagram(MPI_Comm comm, const VoronoiSpec &spec, VoronoiDiagram *diagram)
{
  VoronoiDiagram &D = *diagram;
  const size_t    N = (size_t)spec.cells;
  const PetscReal W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  UniformRandom   u(spec.seed);
  PetscFunctionBeginUser;
  D = VoronoiDiagram();
  D.seeds.resize(N);
  for (Point2 &s : D.seeds) {
    const PetscReal x = u(), y = u();
    s = {spec.box[0] + W * x, spec.box[1] + H * y};
  }
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
    if (spec.size_cv > 0) PetscCall(AdaptWeights(comm, spec.box, D));
    else PetscCall(ComputePowerDiagram(spec.box, D.seeds, D.weights, &D.cells));
    if (step == spec.lloyd_steps) break;
    for (size_t i = 0; i < N; i++)
      if (!D.cells[i].v.empty()) {
        const Point2 c = RingCentroid(D.cells[i].v);
        D.seeds[i]     = {std::min(spec.box[2], std::max(spec.box[0], c[0])), std::min(spec.box[3], std::max(spec.box[1], c[1]))};
      }
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

PetscErrorCode GenerateVoronoiTissue(MPI_Comm comm, const VoronoiSpec &spec, const PolygonTissueSpec &poly, Tissue *tissue, VoronoiDiagram *diagram)
{
  VoronoiDiagram local, &D = diagram ? *diagram : local;
  PetscLogEvent  ev;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgVoronoi", PETSC_OBJECT_CLASSID, &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCall(BuildVoronoiDiagram(comm, spec, &D));
  const PetscReal          W = spec.box[2] - spec.box[0], H = spec.box[3] - spec.box[1];
  const PetscReal          min_edge = std::max(poly.bar_radius, 1e-9 * std::sqrt(W * H / (PetscReal)spec.cells));
  std::vector<PolygonRing> rings(D.cells.size());
  for (size_t i = 0; i < D.cells.size(); i++) {
    ShrinkPowerCell(D.cells[i], poly.bar_radius + 0.5 * spec.gap, min_edge, &rings[i].points);
    PetscCheck(rings[i].points.size() >= 3, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Options -tissue_bar_radius = %g, -tissue_gap = %g: Voronoi cell %zu (area %g µm^2) vanishes when shrunk by the bar radius and half the gap "
               "(-tissue_voronoi_cells %" PetscInt_FMT " in a %g x %g box: cells of about %g µm); use a smaller radius or gap, or fewer cells",
               (double)poly.bar_radius, (double)spec.gap, i, D.cells[i].v.empty() ? 0.0 : (double)RingSignedArea(D.cells[i].v), spec.cells, (double)W,
               (double)H, (double)std::sqrt(W * H / (PetscReal)spec.cells));
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

} // namespace turgor
