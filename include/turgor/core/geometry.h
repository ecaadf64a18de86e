#pragma once
/* Plane geometry shared by the tissue generators, the neighbour search, the force terms, the
   partitioner and the outputs: points, segments, polygons and boxes. The small functions are inline
   (inner loops call them); each is written once, so that every user gets the same bits. */
#include <petscsys.h>
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace turgor {

using Point2 = std::array<PetscReal, 2>;

/* The parameter t in [0, 1] of the point a + t (b - a) of the segment [a, b] closest to p (0 for a
   segment of zero length). p, a, b: x, y pairs. */
inline PetscReal SegmentClosestParameter(const PetscReal *p, const PetscReal *a, const PetscReal *b)
{
  const PetscReal tx = b[0] - a[0], ty = b[1] - a[1], L2 = tx * tx + ty * ty;
  const PetscReal t = L2 > 0 ? ((p[0] - a[0]) * tx + (p[1] - a[1]) * ty) / L2 : 0;
  return std::min((PetscReal)1, std::max((PetscReal)0, t));
}

/* Squared distance from p to the segment [a, b]. */
inline PetscReal PointSegmentDistance2(const PetscReal *p, const PetscReal *a, const PetscReal *b)
{
  const PetscReal t  = SegmentClosestParameter(p, a, b);
  const PetscReal dx = p[0] - a[0] - t * (b[0] - a[0]), dy = p[1] - a[1] - t * (b[1] - a[1]);
  return dx * dx + dy * dy;
}

/* Signed area (counter-clockwise positive) of the closed polygon of the n vertices vertex(0), ...,
   vertex(n - 1) (each a Point2), by the shoelace formula. */
template <class Vertex>
PetscReal PolygonSignedArea(size_t n, Vertex vertex)
{
  PetscReal a = 0;
  for (size_t k = 0; k + 1 < n; k++) { /* the closing edge after the loop: no modulo (a division) per vertex */
    const Point2 p = vertex(k), q = vertex(k + 1);
    a += p[0] * q[1] - q[0] * p[1];
  }
  if (n > 0) {
    const Point2 p = vertex(n - 1), q = vertex(0);
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * a;
}

/* Signed area of the polygon through the points (x[2 i], x[2 i + 1]) of the indices i in ring. */
inline PetscReal PolygonArea(const std::vector<PetscInt> &ring, const PetscReal *x)
{
  return PolygonSignedArea(ring.size(), [&](size_t k) { return Point2{x[2 * ring[k]], x[2 * ring[k] + 1]}; });
}

/* Signed area and centroid of a closed ring, summed relative to its first point: the cancellation
   of the shoelace formula then scales with the ring's size, not with |x| (a generator's rings lie
   far from the origin). */
PetscReal RingSignedArea(const std::vector<Point2> &p);
Point2    RingCentroid(const std::vector<Point2> &p);
/* Do the closed segments ab and cd share a point (touching counts)? */
bool SegmentsIntersect(const Point2 &a, const Point2 &b, const Point2 &c, const Point2 &d);
/* Distance between the segments ab and cd (0 if they intersect). */
PetscReal SegmentDistance(const Point2 &a, const Point2 &b, const Point2 &c, const Point2 &d);
/* Is the ring simple? If not, *e1 < *e2 are two edges (edge k joins p[k] and p[k+1]) that cross or
   touch, or two consecutive edges that fold back onto each other. Uses a grid of the edges, so that
   a ring of n points costs about O(n) rather than O(n^2). */
bool FindSelfIntersection(const std::vector<Point2> &p, bool open, size_t *e1, size_t *e2);
/* Is the point strictly inside the closed ring (crossing number)? */
bool PointInRing(const Point2 &q, const std::vector<Point2> &p);

/* Is (x, y) in the closed box xmin, ymin, xmax, ymax (core/options.h's BoxOption)? */
inline bool InBox(const PetscReal box[4], PetscReal x, PetscReal y)
{
  return x >= box[0] && x <= box[2] && y >= box[1] && y <= box[3];
}

/* The space order of a tissue's cells for dealing them in ranges (-fine_partitioner ranges): each
   cell's point (a seed, a box's centre) on a 2^16 x 2^16 grid over `box` (xmin, ymin, xmax, ymax),
   ordered along the Hilbert curve through the grid, ties by index; place[i] is cell i's place in
   that order. Integer arithmetic after the grid: the same order on every machine. */
void HilbertPlaces(const std::vector<Point2> &points, const PetscReal box[4], std::vector<PetscInt> *place);

} // namespace turgor
