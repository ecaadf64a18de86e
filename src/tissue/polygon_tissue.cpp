/* Shared pieces of the polygonal tissues: the bar radius, node mass and subdivision options, the
   builder from rings of points to nodes and bars, and the planar geometry of their checks. */
#include <turgor/core/options.h>
#include <turgor/tissue/polygon_tissue.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode PolygonTissueSpec::SetFromOptions(MPI_Comm comm, bool subdivide, ParameterList *params)
{
  PetscReal box[5] = {0, 0, 0, 0, 0};
  PetscInt  nbox   = 5;
  PetscBool set_box;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "tissue_", "Polygonal cells of nodes and bars (node_file, voronoi, polyline; units µm, ng)", "turgor");
  PetscCall(TurgorOptionsReal(params, "-bar_radius", "Bar radius r [µm]: nodes are disks and bars capsules of radius r; neighbouring polygons are 2 r apart",
                              "PolygonTissueSpec", bar_radius, &bar_radius, NULL));
  PetscCall(TurgorOptionsReal(params, "-node_mass", "Mass of every node [ng]", "PolygonTissueSpec", node_mass, &node_mass, NULL));
  if (subdivide)
    PetscCall(TurgorOptionsReal(params, "-bar_length", "Longest bar [µm]: polygon edges are cut into equal bars no longer than this (0: one bar per edge)",
                                "PolygonTissueSpec", bar_length, &bar_length, NULL));
  PetscCall(TurgorOptionsRealArray(params, "-cut_box",
                                   "xmin,ymin,xmax,ymax [µm]: the closed cells whose centroid is inside are removed (a notch cut out of the tissue)",
                                   "PolygonTissueSpec", box, &nbox, &set_box));
  PetscOptionsEnd();
  PetscCall(CheckNotEmpty(comm, "-tissue_cut_box", "xmin,ymin,xmax,ymax"));
  if (set_box) {
    PetscCheck(nbox == 4, comm, PETSC_ERR_ARG_SIZ, "Option -tissue_cut_box: %" PetscInt_FMT " values given, expected 4 (xmin,ymin,xmax,ymax)", nbox);
    PetscCheck(std::isfinite(box[0]) && std::isfinite(box[1]) && std::isfinite(box[2]) && std::isfinite(box[3]) && box[0] <= box[2] && box[1] <= box[3], comm,
               PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_cut_box = %g,%g,%g,%g: needs finite values with xmin <= xmax and ymin <= ymax", (double)box[0],
               (double)box[1], (double)box[2], (double)box[3]);
    has_cut_box = true;
    for (int k = 0; k < 4; k++) cut_box[k] = box[k];
  }
  PetscCheck(std::isfinite(bar_radius) && bar_radius >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_bar_radius = %g: must be finite and >= 0",
             (double)bar_radius);
  PetscCheck(std::isfinite(node_mass) && node_mass > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_node_mass = %g: a node mass must be finite and > 0",
             (double)node_mass);
  PetscCheck(std::isfinite(bar_length) && bar_length >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_bar_length = %g: must be finite and > 0 (or 0: one bar per polygon edge)", (double)bar_length);
  PetscCall(plates.SetFromOptions(comm, params));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal BarsPerEdge(PetscReal L, PetscReal h)
{
  if (!(h > 0)) return 1;
  return std::max((PetscReal)1, std::ceil(L / h * (1 - 1e-12))); /* an edge of exactly k h is k bars, not k + 1 */
}

PetscReal RingNodeCount(const PolygonRing &ring, PetscReal h)
{
  const size_t n = ring.points.size(), m = ring.open ? n - 1 : n;
  PetscReal    c = ring.open ? 1 : 0;
  for (size_t k = 0; k < m; k++) {
    const Point2 &a = ring.points[k], &b = ring.points[(k + 1) % n];
    c += BarsPerEdge(std::hypot(b[0] - a[0], b[1] - a[1]), h);
  }
  return c;
}

void BuildPolygonTissue(const std::vector<PolygonRing> &cells, const PolygonTissueSpec &spec, bool subdivide, Tissue *tissue)
{
  std::vector<PolygonRing> rings;
  for (const PolygonRing &R : cells) { /* the notch: closed cells whose centroid is in the cut box are left out */
    if (spec.has_cut_box && !R.open && R.points.size() >= 3) {
      const Point2 c = RingCentroid(R.points);
      if (c[0] >= spec.cut_box[0] && c[0] <= spec.cut_box[2] && c[1] >= spec.cut_box[1] && c[1] <= spec.cut_box[3]) continue;
    }
    rings.push_back(R);
  }
  std::vector<std::pair<std::string, PetscInt>> names;
  AddPlateRings(spec.plates, spec.bar_radius, &rings, &names);
  *tissue        = Tissue();
  Tissue &T      = *tissue;
  T.named_cells  = names;
  ParticleSet &P = T.particles;
  P.bar_radius   = spec.bar_radius;
  P.polygons.resize(rings.size());
  for (size_t c = 0; c < rings.size(); c++) {
    const PolygonRing &R = rings[c];
    PolygonCell       &C = P.polygons[c];
    C.open               = R.open;
    const size_t    n = R.points.size(), m = R.open ? n - 1 : n;
    const PetscReal h = subdivide && !R.whole ? spec.bar_length : 0;
    for (size_t k = 0; k < m; k++) {
      const Point2  &a = R.points[k], &b = R.points[(k + 1) % n];
      const PetscInt nb = (PetscInt)BarsPerEdge(std::hypot(b[0] - a[0], b[1] - a[1]), h);
      for (PetscInt t = 0; t < nb; t++) {
        const PetscReal s = (PetscReal)t / (PetscReal)nb;
        C.nodes.push_back(T.AddParticle(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), spec.node_mass, KIND_WALL));
      }
    }
    if (R.open) C.nodes.push_back(T.AddParticle(R.points[n - 1][0], R.points[n - 1][1], spec.node_mass, KIND_WALL));
    const size_t nn = C.nodes.size(), nbar = R.open ? nn - 1 : nn;
    for (size_t k = 0; k < nbar; k++) {
      C.bars.push_back((PetscInt)P.springs.size());
      T.AddSpring(C.nodes[k], C.nodes[(k + 1) % nn]);
    }
    T.cell_walls.push_back(C.nodes);
  }
  P.node_polygon.assign(P.n, -1);
  for (size_t c = 0; c < P.polygons.size(); c++)
    for (PetscInt i : P.polygons[c].nodes) P.node_polygon[i] = (PetscInt)c;
  T.Finalize();
}

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
  const PetscReal ux = b[0] - a[0], uy = b[1] - a[1], L2 = ux * ux + uy * uy;
  PetscReal       t = L2 > 0 ? ((q[0] - a[0]) * ux + (q[1] - a[1]) * uy) / L2 : 0;
  t                 = std::min((PetscReal)1, std::max((PetscReal)0, t));
  return std::hypot(q[0] - a[0] - t * ux, q[1] - a[1] - t * uy);
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

} // namespace turgor
