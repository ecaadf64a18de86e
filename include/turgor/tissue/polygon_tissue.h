#pragma once
/* What the polygonal tissues (-tissue_type node_file, voronoi, polyline) share: the bar radius,
   the node mass and the bar subdivision (PolygonTissueSpec), the builder that turns rings of points
   into nodes, bars and PolygonCells, and the planar geometry their checks use. */
#include <turgor/core/parameters.h>
#include <turgor/tissue/plates.h>
#include <turgor/tissue/tissue.h>
#include <array>
#include <cstddef>

namespace turgor {

/* Options -tissue_bar_radius, -tissue_node_mass, -tissue_bar_length (prefix tissue_). Units µm, ng. */
struct PolygonTissueSpec {
  PetscReal bar_radius = 0.5;    /* µm: a node is a disk, a bar a capsule of this radius */
  PetscReal node_mass  = 0.5;    /* ng, every node */
  PetscReal bar_length = 0;      /* µm: each polygon edge is cut into bars of at most this length; 0: one bar per edge */
  PlateSpec plates;              /* -tissue_plates: plates along the sides, added after the tissue's cells */
  bool      has_cut_box = false; /* -tissue_cut_box: cells whose centroid is inside are removed (a notch) */
  PetscReal cut_box[4]  = {0, 0, 0, 0};

  /* `subdivide`: the generator honours -tissue_bar_length (the polyline, whose node count is given,
     leaves it unread so that a stray one is reported as unused). */
  PetscErrorCode SetFromOptions(MPI_Comm comm, bool subdivide, ParameterList *params = nullptr);
};

using Point2 = std::array<PetscReal, 2>;

/* A cell before it becomes nodes: its corner points in order (closed rings counter-clockwise). */
struct PolygonRing {
  std::vector<Point2> points;
  bool                open  = false;
  bool                whole = false; /* never subdivided (a plate: one bar) */
};

/* Bars an edge of length L is cut into: ceil(L / h), at least 1 (h <= 0: 1). */
PetscReal BarsPerEdge(PetscReal L, PetscReal h);
/* Nodes (= bars for a closed ring) after subdivision, in floating point (estimates). */
PetscReal RingNodeCount(const PolygonRing &ring, PetscReal h);

/* Fill *tissue from the rings and the plates of spec.plates (plates.h): nodes (KIND_WALL, mass
   spec.node_mass) cell by cell in ring order, each edge cut into BarsPerEdge(L, h) equal bars
   (h = spec.bar_length if `subdivide`, else none), bars as springs with the geometric rest length,
   ParticleSet::polygons/node_polygon/bar_radius, Tissue::cell_walls and named_cells; then
   Tissue::Finalize(). */
void BuildPolygonTissue(const std::vector<PolygonRing> &rings, const PolygonTissueSpec &spec, bool subdivide, Tissue *tissue);

/* Signed area (counter-clockwise positive) and centroid of a closed ring. */
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

} // namespace turgor
