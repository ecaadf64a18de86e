/* Plane geometry (geometry.h): what is not small enough to be inline. */
#include <turgor/core/geometry.h>
#include <cstdint>
#include <cmath>

namespace turgor {

PetscReal RingSignedArea(const std::vector<Point2> &p)
{
  /* relative to the first point: the cancellation of the shoelace formula scales with |x|, not the cell */
  PetscReal a = 0;
  for (size_t k = 1; k + 1 < p.size(); k++) {
    const PetscReal ux = p[k][0] - p[0][0], uy = p[k][1] - p[0][1], vx = p[k + 1][0] - p[0][0], vy = p[k + 1][1] - p[0][1];
    a += ux * vy - uy * vx;
  }
  return 0.5 * a;
}

Point2 RingCentroid(const std::vector<Point2> &p)
{
  PetscReal a = 0, cx = 0, cy = 0;
  for (size_t k = 1; k + 1 < p.size(); k++) {
    const PetscReal ux = p[k][0] - p[0][0], uy = p[k][1] - p[0][1], vx = p[k + 1][0] - p[0][0], vy = p[k + 1][1] - p[0][1];
    const PetscReal t = ux * vy - uy * vx;
    a += t;
    cx += t * (ux + vx);
    cy += t * (uy + vy);
  }
  if (a == 0) return p.empty() ? Point2{0, 0} : p[0];
  return {p[0][0] + cx / (3 * a), p[0][1] + cy / (3 * a)};
}

static PetscReal Orient(const Point2 &a, const Point2 &b, const Point2 &c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static bool OnSegment(const Point2 &a, const Point2 &b, const Point2 &q) /* q collinear with ab */
{
  return std::min(a[0], b[0]) <= q[0] && q[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= q[1] && q[1] <= std::max(a[1], b[1]);
}

bool SegmentsIntersect(const Point2 &a, const Point2 &b, const Point2 &c, const Point2 &d)
{
  const PetscReal o1 = Orient(a, b, c), o2 = Orient(a, b, d), o3 = Orient(c, d, a), o4 = Orient(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && OnSegment(a, b, c)) || (o2 == 0 && OnSegment(a, b, d)) || (o3 == 0 && OnSegment(c, d, a)) || (o4 == 0 && OnSegment(c, d, b));
}

static PetscReal PointSegmentDistance(const Point2 &q, const Point2 &a, const Point2 &b)
{
  return std::sqrt(PointSegmentDistance2(q.data(), a.data(), b.data()));
}

PetscReal SegmentDistance(const Point2 &a, const Point2 &b, const Point2 &c, const Point2 &d)
{
  if (SegmentsIntersect(a, b, c, d)) return 0;
  return std::min(std::min(PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d)),
                  std::min(PointSegmentDistance(c, a, b), PointSegmentDistance(d, a, b)));
}

bool FindSelfIntersection(const std::vector<Point2> &p, bool open, size_t *e1, size_t *e2)
{
  const size_t n = p.size(), m = open ? (n ? n - 1 : 0) : n;
  auto         adjacent = [&](size_t k, size_t l) { return l == k + 1 || (!open && k == 0 && l == m - 1); };
  /* consecutive edges meet at their shared node; they overlap only when the second folds back */
  for (size_t k = 0; k + (open ? 1 : 0) < m; k++) {
    const size_t    l = (k + 1) % m;
    const Point2   &a = p[k], &b = p[(k + 1) % n], &c = p[(k + 2) % n];
    const PetscReal ux = a[0] - b[0], uy = a[1] - b[1], vx = c[0] - b[0], vy = c[1] - b[1];
    if (m > 1 && ux * vy - uy * vx == 0 && ux * vx + uy * vy > 0) {
      *e1 = std::min(k, l);
      *e2 = std::max(k, l);
      return true;
    }
  }
  auto check = [&](size_t k, size_t l) {
    if (k > l) std::swap(k, l);
    if (k == l || adjacent(k, l)) return false;
    if (!SegmentsIntersect(p[k], p[(k + 1) % n], p[l], p[(l + 1) % n])) return false;
    *e1 = k;
    *e2 = l;
    return true;
  };
  if (m <= 32) {
    for (size_t k = 0; k < m; k++)
      for (size_t l = k + 2; l < m; l++)
        if (check(k, l)) return true;
    return false;
  }
  /* a grid of about m cells over the bounding box; each edge is listed in every cell its box meets */
  PetscReal lo[2] = {p[0][0], p[0][1]}, hi[2] = {p[0][0], p[0][1]};
  for (const Point2 &q : p)
    for (int d = 0; d < 2; d++) {
      lo[d] = std::min(lo[d], q[d]);
      hi[d] = std::max(hi[d], q[d]);
    }
  const PetscReal                  w  = std::max(hi[0] - lo[0], hi[1] - lo[1]) * (1 + 1e-12) + 1e-300;
  const size_t                     g  = std::max((size_t)1, (size_t)std::sqrt((double)m));
  const PetscReal                  cs = w / (PetscReal)g;
  std::vector<std::vector<size_t>> bins(g * g);
  auto                             idx = [&](PetscReal x, int d) { return std::min(g - 1, (size_t)std::max((PetscReal)0, (x - lo[d]) / cs)); };
  for (size_t k = 0; k < m; k++) {
    const Point2 &a = p[k], &b = p[(k + 1) % n];
    for (size_t ix = idx(std::min(a[0], b[0]), 0); ix <= idx(std::max(a[0], b[0]), 0); ix++)
      for (size_t iy = idx(std::min(a[1], b[1]), 1); iy <= idx(std::max(a[1], b[1]), 1); iy++) bins[iy * g + ix].push_back(k);
  }
  for (const std::vector<size_t> &bin : bins)
    for (size_t s = 0; s < bin.size(); s++)
      for (size_t t = s + 1; t < bin.size(); t++)
        if (check(bin[s], bin[t])) return true;
  return false;
}

bool PointInRing(const Point2 &q, const std::vector<Point2> &p)
{
  bool         in = false;
  const size_t n  = p.size();
  for (size_t k = 0, j = n - 1; k < n; j = k++) {
    const Point2 &a = p[k], &b = p[j];
    if ((a[1] > q[1]) != (b[1] > q[1]) && q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

/* The index of (x, y) in [0, n)^2 along the Hilbert curve of order log2 n: quadrant by quadrant from
   the coarsest, each quadrant's sub-square turned so that the curve runs on without a jump. */
static std::uint64_t HilbertIndex(std::uint64_t n, std::uint64_t x, std::uint64_t y)
{
  std::uint64_t d = 0;
  for (std::uint64_t s = n / 2; s > 0; s /= 2) {
    const std::uint64_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = n - 1 - x;
        y = n - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

void HilbertPlaces(const std::vector<Point2> &points, const PetscReal box[4], std::vector<PetscInt> *place)
{
  const std::uint64_t        n = 1 << 16;
  const size_t               N = points.size();
  const PetscReal            W = box[2] - box[0], H = box[3] - box[1];
  std::vector<std::uint64_t> key(N);
  std::vector<PetscInt>      order(N);
  auto                       grid = [&](PetscReal t) { return (std::uint64_t)std::min((PetscReal)(n - 1), std::max((PetscReal)0, t * (PetscReal)n)); };
  for (size_t i = 0; i < N; i++) {
    const Point2 &p = points[i];
    key[i]          = HilbertIndex(n, grid(W > 0 ? (p[0] - box[0]) / W : 0), grid(H > 0 ? (p[1] - box[1]) / H : 0));
    order[i]        = (PetscInt)i;
  }
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  place->resize(N);
  for (size_t k = 0; k < N; k++) (*place)[(size_t)order[k]] = (PetscInt)k;
}

} // namespace turgor
