static const char help[] = "Polygonal tissues: Voronoi/Laguerre tiling, shrinking, reproducibility, Lloyd, size cv; node-file round trip "
                           "and errors; polyline.\n";
#include "test_util.h"
#include <turgor/core/uniform_random.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

using namespace turgor;

static std::vector<std::vector<Point2>> Rings(const Tissue &T)
{
  std::vector<std::vector<Point2>> r;
  for (const PolygonCell &c : T.particles.polygons) {
    r.emplace_back();
    for (PetscInt i : c.nodes) r.back().push_back({T.X[2 * i], T.X[2 * i + 1]});
  }
  return r;
}

static PetscReal CV(const std::vector<PetscReal> &a)
{
  PetscReal m = 0, v = 0;
  for (PetscReal x : a) m += x;
  m /= (PetscReal)a.size();
  for (PetscReal x : a) v += (x - m) * (x - m);
  return std::sqrt(v / (PetscReal)a.size()) / m;
}

static std::vector<PetscReal> DiagramAreas(const VoronoiDiagram &D)
{
  std::vector<PetscReal> a;
  for (const PowerCell &c : D.cells) a.push_back(c.v.empty() ? 0 : RingSignedArea(c.v));
  return a;
}

/* Minimal distance between the boundaries of two polygons (bars as segments). */
static PetscReal RingDistance(const std::vector<Point2> &a, const std::vector<Point2> &b)
{
  PetscReal d = PETSC_MAX_REAL;
  for (size_t k = 0; k < a.size(); k++)
    for (size_t l = 0; l < b.size(); l++) d = std::min(d, SegmentDistance(a[k], a[(k + 1) % a.size()], b[l], b[(l + 1) % b.size()]));
  return d;
}

/* The checks every polygonal tissue must pass: consistent bookkeeping, simple counter-clockwise
   closed cells, bars = springs with the geometric rest length. */
