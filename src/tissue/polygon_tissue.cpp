/* Shared pieces of the polygonal tissues: the bar radius, node mass and subdivision options, and the
   builder from rings of points to nodes and bars. */
#include <turgor/core/options.h>
#include <turgor/tissue/polygon_tissue.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace turgor {

PetscErrorCode PolygonTissueSpec::SetFromOptions(MPI_Comm comm, bool subdivide, ParameterList *params)
{
  BoxOption cut(cut_box);
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
                                   "PolygonTissueSpec", cut.value, &cut.n, &cut.set));
  PetscOptionsEnd();
  PetscCall(cut.Take(comm, "-tissue_cut_box", BoxShape::MayBeFlat, cut_box, &has_cut_box));
  PetscCheck(std::isfinite(bar_radius) && bar_radius >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_bar_radius = %g: must be finite and >= 0",
             (double)bar_radius);
  PetscCheck(std::isfinite(node_mass) && node_mass > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -tissue_node_mass = %g: a node mass must be finite and > 0",
             (double)node_mass);
  PetscCheck(std::isfinite(bar_length) && bar_length >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_bar_length = %g: must be finite and > 0 (or 0: one bar per polygon edge)", (double)bar_length);
  PetscCall(plates.SetFromOptions(comm, params));
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::string PolygonTissueSpec::BarLengthOption(bool subdivide) const
{
  if (!subdivide || !(bar_length > 0)) return "";
  std::ostringstream s;
  s << " -tissue_bar_length " << bar_length;
  return s.str();
}

std::string PolygonTissueSpec::Description(bool subdivide) const
{
  char buf[160];
  std::snprintf(buf, sizeof buf, "bar radius %g µm, node mass %g ng", (double)bar_radius, (double)node_mass);
  std::string s = buf;
  if (subdivide) {
    std::snprintf(buf, sizeof buf, ", bar length %g µm", (double)bar_length);
    s += buf;
  }
  return s;
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

void AddRingCell(const PolygonRing &R, PetscReal node_mass, PetscReal h, Tissue *tissue)
{
  Tissue      &T = *tissue;
  ParticleSet &P = T.particles;
  PolygonCell  C;
  C.open = R.open;
  ForEachRingNode(R, h, [&](PetscReal x, PetscReal y) { C.nodes.push_back(T.AddParticle(x, y, node_mass, KIND_WALL)); });
  const size_t nn = C.nodes.size(), nbar = R.open ? nn - 1 : nn;
  for (size_t k = 0; k < nbar; k++) {
    C.bars.push_back((PetscInt)P.springs.size());
    T.AddSpring(C.nodes[k], C.nodes[(k + 1) % nn]);
  }
  T.cell_walls.push_back(C.nodes);
  P.polygons.push_back(std::move(C));
}

PolygonPart::PolygonPart(Tissue *part, PetscReal bar_radius) : T_(*part)
{
  T_                      = Tissue();
  T_.particles.bar_radius = bar_radius;
}

bool PolygonPart::Add(const PolygonRing &R, PetscReal node_mass, PetscReal h, PetscInt cell, PetscInt node0, PetscInt nodes, PetscInt bar0, PetscInt bars)
{
  const PetscInt first = T_.particles.n, first_bar = (PetscInt)T_.particles.springs.size();
  AddRingCell(R, node_mass, h, &T_);
  if (T_.particles.n - first != nodes || (PetscInt)T_.particles.springs.size() - first_bar != bars) return false;
  for (PetscInt k = 0; k < nodes; k++) gid_.push_back(node0 + k);
  for (PetscInt k = 0; k < bars; k++) spring_gid_.push_back(bar0 + k);
  T_.cell_gid.push_back(cell);
  return true;
}

void PolygonPart::Finish(const PetscReal lo[2], const PetscReal hi[2])
{
  ParticleSet &P = T_.particles;
  if (P.n > 0) {
    P.node_polygon.assign(P.n, -1);
    for (size_t c = 0; c < P.polygons.size(); c++)
      for (PetscInt i : P.polygons[c].nodes) P.node_polygon[i] = (PetscInt)c;
    P.polygon_gid = T_.cell_gid;
    T_.Finalize();
    P.gid.swap(gid_);
    P.spring_gid.swap(spring_gid_);
  }
  for (int d = 0; d < 2; d++) T_.lo[d] = lo[d], T_.hi[d] = hi[d];
}

PetscErrorCode BuildPolygonTissue(MPI_Comm comm, const std::vector<PolygonRing> &cells, const PolygonTissueSpec &spec, bool subdivide, Tissue *tissue)
{
  std::vector<PolygonRing> rings;
  size_t                   closed = 0, cut = 0;
  PetscFunctionBeginUser;
  for (const PolygonRing &R : cells) { /* the notch: closed cells whose centroid is in the cut box are left out */
    if (!R.open) closed++;
    if (spec.has_cut_box && !R.open && R.points.size() >= 3) {
      const Point2 c = RingCentroid(R.points);
      if (InBox(spec.cut_box, c[0], c[1])) {
        cut++;
        continue;
      }
    }
    rings.push_back(R);
  }
  /* a notch that takes every cell leaves nothing to simulate (an empty tissue would run to the end) */
  PetscCheck(cut == 0 || cut < closed, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -tissue_cut_box = %g,%g,%g,%g: removes all %zu closed cells of the tissue (their centroids are all inside it); a notch must leave some",
             (double)spec.cut_box[0], (double)spec.cut_box[1], (double)spec.cut_box[2], (double)spec.cut_box[3], closed);
  std::vector<std::pair<std::string, PetscInt>> names;
  PetscCall(AddPlateRings(comm, spec.plates, spec.bar_radius, &rings, &names));
  *tissue        = Tissue();
  Tissue &T      = *tissue;
  T.named_cells  = names;
  ParticleSet &P = T.particles;
  P.bar_radius   = spec.bar_radius;
  for (const PolygonRing &R : rings) AddRingCell(R, spec.node_mass, subdivide && !R.whole ? spec.bar_length : 0, &T);
  P.node_polygon.assign(P.n, -1);
  for (size_t c = 0; c < P.polygons.size(); c++)
    for (PetscInt i : P.polygons[c].nodes) P.node_polygon[i] = (PetscInt)c;
  T.Finalize();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
