#include <turgor/particles/polygon_couplings.h>
#include <turgor/rve/periodic_cell.h>
#include <algorithm>
#include <cmath>
#include <set>

namespace turgor {

PetscErrorCode PeriodicCell::SetUpPolygons(MPI_Comm comm, const std::vector<PolygonRing> &rings, const PolygonTissueSpec &poly, const PetscReal period[2],
                                           PetscReal reach, PetscReal margin)
{
  Tissue base;
  PetscFunctionBeginUser;
  PetscCall(BuildPolygonTissue(comm, rings, poly, true, &base));
  const ParticleSet &B = base.particles;
  const PetscInt     N = B.n, S = (PetscInt)B.springs.size(), C = (PetscInt)B.polygons.size();
  reach_             = reach;
  margin_            = margin;
  tissue_            = base;
  tissue_.period[0]  = period[0];
  tissue_.period[1]  = period[1];
  ParticleSet &P     = tissue_.particles;
  P.n_owned          = N;
  P.n_springs_owned  = S;
  P.n_polygons_owned = C;
  P.spring_gid.resize(S);
  P.polygon_gid.resize(C);
  for (PetscInt s = 0; s < S; s++) P.spring_gid[s] = s;
  for (PetscInt c = 0; c < C; c++) P.polygon_gid[c] = c;
  halo_owner_.clear();
  halo_image_.clear();

  /* the images of the cells within reach + margin of a cell of the box; an image's particle, bar and
     cell ids are its owner's plus (image index + 1) x the counts (unique, and the same on any rank) */
  std::vector<CellBox>  box(C);
  std::vector<PetscInt> node_of(N, -1); /* an image's node of each owned node (its cell's, while it is made) */
  for (PetscInt c = 0; c < C; c++) box[c] = BoxOf(B.polygons[c].nodes, base.X.data());
  for (int n1 = -1; n1 <= 1; n1++)
    for (int n2 = -1; n2 <= 1; n2++) {
      if (!n1 && !n2) continue;
      const int       k        = PeriodicImages::Index(n1, n2);
      const PetscReal shift[2] = {n1 * period[0], n2 * period[1]};
      for (PetscInt c = 0; c < C; c++) {
        PetscReal gap = PETSC_MAX_REAL;
        for (PetscInt d = 0; d < C; d++) gap = std::min(gap, BoxGap(box[d], box[c], shift));
        if (gap > reach + margin) continue;
        const PolygonCell &src = B.polygons[c];
        PolygonCell        img;
        for (PetscInt i : src.nodes) {
          const PetscInt h = P.n++;
          node_of[i]       = h;
          img.nodes.push_back(h);
          P.mass.push_back(B.mass[i]), P.kind.push_back(B.kind[i]), P.cell.push_back(B.cell[i]);
          P.gid.push_back(B.gid[i] + (PetscInt)(k + 1) * N);
          P.node_polygon.push_back((PetscInt)P.polygons.size());
          for (int d = 0; d < 2; d++) tissue_.X.push_back(base.X[2 * i + d] + shift[d]);
          halo_owner_.push_back(i);
          halo_image_.push_back(k);
        }
        for (PetscInt s : src.bars) {
          Spring sp = B.springs[s];
          sp.i = node_of[sp.i], sp.j = node_of[sp.j];
          sp.joint[0] = sp.joint[1] = -1; /* the joints are the repulsion's (square grid), not the polygon terms' */
          img.bars.push_back((PetscInt)P.springs.size());
          P.springs.push_back(sp);
          P.spring_gid.push_back(s + (PetscInt)(k + 1) * S);
        }
        img.open = src.open;
        P.polygons.push_back(img);
        P.polygon_gid.push_back(c + (PetscInt)(k + 1) * C);
      }
    }
  tissue_.UpdateBounds();
  /* one node held at F X (the fluctuation is periodic: that fixes its translation) */
  P.fixed.assign(P.n, 0);
  P.fixed[0] = 1;
  free_.clear();
  for (PetscInt i = 1; i < N; i++) free_.push_back(i);
  length_ = std::sqrt(period[0] * period[1] / (PetscReal)std::max(C, (PetscInt)1));
  mass_   = 0;
  for (PetscInt i = 0; i < N; i++) mass_ += B.mass[i];
  PetscFunctionReturn(PETSC_SUCCESS);
}

void PeriodicCell::PolygonCouplings(const PetscReal *x, std::vector<std::vector<PetscInt>> &cols) const
{
  const PetscInt                  N = tissue_.particles.NumOwned();
  std::vector<PetscInt>           dof(N, -1);
  std::vector<std::set<PetscInt>> adj;
  for (size_t k = 0; k < free_.size(); k++) dof[free_[k]] = (PetscInt)k;
  turgor::PolygonCouplings(
    tissue_.particles, x, reach_, [&](PetscInt i) { return i < N ? i : halo_owner_[i - N]; }, adj);
  cols.assign(free_.size(), {});
  for (size_t k = 0; k < free_.size(); k++) {
    std::set<PetscInt> c;
    for (PetscInt i : adj[free_[k]])
      if (dof[i] >= 0) c.insert(dof[i]);
    cols[k].assign(c.begin(), c.end());
  }
}

PetscInt PeriodicCell::InvertedCell(const PetscReal *x) const
{
  const ParticleSet &P = tissue_.particles;
  if (!HasHalo()) return -1;
  for (size_t c = 0; c < P.OwnedPolygons(); c++)
    if (!P.polygons[c].open && !(PolygonArea(P.polygons[c].nodes, x) > 0)) return (PetscInt)c;
  return -1;
}

void PeriodicCell::ReturnHaloForces(PetscReal *f) const
{
  const PetscInt N = tissue_.particles.NumOwned();
  for (size_t h = 0; h < halo_owner_.size(); h++)
    for (int d = 0; d < 2; d++) f[2 * halo_owner_[h] + d] += f[2 * (N + (PetscInt)h) + d];
}

bool PeriodicCell::Admissible(const PetscReal *x, const Tensor2 &F, const PeriodicImages &images, std::string *why) const
{
  if (!HasHalo()) {
    *why = "the relaxed RVE has fluid particles outside their cell (a wall was crossed)";
    return FluidInsideCells(x, images);
  }
  const ParticleSet &P        = tissue_.particles;
  const PetscInt     inverted = InvertedCell(x);
  if (inverted >= 0) {
    *why = "cell " + std::to_string((long long)inverted) + " of the RVE is inverted (area " + std::to_string(PolygonArea(P.polygons[inverted].nodes, x)) +
           " µm^2)";
    return false;
  }
  /* an image left out of the halo was farther than reach + margin from every cell: now it is at
     least s_min(F) (reach + margin) - 2 max |x - F X| away (s_min the smaller singular value of F) */
  const PetscReal tr = F(0, 0) * F(0, 0) + F(0, 1) * F(0, 1) + F(1, 0) * F(1, 0) + F(1, 1) * F(1, 1), det = F.Det();
  const PetscReal s_min = std::sqrt(std::max((PetscReal)0, 0.5 * (tr - std::sqrt(std::max((PetscReal)0, tr * tr - 4 * det * det)))));
  PetscReal       u_max = 0;
  for (PetscInt i = 0; i < P.NumOwned(); i++) {
    PetscReal FX[2];
    F.Apply(&tissue_.X[2 * i], FX);
    u_max = std::max(u_max, std::hypot(x[2 * i] - FX[0], x[2 * i + 1] - FX[1]));
  }
  if (s_min * (reach_ + margin_) - 2 * u_max < reach_) {
    *why = "the RVE's halo of periodic images is too thin for this state (smallest stretch " + std::to_string(s_min) + ", largest fluctuation " +
           std::to_string(u_max) + " µm): raise -prve_halo_margin";
    return false;
  }
  return true;
}

PetscErrorCode PeriodicCell::SetUp(MPI_Comm comm, const SquareGridSpec &cell, PetscInt cells)
{
  SquareGridSpec spec = cell;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = cells;
  PetscCall(GeneratePeriodicSquareGridTissue(comm, spec, &tissue_));
  const ParticleSet &P = tissue_.particles;
  free_.clear();
  for (PetscInt i = 0; i < P.n; i++)
    if (!P.fixed[i]) free_.push_back(i);
  length_ = spec.cell_size;
  mass_   = 0;
  for (PetscReal m : P.mass) mass_ += m;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PeriodicImages PeriodicCell::Lattice(const Tensor2 &F, const Tensor2 &Fdot) const
{
  const PetscReal A1[2] = {tissue_.period[0], 0}, A2[2] = {0, tissue_.period[1]};
  PetscReal       a1[2], a2[2], va1[2], va2[2];
  PeriodicImages  images;
  F.Apply(A1, a1);
  F.Apply(A2, a2);
  Fdot.Apply(A1, va1);
  Fdot.Apply(A2, va2);
  images.Set(a1, a2, va1, va2);
  return images;
}

void PeriodicCell::Deform(const Tensor2 &F, const Tensor2 &Fdot, PetscReal *x, PetscReal *v) const
{
  for (PetscInt i = 0; i < tissue_.particles.n; i++) {
    F.Apply(&tissue_.X[2 * i], &x[2 * i]);
    Fdot.Apply(&tissue_.X[2 * i], &v[2 * i]);
  }
}

void PeriodicCell::Place(const Tensor2 &F, const PetscScalar *w, PetscReal *x) const
{
  for (size_t k = 0; k < free_.size(); k++) {
    const PetscInt i = free_[k];
    PetscReal      X[2];
    F.Apply(&tissue_.X[2 * i], X);
    x[2 * i]     = X[0] + length_ * w[2 * k];
    x[2 * i + 1] = X[1] + length_ * w[2 * k + 1];
  }
  if (HasHalo()) {
    const PeriodicImages lattice = Lattice(F, Tensor2::Zero());
    const PetscInt       N       = tissue_.particles.NumOwned();
    for (size_t h = 0; h < halo_owner_.size(); h++)
      for (int d = 0; d < 2; d++) x[2 * (N + (PetscInt)h) + d] = x[2 * halo_owner_[h] + d] + lattice.x[halo_image_[h]][d];
  }
}

bool PeriodicCell::FluidInsideCells(const PetscReal *x, const PeriodicImages &images) const
{
  const ParticleSet &P = tissue_.particles;
  for (PetscInt p = 0; p < P.n; p++) {
    if (P.kind[p] != KIND_FLUID) continue;
    const auto     &ring = tissue_.cell_walls[P.cell[p]];
    const auto     &img  = tissue_.cell_wall_images[P.cell[p]];
    const PetscReal px = x[2 * p], py = x[2 * p + 1];
    bool            in = false; /* crossing-number test */
    for (size_t e = 0, n = ring.size(); e < n; e++) {
      const size_t    f  = (e + 1) % n;
      const PetscReal ax = x[2 * ring[e]] + images.x[img[e]][0], ay = x[2 * ring[e] + 1] + images.x[img[e]][1];
      const PetscReal bx = x[2 * ring[f]] + images.x[img[f]][0], by = x[2 * ring[f] + 1] + images.x[img[f]][1];
      if ((ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay)) in = !in;
    }
    if (!in) return false;
  }
  return true;
}

} // namespace turgor