static PetscErrorCode CheckBookkeeping(const Tissue &T)
{
  const ParticleSet &P = T.particles;
  PetscFunctionBeginUser;
  TG_CHECK(P.node_polygon.size() == (size_t)P.n, "node_polygon size");
  TG_CHECK(T.cell_walls.size() == P.polygons.size(), "cell_walls");
  size_t nbars = 0;
  for (size_t c = 0; c < P.polygons.size(); c++) {
    const PolygonCell &C = P.polygons[c];
    TG_CHECK(T.cell_walls[c] == C.nodes, "cell_walls[%zu] differs from the polygon", c);
    TG_CHECK(C.bars.size() == (C.open ? C.nodes.size() - 1 : C.nodes.size()), "cell %zu: bar count", c);
    for (size_t k = 0; k < C.bars.size(); k++) {
      const Spring  &s = P.springs[C.bars[k]];
      const PetscInt a = C.nodes[k], b = C.nodes[(k + 1) % C.nodes.size()];
      TG_CHECK(s.i == a && s.j == b, "cell %zu bar %zu joins the wrong nodes", c, k);
      TG_CHECK_CLOSE(s.rest_length, std::hypot(T.X[2 * b] - T.X[2 * a], T.X[2 * b + 1] - T.X[2 * a + 1]), 1e-15, 0, "rest length");
      TG_CHECK(s.rest_length > 0, "zero rest length");
    }
    nbars += C.bars.size();
    for (PetscInt i : C.nodes) TG_CHECK(P.node_polygon[i] == (PetscInt)c && P.kind[i] == KIND_WALL, "node %" PetscInt_FMT " of cell %zu", i, c);
    std::vector<Point2> r;
    for (PetscInt i : C.nodes) r.push_back({T.X[2 * i], T.X[2 * i + 1]});
    size_t e1, e2;
    TG_CHECK(!FindSelfIntersection(r, C.open, &e1, &e2), "cell %zu is not simple (edges %zu, %zu)", c, e1, e2);
    if (!C.open) TG_CHECK(RingSignedArea(r) > 0, "cell %zu is not counter-clockwise", c);
  }
  TG_CHECK(nbars == P.springs.size(), "every spring is a bar");
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestVoronoi()
{
  VoronoiSpec       spec;
  PolygonTissueSpec poly;
  spec.cells      = 400;
  spec.box[2]     = 500;
  spec.box[3]     = 500;
  poly.bar_radius = 0.5;
  Tissue         T;
  VoronoiDiagram D;
  PetscFunctionBeginUser;
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T, &D));
  const PetscReal boxA = 500.0 * 500.0;
  /* 1. the diagram tiles the box */
  PetscReal sum = 0;
  for (PetscReal a : DiagramAreas(D)) {
    TG_CHECK(a > 0, "empty Voronoi cell");
    sum += a;
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "voronoi 400: cell areas sum to the box area within %.2e (relative)\n", std::fabs(sum - boxA) / boxA));
  TG_CHECK_CLOSE(sum, boxA, 1e-10, 0, "sum of Voronoi cell areas = box area");
  /* 2. a second method: points sampled in the box lie in the cell of their nearest seed (brute force) */
  turgor_test::Random rnd(7);
  PetscInt            ambiguous = 0;
  for (int t = 0; t < 4000; t++) {
    const Point2 q    = {250 + 250 * rnd(), 250 + 250 * rnd()};
    size_t       best = 0, second = 0;
    PetscReal    d1 = PETSC_MAX_REAL, d2 = PETSC_MAX_REAL;
    for (size_t i = 0; i < D.seeds.size(); i++) {
      const PetscReal d = std::hypot(q[0] - D.seeds[i][0], q[1] - D.seeds[i][1]);
      if (d < d1) {
        d2     = d1;
        second = best;
        d1     = d;
        best   = i;
      } else if (d < d2) {
        d2     = d;
        second = i;
      }
    }
    (void)second;
    if (d2 - d1 < 1e-9 * d1) {
      ambiguous++;
      continue;
    }
    TG_CHECK(PointInRing(q, D.cells[best].v), "point (%g, %g) is not in the cell of its nearest seed %zu", (double)q[0], (double)q[1], best);
  }
  /* 3. after shrinking: simple, counter-clockwise, inside the box by r, no two overlap, neighbours 2 r apart */
  PetscCall(CheckBookkeeping(T));
  const ParticleSet &P = T.particles;
  TG_CHECK(P.polygons.size() == 400, "400 polygons");
  TG_CHECK(P.bar_radius == 0.5, "bar radius");
  for (PetscInt i = 0; i < P.n; i++)
    TG_CHECK(T.X[2 * i] >= 0.5 - 1e-9 && T.X[2 * i] <= 499.5 + 1e-9 && T.X[2 * i + 1] >= 0.5 - 1e-9 && T.X[2 * i + 1] <= 499.5 + 1e-9,
             "node %" PetscInt_FMT " within r of the box", i);
  const auto             R = Rings(T);
  std::vector<PetscReal> lo(2 * R.size()), hi(2 * R.size());
  for (size_t c = 0; c < R.size(); c++)
    for (int d = 0; d < 2; d++) {
      lo[2 * c + d] = hi[2 * c + d] = R[c][0][d];
      for (const Point2 &p : R[c]) {
        lo[2 * c + d] = std::min(lo[2 * c + d], p[d]);
        hi[2 * c + d] = std::max(hi[2 * c + d], p[d]);
      }
    }
  PetscInt  pairs = 0;
  PetscReal dmin  = PETSC_MAX_REAL;
  for (size_t a = 0; a < R.size(); a++)
    for (size_t b = a + 1; b < R.size(); b++) {
      if (lo[2 * a] > hi[2 * b] + 2 || lo[2 * b] > hi[2 * a] + 2 || lo[2 * a + 1] > hi[2 * b + 1] + 2 || lo[2 * b + 1] > hi[2 * a + 1] + 2) continue;
      pairs++;
      const PetscReal d = RingDistance(R[a], R[b]); /* 0 if a bar of a crosses a bar of b */
      dmin              = std::min(dmin, d);
      TG_CHECK(d >= 1.0 * (1 - 1e-9), "polygons %zu and %zu are %g apart (< 2 r = 1)", a, b, (double)d);
      for (const Point2 &p : R[a]) TG_CHECK(!PointInRing(p, R[b]), "a node of %zu is inside %zu", a, b);
      for (const Point2 &p : R[b]) TG_CHECK(!PointInRing(p, R[a]), "a node of %zu is inside %zu", b, a);
    }
  /* shared edges long enough to survive the offset at their middle. Shrunk without merging short
     edges, the two polygons are exactly 2 r apart there; the tissue merges the corners of edges
     shorter than r into their midpoint, which moves a corner inward by at most r / 2 on each side,
     so there the distance is in [2 r, 3 r] */
  std::vector<std::vector<Point2>> exact(D.cells.size());
  for (size_t i = 0; i < D.cells.size(); i++) ShrinkPowerCell(D.cells[i], poly.bar_radius, 0, &exact[i]);
  PetscInt  shared = 0, off = 0;
  PetscReal worst = 0, worst_merged = 0;
  for (size_t i = 0; i < D.cells.size(); i++) {
    const PowerCell &c = D.cells[i];
    for (size_t k = 0; k < c.v.size(); k++) {
      const PetscInt j = c.label[k];
      if (j <= (PetscInt)i) continue;
      const Point2 &a = c.v[k], &b = c.v[(k + 1) % c.v.size()];
      if (std::hypot(b[0] - a[0], b[1] - a[1]) < 20 * poly.bar_radius) continue;
      shared++;
      worst              = std::max(worst, std::fabs(RingDistance(exact[i], exact[j]) - 1.0));
      const PetscReal dm = RingDistance(R[i], R[j]) - 1.0;
      worst_merged       = std::max(worst_merged, dm);
      off += dm > 1e-9;
      TG_CHECK(dm > -1e-9 && dm <= 0.5 + 1e-9, "cells %zu and %zu: %g apart along their shared edge (2 r = 1)", i, (size_t)j, 1 + (double)dm);
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "voronoi 400: %" PetscInt_FMT " nodes; %" PetscInt_FMT " nearby pairs, closest %.12g (2 r = 1); %" PetscInt_FMT
                        " shared edges >= 20 r: 2 r apart within %.2e without merging; with merging %" PetscInt_FMT " farther, by at most %.3f; %" PetscInt_FMT
                        " of 4000 sample points on a tie\n",
                        P.n, pairs, (double)dmin, shared, (double)worst, off, (double)worst_merged, ambiguous));
  TG_CHECK(shared > 500, "too few long shared edges (%" PetscInt_FMT ")", shared);
  TG_CHECK(worst < 1e-9, "neighbours along a shared edge are not 2 r apart (off by %g)", (double)worst);
  /* 4. the same seed gives the same tissue bit for bit, another seed another tissue */
  Tissue T2, T3;
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T2));
  TG_CHECK(T2.X.size() == T.X.size() && std::memcmp(T2.X.data(), T.X.data(), T.X.size() * sizeof(PetscReal)) == 0, "same seed, different nodes");
  TG_CHECK(T2.particles.springs.size() == P.springs.size(), "same seed, different bars");
  for (size_t s = 0; s < P.springs.size(); s++)
    TG_CHECK(T2.particles.springs[s].i == P.springs[s].i && T2.particles.springs[s].j == P.springs[s].j &&
               T2.particles.springs[s].rest_length == P.springs[s].rest_length,
             "same seed, bar %zu differs", s);
  spec.seed = 2;
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T3));
  TG_CHECK(T3.X.size() != T.X.size() || std::memcmp(T3.X.data(), T.X.data(), T.X.size() * sizeof(PetscReal)) != 0, "seed 2 gives the tissue of seed 1");
  /* 5. the cells in space order: the drawn seeds, numbered along the Hilbert curve through them, so
     that consecutive cells are neighbours or nearly (drawn at random, consecutive seeds would lie
     about 0.52 of the box apart) */
  {
    std::vector<Point2> drawn(400), got = D.seeds;
    UniformRandom       u(1);
    for (Point2 &q : drawn) {
      const PetscReal x = u(), y = u();
      q = {500 * x, 500 * y};
    }
    std::sort(drawn.begin(), drawn.end());
    std::sort(got.begin(), got.end());
    TG_CHECK(drawn == got, "the seeds are not the drawn seeds renumbered");
    std::vector<PetscInt> place;
    HilbertPlaces(D.seeds, spec.box, &place);
    for (size_t i = 0; i < place.size(); i++) TG_CHECK(place[i] == (PetscInt)i, "seed %zu is at place %" PetscInt_FMT " of the Hilbert curve", i, place[i]);
    PetscReal step = 0;
    for (size_t i = 1; i < D.seeds.size(); i++) step += std::hypot(D.seeds[i][0] - D.seeds[i - 1][0], D.seeds[i][1] - D.seeds[i - 1][1]);
    step /= (PetscReal)(D.seeds.size() - 1);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "voronoi 400: consecutive cells' seeds %.1f µm apart on average (cells of 25 µm)\n", (double)step));
    TG_CHECK(step < 40, "consecutive cells' seeds are %g µm apart on average: not in space order", (double)step);
  }
  /* a fingerprint, printed so that other machines can be compared by eye */
  PetscReal fp = 0;
  for (size_t k = 0; k < T.X.size(); k++) fp += T.X[k] * (PetscReal)(k % 7 + 1);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "voronoi 400 seed 1: fingerprint %.17g\n", (double)fp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestLloydAndLaguerre()
{
  VoronoiSpec    spec;
  VoronoiDiagram D0, D1, DL;
  PetscFunctionBeginUser;
  spec.cells = 400;
  PetscCall(BuildVoronoiDiagram(PETSC_COMM_SELF, spec, &D0));
  spec.lloyd_steps = 20;
  PetscCall(BuildVoronoiDiagram(PETSC_COMM_SELF, spec, &D1));
  const PetscReal cv0 = CV(DiagramAreas(D0)), cv1 = CV(DiagramAreas(D1));
  PetscCall(
    PetscPrintf(PETSC_COMM_SELF, "Lloyd: cv of the areas %.4f with 0 steps (Poisson-Voronoi: about 0.53), %.4f with 20 steps\n", (double)cv0, (double)cv1));
  TG_CHECK(cv0 > 0.4 && cv0 < 0.65, "Poisson-Voronoi area cv %g, expected about 0.53", (double)cv0);
  TG_CHECK(cv1 < 0.5 * cv0, "Lloyd steps did not reduce the spread of the areas (%g -> %g)", (double)cv0, (double)cv1);
  /* Laguerre: the areas follow their targets (Newton to a largest relative area error of 1e-6), and
     the targets are a stratified uniform sample whose cv is the request times sqrt(1 - 1/N^2), so the
     measured cv must match the request to 1e-3 (relative) */
  for (PetscReal cv : {0.2, 0.4}) {
    spec.lloyd_steps = 5;
    spec.size_cv     = cv;
    PetscCall(BuildVoronoiDiagram(PETSC_COMM_SELF, spec, &DL));
    const std::vector<PetscReal> A   = DiagramAreas(DL);
    PetscReal                    sum = 0;
    for (PetscReal a : A) {
      TG_CHECK(a > 0, "empty Laguerre cell");
      sum += a;
    }
    TG_CHECK_CLOSE(sum, 400.0 * 400.0, 1e-10, 0, "Laguerre cells tile the box");
    const PetscReal got = CV(A), targets = CV(DL.targets);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "Laguerre cv %.2f: areas cv %.4f, targets cv %.4f, %" PetscInt_FMT " weight iterations, largest area error %.2e\n",
                          (double)cv, (double)got, (double)targets, DL.weight_iterations, (double)DL.max_area_error));
    TG_CHECK(DL.max_area_error < 1e-6, "Laguerre areas missed their targets by %g", (double)DL.max_area_error);
    TG_CHECK_CLOSE(got, targets, 1e-5, 0, "areas cv vs targets cv");
    TG_CHECK_CLOSE(got, cv, 1e-3, 0, "areas cv vs requested cv");
    /* and the tissue from it is still clean */
    Tissue            T;
    PolygonTissueSpec poly;
    PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T));
    PetscCall(CheckBookkeeping(T));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestSubdivision()
{
  VoronoiSpec       spec;
  PolygonTissueSpec poly;
  VoronoiGenerator  gen;
  Tissue            T;
  PetscReal         est, est_s;
  PetscFunctionBeginUser;
  spec.cells      = 100;
  poly.bar_length = 4;
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, spec, poly, &T));
  PetscCall(CheckBookkeeping(T));
  PetscReal longest = 0;
  for (const Spring &s : T.particles.springs) longest = std::max(longest, s.rest_length);
  TG_CHECK(longest <= 4 * (1 + 1e-12), "bar of %g > -tissue_bar_length 4", (double)longest);
  gen.spec = spec;
  gen.poly = poly;
  PetscCall(gen.Estimate(&est, &est_s));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "voronoi 100, bar length 4: %" PetscInt_FMT " nodes, longest bar %.4f, estimate %.0f\n", T.particles.n,
                        (double)longest, (double)est));
  TG_CHECK(est > 0.5 * T.particles.n && est < 2.0 * T.particles.n, "estimate %g vs %" PetscInt_FMT " nodes", (double)est, T.particles.n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ReadNodes(const std::string &path, Tissue *T, std::vector<PetscInt> open = {}, PetscReal scale = 1, PetscReal h = 0)
{
  NodeFileSpec      spec;
  PolygonTissueSpec poly;
  PetscFunctionBeginUser;
  spec.path         = path;
  spec.open_cells   = open;
  spec.length_scale = scale;
  poly.bar_length   = h;
  PetscCall(GenerateNodeFileTissue(PETSC_COMM_SELF, spec, poly, T));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static bool SameTissue(const Tissue &a, const Tissue &b)
{
  const ParticleSet &P = a.particles, &Q = b.particles;
  if (a.X != b.X || P.n != Q.n || P.mass != Q.mass || P.node_polygon != Q.node_polygon || P.springs.size() != Q.springs.size() ||
      P.polygons.size() != Q.polygons.size())
    return false;
  for (size_t s = 0; s < P.springs.size(); s++)
    if (P.springs[s].i != Q.springs[s].i || P.springs[s].j != Q.springs[s].j || P.springs[s].rest_length != Q.springs[s].rest_length) return false;
  for (size_t c = 0; c < P.polygons.size(); c++)
    if (P.polygons[c].nodes != Q.polygons[c].nodes || P.polygons[c].bars != Q.polygons[c].bars || P.polygons[c].open != Q.polygons[c].open) return false;
  return a.cell_walls == b.cell_walls;
}

static PetscErrorCode ExpectFailure(const std::string &name, const std::string &text, std::vector<PetscInt> open = {})
{
  Tissue         T;
  PetscErrorCode ierr;
  PetscFunctionBeginUser;
  {
    std::ofstream f(name);
    f << text;
  }
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = ReadNodes(name, &T, open);
  PetscCall(PetscPopErrorHandler());
  TG_CHECK(ierr != 0, "the node file %s was accepted", name.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestNodeFile(const std::string &data)
{
  Tissue T, T2, T3, Topen, Topen2, Tsub, Tscale;
  PetscFunctionBeginUser;
  const std::string two = data + "/two_cells.nodes";
  PetscCall(ReadNodes(two, &T));
  PetscCall(CheckBookkeeping(T));
  TG_CHECK(T.particles.n == 8 && T.particles.polygons.size() == 2, "two_cells: 8 nodes, 2 cells");
  /* cell 1 was clockwise: reversed from its first node, (11,0) (21,0) (21,10) (11,10) */
  const PetscInt n1 = T.particles.polygons[1].nodes[1];
  TG_CHECK(T.X[2 * n1] == 21 && T.X[2 * n1 + 1] == 0, "cell 1 not reversed");
  TG_CHECK(PolygonArea(T.cell_walls[0], T.X.data()) == 100 && PolygonArea(T.cell_walls[1], T.X.data()) == 100, "areas 100");
  /* write, read, compare: the same tissue bit for bit; and once more (a fixed point) */
  PetscCall(WriteNodeFile(PETSC_COMM_SELF, "two_cells_out.nodes", T));
  PetscCall(ReadNodes("two_cells_out.nodes", &T2));
  TG_CHECK(SameTissue(T, T2), "node file round trip changed the tissue");
  /* a Voronoi tissue (irrational coordinates, 17 digits) round trips too, and an open cell */
  VoronoiSpec       vs;
  PolygonTissueSpec vp;
  vs.cells      = 50;
  vp.bar_length = 7;
  Tissue V, V2;
  PetscCall(GenerateVoronoiTissue(PETSC_COMM_SELF, vs, vp, &V));
  PetscCall(WriteNodeFile(PETSC_COMM_SELF, "voronoi50.nodes", V));
  PetscCall(ReadNodes("voronoi50.nodes", &V2));
  TG_CHECK(SameTissue(V, V2), "Voronoi node file round trip changed the tissue");
  PetscCall(ReadNodes(two, &Topen, {1}));
  PetscCall(CheckBookkeeping(Topen));
  TG_CHECK(Topen.particles.polygons[1].open && !Topen.particles.polygons[0].open && Topen.particles.polygons[1].bars.size() == 3, "open cell 1: 3 bars");
  TG_CHECK(Topen.X[2 * Topen.particles.polygons[1].nodes[1]] == 11 && Topen.X[2 * Topen.particles.polygons[1].nodes[1] + 1] == 10,
           "open cell kept in file order");
  PetscCall(WriteNodeFile(PETSC_COMM_SELF, "two_cells_open.nodes", Topen));
  PetscCall(ReadNodes("two_cells_open.nodes", &Topen2, {1}));
  TG_CHECK(SameTissue(Topen, Topen2), "round trip with an open cell");
  /* subdivision: edges of 10 with bars <= 3 are 4 bars of 2.5; the length scale multiplies */
  PetscCall(ReadNodes(two, &Tsub, {}, 1, 3));
  TG_CHECK(Tsub.particles.n == 32 && Tsub.particles.springs.size() == 32, "subdivided: 32 nodes");
  for (const Spring &s : Tsub.particles.springs) TG_CHECK_CLOSE(s.rest_length, 2.5, 1e-14, 0, "subdivided bar");
  PetscCall(ReadNodes(two, &Tscale, {}, 2.0));
  TG_CHECK_CLOSE(PolygonArea(Tscale.cell_walls[1], Tscale.X.data()), 400, 1e-14, 0, "scaled area");
  NodeFileGenerator gen;
  PetscReal         est, est_s;
  gen.spec.path = two;
  PetscCall(gen.Estimate(&est, &est_s));
  TG_CHECK(est >= 8 && est <= 12, "node file estimate %g", (double)est);
  /* bad files are refused */
  PetscCall(ExpectFailure("bad_malformed.nodes", "0 0 0\n1 0 zero\n1 1 0\n"));
  PetscCall(ExpectFailure("bad_ids.nodes", "0 0 0\n1 0 0\n1 1 0\n5 5 1\n6 5 1\n6 6 1\n0 5 0\n"));
  PetscCall(ExpectFailure("bad_gap.nodes", "0 0 0\n1 0 0\n1 1 0\n5 5 2\n6 5 2\n6 6 2\n"));
  PetscCall(ExpectFailure("bad_two.nodes", "0 0 0\n1 0 0\n"));
  PetscCall(ExpectFailure("bad_one_open.nodes", "0 0 0\n", {0}));
  PetscCall(ExpectFailure("bad_zero_bar.nodes", "0 0 0\n1 0 0\n1 0 0\n0 1 0\n"));
  PetscCall(ExpectFailure("bad_closing.nodes", "0 0 0\n1 0 0\n1 1 0\n0 0 0\n"));
  PetscCall(ExpectFailure("bad_bowtie.nodes", "0 0 0\n1 1 0\n1 0 0\n0 1 0\n"));
  PetscCall(ExpectFailure("bad_fold.nodes", "0 0 0\n2 0 0\n1 0 0\n1 1 0\n"));
  PetscCall(ExpectFailure("bad_collinear.nodes", "0 0 0\n1 0 0\n3 0 0\n"));
  PetscCall(ExpectFailure("bad_open_id.nodes", "0 0 0\n1 0 0\n1 1 0\n", {4}));
  PetscCall(ExpectFailure("bad_empty.nodes", "# nothing\n"));
  /* a long open chain that crosses itself near its end is found (the grid path, > 32 edges) */
  {
    std::string s;
    for (int k = 0; k < 200; k++) s += std::to_string(k) + " 0 0\n";
    s += "150.5 -1 0\n150.5 1 0\n";
    PetscCall(ExpectFailure("bad_long.nodes", s, {0}));
  }
  /* bounded reading: a line without end, a NUL byte, a file beyond 1 GiB (sparse: no disk used), a
     directory, a device */
  PetscCall(ExpectFailure("bad_long_line.nodes", std::string(5000, '1') + " 0 0\n"));
  PetscCall(ExpectFailure("bad_nul.nodes", std::string("0 0 0\n1 0 0\0 junk\n1 1 0\n", 22)));
  {
    std::ofstream("bad_huge.nodes") << "0 0 0\n1 0 0\n1 1 0\n";
    TG_CHECK(truncate("bad_huge.nodes", (1LL << 30) + 1) == 0, "cannot make the sparse file bad_huge.nodes");
    Tissue         Th;
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = ReadNodes("bad_huge.nodes", &Th);
    PetscCall(PetscPopErrorHandler());
    std::remove("bad_huge.nodes");
    TG_CHECK(ierr != 0, "a node file of more than 1 GiB was accepted");
    for (const char *path : {".", "/dev/zero"}) {
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      ierr = ReadNodes(path, &Th);
      PetscCall(PetscPopErrorHandler());
      TG_CHECK(ierr != 0, "%s was read as a node file", path);
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "node file: round trips identical (2 squares, 50 Voronoi cells, an open cell); 18 bad files refused\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestPolyline()
{
  PolylineSpec      spec;
  PolygonTissueSpec poly;
  Tissue            T;
  PetscFunctionBeginUser;
  poly.node_mass = 0.25;
  PetscCall(GeneratePolylineTissue(PETSC_COMM_SELF, spec, poly, &T));
  PetscCall(CheckBookkeeping(T));
  const ParticleSet &P = T.particles;
  TG_CHECK(P.n == 101 && P.springs.size() == 100 && P.polygons.size() == 1 && P.polygons[0].open, "polyline: 101 nodes, 100 bars, one open cell");
  for (PetscInt i = 0; i < P.n; i++) {
    TG_CHECK(P.mass[i] == 0.25, "node mass");
    TG_CHECK(P.node_polygon[i] == 0 && P.polygons[0].nodes[i] == i, "node order");
    TG_CHECK(T.X[2 * i + 1] == 0, "on the x axis");
  }
  for (const Spring &s : P.springs) TG_CHECK_CLOSE(s.rest_length, 0.01, 1e-12, 0, "spacing 0.01");
  TG_CHECK(T.X[0] == 0 && T.X[200] == 1, "end points exact");
  /* a slanted one */
  spec.start[0] = 1;
  spec.start[1] = 2;
  spec.end[0]   = 4;
  spec.end[1]   = 6;
  spec.nodes    = 2;
  PetscCall(GeneratePolylineTissue(PETSC_COMM_SELF, spec, poly, &T));
  TG_CHECK(T.particles.n == 2 && T.particles.springs.size() == 1, "2-node polyline");
  TG_CHECK_CLOSE(T.particles.springs[0].rest_length, 5, 1e-15, 0, "3-4-5 bar");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "polyline: 101 nodes 0.01 apart, one open cell\n"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      data[PETSC_MAX_PATH_LEN] = "";
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-data", data, sizeof data, &set));
  TG_CHECK(set, "-data DIR (tests/data) is needed");
  PetscCall(TestPolyline());
  PetscCall(TestNodeFile(data));
  PetscCall(TestVoronoi());
  PetscCall(TestLloydAndLaguerre());
  PetscCall(TestSubdivision());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_polygon_tissue: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
