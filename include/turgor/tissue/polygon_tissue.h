#pragma once
/* What the polygonal tissues (-tissue_type node_file, voronoi, polyline) share: the bar radius,
   the node mass and the bar subdivision (PolygonTissueSpec), the builder that turns rings of points
   into nodes, bars and PolygonCells. Their plane geometry is core/geometry.h's. */
#include <turgor/core/geometry.h>
#include <turgor/tissue/plates.h>
#include <turgor/tissue/tissue.h>
#include <turgor/tissue/tissue_generator.h>
#include <cmath>
#include <cstddef>
#include <string>

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
  /* For messages: " -tissue_bar_length h" where the edges are cut into bars (else ""), and "bar
     radius r µm, node mass m ng[, bar length h µm]". */
  std::string BarLengthOption(bool subdivide) const;
  std::string Description(bool subdivide) const;
};

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

/* The nodes of a ring in order, each edge cut into BarsPerEdge(L, h) equal bars: f(x, y) for every
   node (an open ring's last point too). */
template <class F>
void ForEachRingNode(const PolygonRing &R, PetscReal h, F &&f)
{
  const size_t n = R.points.size(), m = R.open ? n - 1 : n;
  for (size_t k = 0; k < m; k++) {
    const Point2  &a = R.points[k], &b = R.points[(k + 1) % n];
    const PetscInt nb = (PetscInt)BarsPerEdge(std::hypot(b[0] - a[0], b[1] - a[1]), h);
    for (PetscInt t = 0; t < nb; t++) {
      const PetscReal s = (PetscReal)t / (PetscReal)nb;
      f(a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]));
    }
  }
  if (R.open) f(R.points[n - 1][0], R.points[n - 1][1]);
}

/* Append ring R as a cell of *tissue: its nodes (KIND_WALL, mass node_mass; ForEachRingNode), its
   bars as springs with the geometric rest length, its PolygonCell and wall ring. */
void AddRingCell(const PolygonRing &R, PetscReal node_mass, PetscReal h, Tissue *tissue);

/* A part of a polygonal tissue being built (TissueGenerator::GeneratePart): cells added in increasing
   number of the whole tissue, each with its first node and bar there; Finish() gives the part its
   numbers (ParticleSet::gid, spring_gid, polygon_gid, Tissue::cell_gid), joints and the whole
   tissue's bounds. */
class PolygonPart {
public:
  PolygonPart(Tissue *part, PetscReal bar_radius);
  /* ring R as cell `cell` of the whole tissue (AddRingCell), its nodes numbered from node0 and its
     bars from bar0 there; false if it has other than `nodes` nodes and `bars` bars (the whole
     tissue's count) */
  bool Add(const PolygonRing &R, PetscReal node_mass, PetscReal h, PetscInt cell, PetscInt node0, PetscInt nodes, PetscInt bar0, PetscInt bars);
  void Finish(const PetscReal lo[2], const PetscReal hi[2]);

private:
  Tissue               &T_;
  std::vector<PetscInt> gid_, spring_gid_;
};

/* Fill *tissue from the rings and the plates of spec.plates (plates.h): nodes (KIND_WALL, mass
   spec.node_mass) cell by cell in ring order, each edge cut into BarsPerEdge(L, h) equal bars
   (h = spec.bar_length if `subdivide`, else none), bars as springs with the geometric rest length,
   ParticleSet::polygons/node_polygon/bar_radius, Tissue::cell_walls and named_cells; then
   Tissue::Finalize(). Refused (errors naming the option): a -tissue_cut_box that removes every closed
   cell, plates that would have no length (plates.h). */
PetscErrorCode BuildPolygonTissue(MPI_Comm comm, const std::vector<PolygonRing> &rings, const PolygonTissueSpec &spec, bool subdivide, Tissue *tissue);

/* What the polygonal generators (node_file, voronoi, polyline) share: their own Spec and the
   PolygonTissueSpec, read in that order (the shared options first), and the shared spec's part of
   their messages. `Subdivides`: the generator cuts polygon edges into bars of -tissue_bar_length
   (the polyline, whose node count is given, does not: the option is then left unread, so that a
   stray one is reported as unused). */
template <class Spec, bool Subdivides = true>
class PolygonGenerator : public TissueGenerator {
public:
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) override
  {
    PetscFunctionBeginUser;
    PetscCall(poly.SetFromOptions(comm, Subdivides, params));
    PetscCall(spec.SetFromOptions(comm, params));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  Spec              spec;
  PolygonTissueSpec poly;

protected:
  std::string BarLengthOption() const { return poly.BarLengthOption(Subdivides); }
  std::string PolygonDescription() const { return poly.Description(Subdivides); }
};

} // namespace turgor
