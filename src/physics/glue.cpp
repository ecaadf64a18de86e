#include <turgor/core/geometry.h>
#include <turgor/core/options.h>
#include <turgor/physics/glue.h>
#include <turgor/physics/glue_bond_forces.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#if defined(__SSE2__)
  #include <emmintrin.h>
#endif

namespace turgor {

/* Names in the order of Glue::Law. Read with PetscOptionsEList into a PetscInt: PETSc 3.18's
   PetscEnum has only the values 0 and 1, so a third law held in one is undefined behaviour. */
static const char *const kLaws[] = {"energy", "strength", "softening"};

PetscErrorCode Glue::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscInt  e  = (PetscInt)law;
  PetscBool oc = open_cells ? PETSC_TRUE : PETSC_FALSE, cp = compression ? PETSC_TRUE : PETSC_FALSE;
  BoxOption unbonded(unbonded_box);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "glue_", "Glue bonds between polygonal cells, and their fracture", "turgor");
  PetscCall(TurgorOptionsEList(ctx.params, "-law",
                               "Rupture: energy (G_c reached), strength (quadratic sigma_c, tau_c interaction), softening (bilinear, G_c dissipated)", "Glue",
                               kLaws, 3, kLaws[e], &e, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-distance", "Gluing distance eps [µm]: a node this close (surface gap) to a bar of another cell is bonded to it",
                              "Glue", distance, &distance, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-normal_stiffness", "k_n [N/m per µm of interface]", "Glue", normal_stiffness, &normal_stiffness, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-tangential_stiffness", "k_t [N/m per µm of interface]; negative: k_n", "Glue", tangential_stiffness,
                              &tangential_stiffness, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-fracture_energy", "G_c [µN µm per µm of interface] (laws energy and softening)", "Glue", fracture_energy,
                              &fracture_energy, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-strength", "sigma_c, normal strength [N/m] (laws strength and softening); negative: sqrt(2 G_c k_n)", "Glue",
                              strength, &strength, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-shear_strength", "tau_c, shear strength [N/m] (law strength); negative: sigma_c sqrt(k_t/k_n)", "Glue",
                              shear_strength, &shear_strength, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-open_cells", "Glue open cells (plates, walls) too", "Glue", oc, &oc, NULL));
  PetscCall(TurgorOptionsBool(ctx.params, "-compression",
                              "An intact bond also resists closing, with k_n (the lamella carries compression; damage still grows in opening only)", "Glue", cp,
                              &cp, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-start_time",
                              "The bonds are made at the first accepted state at or after this time [µs] (0: the first evaluation, the reference geometry)",
                              "Glue", start_time, &start_time, NULL));
  PetscCall(TurgorOptionsRealArray(ctx.params, "-unbonded_box", "xmin,ymin,xmax,ymax [µm]: no bond whose bond point is inside (a pre-crack or notch)", "Glue",
                                   unbonded.value, &unbonded.n, &unbonded.set));
  PetscOptionsEnd();
  PetscCall(unbonded.Take(comm, "-glue_unbonded_box", BoxShape::MayBeFlat, unbonded_box, &has_unbonded_box));
  law         = (Law)e;
  open_cells  = oc;
  compression = cp;
  PetscCheck(std::isfinite(start_time) && start_time >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -glue_start_time = %g: must be finite and >= 0",
             (double)start_time);
  PetscCheck(std::isfinite(distance) && distance >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -glue_distance = %g: must be finite and >= 0", (double)distance);
  PetscCheck(std::isfinite(normal_stiffness) && normal_stiffness > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -glue_normal_stiffness = %g: must be finite and > 0", (double)normal_stiffness);
  PetscCheck(std::isfinite(tangential_stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -glue_tangential_stiffness = %g: must be finite",
             (double)tangential_stiffness);
  PetscCheck(std::isfinite(fracture_energy) && fracture_energy > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -glue_fracture_energy = %g: must be finite and > 0",
             (double)fracture_energy);
  PetscCheck(std::isfinite(strength) && strength != 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -glue_strength = %g: must be finite and > 0 (or negative: derived)", (double)strength);
  PetscCheck(std::isfinite(shear_strength) && shear_strength != 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -glue_shear_strength = %g: must be finite and > 0 (or negative: derived)", (double)shear_strength);
  kt_    = tangential_stiffness < 0 ? normal_stiffness : tangential_stiffness;
  sigma_ = strength > 0 ? strength : std::sqrt(2 * fracture_energy * normal_stiffness);
  tau_   = shear_strength > 0 ? shear_strength : sigma_ * std::sqrt(kt_ / normal_stiffness);
  l0_    = sigma_ / normal_stiffness;
  l02_   = l0_ * l0_;
  beta2_ = kt_ / normal_stiffness;
  lf_    = 2 * fracture_energy / sigma_;
  PetscCheck(law != SOFTENING || lf_ > l0_ * (1 + 1e-12), comm, PETSC_ERR_ARG_INCOMP,
             "Options -glue_law softening, -glue_strength = %g, -glue_fracture_energy = %g, -glue_normal_stiffness = %g: the softening branch needs G_c > "
             "sigma_c^2 / (2 k_n) = %g (the bond would break at its peak: use -glue_law energy, or a lower strength)",
             (double)sigma_, (double)fracture_energy, (double)normal_stiffness, (double)(sigma_ * sigma_ / (2 * normal_stiffness)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Glue::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  PetscCheck(P.n == 0 || (!P.polygons.empty() && P.node_polygon.size() == (size_t)P.n), PETSC_COMM_SELF,
             PETSC_ERR_ARG_WRONG, /* (P.n == 0: -fine_distribute 0's other ranks) */
             "glue needs a polygonal tissue (cells of nodes and bars: -tissue_type node_file, voronoi or polyline)");
  P_ = &P;
  bonds_.clear();
  breaks_.clear();
  intact_ = accepted_ = 0;
  dissipated_         = 0;
  have_bonds_         = false;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Glue::Opening(PetscInt b, const PetscReal *x, PetscReal *dn, PetscReal *dt) const
{
  const Bond           &B = bonds_[b];
  const GlueBondOpening o = GlueOpeningAt(x, B.p, B.a, B.b, B.lam, B.sign, B.gn0, B.gt0);
  *dn = o.dn, *dt = o.dt;
}

PetscReal Glue::Damage(PetscReal l) const
{
  if (law != SOFTENING || l <= l0_) return 0;
  return l >= lf_ ? 1.0 : lf_ * (l - l0_) / (l * (lf_ - l0_));
}

PetscReal Glue::Dissipated(PetscReal l) const
{
  return law != SOFTENING || l <= l0_ ? 0 : l >= lf_ ? fracture_energy : fracture_energy * (l - l0_) / (lf_ - l0_);
}

/* Bonds at the reference positions X: for every node, the closest bar of each other cell within
   2 r + eps (a grid of the nodes, visited from each bar's box), then the length shares. */
PetscErrorCode Glue::CreateBonds(const ParticleSet &P, const PetscReal *X)
{
  PetscFunctionBeginUser;
  bonds_.clear();
  info_.clear();
  trial_.clear();
  trial_bonds_      = SIZE_MAX;
  unbonded_         = 0;
  const PetscReal R = 2 * P.bar_radius + distance, R2 = R * R;
  PetscReal       lo[2] = {PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[2] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL};
  for (PetscInt i = 0; i < P.n; i++)
    for (int d = 0; d < 2; d++) lo[d] = std::min(lo[d], X[2 * i + d]), hi[d] = std::max(hi[d], X[2 * i + d]);
  if (P.n == 0) lo[0] = lo[1] = hi[0] = hi[1] = 0; /* a rank that holds no particles: one empty bin */
  PetscReal h = std::max(R, 1e-12);
  while (((hi[0] - lo[0]) / h + 1) * ((hi[1] - lo[1]) / h + 1) > 4.0 * P.n + 64) h *= 2;
  const PetscInt        nbx = (PetscInt)((hi[0] - lo[0]) / h) + 1, nby = (PetscInt)((hi[1] - lo[1]) / h) + 1;
  std::vector<PetscInt> start((size_t)nbx * nby + 1, 0), items(P.n), bin(P.n);
  for (PetscInt i = 0; i < P.n; i++) {
    const PetscInt bx = std::min(nbx - 1, (PetscInt)((X[2 * i] - lo[0]) / h)), by = std::min(nby - 1, (PetscInt)((X[2 * i + 1] - lo[1]) / h));
    bin[i] = by * nbx + bx;
    start[bin[i] + 1]++;
  }
  for (size_t k = 0; k + 1 < start.size(); k++) start[k + 1] += start[k];
  {
    std::vector<PetscInt> fill(start.begin(), start.end() - 1);
    for (PetscInt i = 0; i < P.n; i++) items[fill[bin[i]]++] = i;
  }
  std::vector<PetscInt> bar_cell(P.springs.size(), -1);
  for (size_t c = 0; c < P.polygons.size(); c++)
    for (PetscInt s : P.polygons[c].bars) bar_cell[s] = (PetscInt)c;
  /* best bar per (node, other cell): key node * ncells + cell -> (distance^2, bar, lambda) */
  struct Best {
    PetscReal d2, lam;
    PetscInt  s;
  };
  std::map<std::pair<PetscInt, PetscInt>, Best> best;
  for (size_t s = 0; s < P.springs.size(); s++) {
    const PetscInt cs = bar_cell[s];
    if (cs < 0 || (P.polygons[cs].open && !open_cells)) continue;
    const PetscInt   a = P.springs[s].i, b = P.springs[s].j;
    const PetscReal *xa = &X[2 * a], *xb = &X[2 * b];
    const PetscReal  ex = xb[0] - xa[0], ey = xb[1] - xa[1];
    const PetscInt   bx0 = std::max<PetscInt>(0, (PetscInt)std::floor((std::min(xa[0], xb[0]) - R - lo[0]) / h));
    const PetscInt   bx1 = std::min<PetscInt>(nbx - 1, (PetscInt)std::floor((std::max(xa[0], xb[0]) + R - lo[0]) / h));
    const PetscInt   by0 = std::max<PetscInt>(0, (PetscInt)std::floor((std::min(xa[1], xb[1]) - R - lo[1]) / h));
    const PetscInt   by1 = std::min<PetscInt>(nby - 1, (PetscInt)std::floor((std::max(xa[1], xb[1]) + R - lo[1]) / h));
    for (PetscInt jy = by0; jy <= by1; jy++)
      for (PetscInt jx = bx0; jx <= bx1; jx++)
        for (PetscInt t = start[jy * nbx + jx]; t < start[jy * nbx + jx + 1]; t++) {
          const PetscInt p = items[t], cp = P.node_polygon[p];
          if (cp < 0 || cp == cs || (P.polygons[cp].open && !open_cells)) continue;
          const PetscReal px = X[2 * p] - xa[0], py = X[2 * p + 1] - xa[1];
          const PetscReal lam = SegmentClosestParameter(&X[2 * p], xa, xb);
          const PetscReal dx = px - lam * ex, dy = py - lam * ey, d2 = dx * dx + dy * dy;
          if (d2 > R2 || d2 == 0) continue;
          auto it = best.find({p, cs});
          if (it == best.end() || d2 < it->second.d2 || (d2 == it->second.d2 && (PetscInt)s < it->second.s)) best[{p, cs}] = {d2, lam, (PetscInt)s};
        }
  }
  for (const auto &kv : best) { /* ordered by (node, cell): the same bonds in the same order on every run */
    Bond           B;
    BondInfo       I;
    const PetscInt s = kv.second.s;
    B.p = kv.first.first, I.cell_p = P.node_polygon[B.p], I.cell_s = kv.first.second, I.s = s;
    B.a = P.springs[s].i, B.b = P.springs[s].j, B.lam = kv.second.lam, B.sign = 1, B.L = 0;
    if (has_unbonded_box) { /* a pre-crack: no bond whose bond point is in the box */
      const PetscReal cx = (1 - B.lam) * X[2 * B.a] + B.lam * X[2 * B.b], cy = (1 - B.lam) * X[2 * B.a + 1] + B.lam * X[2 * B.b + 1];
      if (InBox(unbonded_box, cx, cy)) {
        unbonded_ += B.p < P.NumOwned();
        continue;
      }
    }
    B.sign                  = GlueOpeningAt(X, B.p, B.a, B.b, B.lam, 1, 0, 0).gn >= 0 ? 1 : -1; /* n points from the bar to the node */
    const GlueBondOpening o = GlueOpeningAt(X, B.p, B.a, B.b, B.lam, B.sign, 0, 0);
    B.gn0 = o.gn, B.gt0 = o.gt;
    bonds_.push_back(B);
    info_.push_back(I);
  }
  /* length shares: runs of consecutive nodes of cell A bonded to cell B, in A's ring order */
  std::map<std::pair<PetscInt, PetscInt>, std::vector<PetscInt>> by_node; /* (node, cell B) -> bond */
  for (size_t k = 0; k < bonds_.size(); k++) by_node[{bonds_[k].p, info_[k].cell_s}].push_back((PetscInt)k);
  std::map<std::pair<PetscInt, PetscInt>, PetscReal> span; /* directed (A, B) -> sum of shares */
  std::vector<PetscReal>                             share(bonds_.size(), 0);
  auto                                               point = [&](const Bond &B, PetscReal *c) {
    c[0] = (1 - B.lam) * X[2 * B.a] + B.lam * X[2 * B.b];
    c[1] = (1 - B.lam) * X[2 * B.a + 1] + B.lam * X[2 * B.b + 1];
  };
  for (size_t A = 0; A < P.polygons.size(); A++) {
    const PolygonCell                                             &C = P.polygons[A];
    const PetscInt                                                 N = (PetscInt)C.nodes.size();
    std::map<PetscInt, std::vector<std::pair<PetscInt, PetscInt>>> runs_of; /* B -> (position k, bond) */
    for (PetscInt k = 0; k < N; k++)
      for (auto it = by_node.lower_bound({C.nodes[k], -1}); it != by_node.end() && it->first.first == C.nodes[k]; ++it)
        runs_of[it->first.second].push_back({k, it->second[0]});
    for (auto &kv : runs_of) {
      std::vector<std::pair<PetscInt, PetscInt>> &v = kv.second; /* sorted by k */
      /* split into runs of consecutive k; a closed ring joins its last run to its first */
      std::vector<std::vector<PetscInt>> runs;
      for (size_t i = 0; i < v.size(); i++) {
        if (i == 0 || v[i].first != v[i - 1].first + 1) runs.emplace_back();
        runs.back().push_back(v[i].second);
      }
      if (!C.open && runs.size() > 1 && v.front().first == 0 && v.back().first == N - 1) {
        runs.back().insert(runs.back().end(), runs.front().begin(), runs.front().end());
        runs.erase(runs.begin());
      }
      auto lone = [&](PetscInt bond) { /* a lone bond: half its node's shorter bar */
                                       const Bond    &B = bonds_[bond];
                                       const PetscInt k = (PetscInt)(std::find(C.nodes.begin(), C.nodes.end(), B.p) - C.nodes.begin());
                                       PetscReal      l = PETSC_MAX_REAL;
                                       for (PetscInt q : {k - 1, k + 1}) {
                                         if (C.open && (q < 0 || q >= N)) continue;
                                         const PetscInt o = C.nodes[(q + N) % N];
                                         l                = std::min(l, std::hypot(X[2 * o] - X[2 * B.p], X[2 * o + 1] - X[2 * B.p + 1]));
                                       }
                                       return 0.5 * (l < PETSC_MAX_REAL ? l : 2 * P.bar_radius);
      };
      for (const auto &run : runs) {
        /* consecutive bonds whose bond points coincide (nodes on a very short bar, bonded to the same
           end of a bar) are one point of the interface: they split its share; a run that is all one
           point is a lone bond for each of them */
        std::vector<size_t> group_start = {0};
        for (size_t i = 1; i < run.size(); i++) {
          PetscReal c0[2], c1[2];
          point(bonds_[run[i - 1]], c0);
          point(bonds_[run[i]], c1);
          if (c0[0] != c1[0] || c0[1] != c1[1]) group_start.push_back(i);
        }
        group_start.push_back(run.size());
        const size_t groups = group_start.size() - 1;
        if (groups == 1)
          for (PetscInt b : run) share[b] = lone(b);
        else {
          std::vector<PetscReal> group_share(groups, 0);
          for (size_t g = 0; g + 1 < groups; g++) {
            PetscReal c0[2], c1[2];
            point(bonds_[run[group_start[g]]], c0);
            point(bonds_[run[group_start[g + 1]]], c1);
            const PetscReal d = std::hypot(c1[0] - c0[0], c1[1] - c0[1]);
            group_share[g] += 0.5 * d;
            group_share[g + 1] += 0.5 * d;
          }
          for (size_t g = 0; g < groups; g++)
            for (size_t i = group_start[g]; i < group_start[g + 1]; i++) share[run[i]] = group_share[g] / (PetscReal)(group_start[g + 1] - group_start[g]);
        }
        for (PetscInt b : run) span[{(PetscInt)A, kv.first}] += share[b];
      }
    }
  }
  for (size_t k = 0; k < bonds_.size(); k++) { /* both sides bonded: each counts half */
    const BondInfo &I    = info_[k];
    const bool      both = span.count({I.cell_s, I.cell_p}) && span[{I.cell_s, I.cell_p}] > 0;
    bonds_[k].L          = share[k] * (both ? 0.5 : 1.0);
  }
  {
    /* a distributed run: the halo nodes' bonds were made only for the shares above (an interface
       bonded from both sides counts each side half); each bond belongs to its node's rank */
    size_t kept = 0;
    for (size_t k = 0; k < bonds_.size(); k++)
      if (bonds_[k].p < P.NumOwned()) bonds_[kept] = bonds_[k], info_[kept] = info_[k], kept++;
    bonds_.resize(kept);
    info_.resize(kept);
  }
  for (size_t k = 0; k < bonds_.size(); k++)
    PetscCheck(bonds_[k].L > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "glue: bond %zu (node %" PetscInt_FMT ", bar %" PetscInt_FMT ") got no length share (-glue_distance %g)", k, bonds_[k].p, info_[k].s,
               (double)distance);
  intact_     = (PetscInt)bonds_.size();
  have_bonds_ = true;
  CopyGeometry();
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Glue::CopyGeometry()
{
  GlueBondGeometry &G = geometry_;
  G.Resize(bonds_.size());
  for (size_t k = 0; k < bonds_.size(); k++) {
    const Bond &B = bonds_[k];
    G.p[k] = B.p, G.a[k] = B.a, G.b[k] = B.b;
    G.lam[k] = B.lam, G.sign[k] = B.sign, G.gn0[k] = B.gn0, G.gt0[k] = B.gt0, G.L[k] = B.L;
    G.intact[k] = B.intact ? 1 : 0, G.lmax[k] = B.lmax;
  }
}

GlueLawParameters Glue::LawParameters() const
{
  return {law, compression, normal_stiffness, kt_, beta2_, l0_, l02_, fracture_energy, sigma_, tau_};
}

/* The bonds [lo, hi) one at a time (MODE as Kernel's): (0, 1) the force with the bond's damage into
   push_ (the block that starts at bond block_lo), recorded in trial_ at entry nt if the accepted step
   may change it (returns the next entry); (2) committed; (3) the energy added to *E. The forces of
   undamaged bonds come from GlueUndamagedForces instead, whose arithmetic is this one's with D = 0. */
template <int MODE>
size_t Glue::BondRange(const ForceInput &in, size_t lo, size_t hi, size_t nt, PetscReal *E, size_t block_lo)
{
  /* the law's parameters in locals: the stores below could alias the members, which would be
     loaded again for every bond */
  const PetscReal        *x         = in.x;
  const GlueLawParameters P         = LawParameters();
  const bool              softening = P.law == SOFTENING;
  PetscReal              *push      = push_.data();
  Trial                  *trial     = trial_.data();
  PetscReal               e         = 0;
  for (size_t k = lo; k < hi; k++) {
    Bond &B = bonds_[k];
    if (!B.intact) continue;
    const GlueBondOpening o  = GlueOpeningAt(x, B.p, B.a, B.b, B.lam, B.sign, B.gn0, B.gt0);
    const PetscReal       dn = o.dn, dt = o.dt, dnp = o.dnp;
    /* damage only past the peak: below it (most bonds, most of the time) no square root */
    const PetscReal l2     = GlueOpening2(dnp, dt, P.beta2);
    const bool      before = GlueBeforePeak(softening, B.lmax, l2, P.l0, P.l02);
    const PetscReal D      = softening && !before ? Damage(std::max(B.lmax, std::sqrt(l2))) : 0;
    if (MODE <= 1) {
      trial[nt] = {k, dnp, dt};
      nt += softening ? !before : GlueBrittleBreaks(P.law == ENERGY, P.kn, P.kt, P.Gc, P.sigma, P.tau, l2, dnp, dt);
    }
    if (MODE == 2) {
      Commit(in, k, dnp, dt);
      continue;
    }
    const PetscReal dnf = P.closing ? dn : dnp; /* the normal force's opening: closing too with -glue_compression */
    if (MODE == 3) {
      e += (1 - D) * B.L * 0.5 * (P.kn * dnf * dnf + P.kt * dt * dt);
      continue;
    }
    GlueForceOf(o, (1 - D) * B.L, P.kn, P.kt, dnf, push + 4 * (k - block_lo));
  }
  if (MODE == 3) *E += e;
  return nt;
}

namespace {
/* Bonds [lo, hi)'s forces (force: 4 values a bond from lo, as GlueUndamagedForces writes them) added
   into f: -F on the node, the share A on bar end a, F - A on b; the broken bonds skipped. With SSE2
   each node's (x, y) is one register: one load, add and store instead of two (GCC does not pair
   them); the same additions in the same order, so the same bits as the scalar loop. */
void ScatterBlock(const GlueBondGeometry &G, size_t lo, size_t hi, const PetscReal *force, PetscReal *f)
{
  const PetscInt  *p = G.p.data(), *a = G.a.data(), *b = G.b.data();
  const PetscReal *intact = G.intact.data();
  for (size_t k = lo; k < hi; k++) {
    if (intact[k] == 0) continue;
    const PetscReal *F  = force + 4 * (k - lo);
    PetscReal       *fp = f + 2 * p[k], *fa = f + 2 * a[k], *fb = f + 2 * b[k];
#if defined(__SSE2__)
    const __m128d Fv = _mm_loadu_pd(F), Av = _mm_loadu_pd(F + 2), Bv = _mm_sub_pd(Fv, Av); /* lambda F - q n = F - ((1 - lambda) F + q n) */
    _mm_storeu_pd(fp, _mm_sub_pd(_mm_loadu_pd(fp), Fv));
    _mm_storeu_pd(fa, _mm_add_pd(_mm_loadu_pd(fa), Av));
    _mm_storeu_pd(fb, _mm_add_pd(_mm_loadu_pd(fb), Bv));
#else
    fp[0] -= F[0], fp[1] -= F[1], fa[0] += F[2], fa[1] += F[3], fb[0] += F[0] - F[2], fb[1] += F[1] - F[3];
#endif
  }
}
/* How many of mark[0, n) lead before the first nonzero one (n if none), eight at a time: marks are
   rare (a bond past its peak or breaking), and a test and branch per bond cost more than the loop that
   made the marks. A mark is 0.0 or 1.0, so the bits of eight ORed together are 0 when none is set. */
size_t UnmarkedRun(const PetscReal *mark, size_t n)
{
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t any = 0;
    for (int j = 0; j < 8; j++) {
      std::uint64_t u;
      std::memcpy(&u, mark + i + j, sizeof u);
      any |= u;
    }
    if (any) break;
  }
  while (i < n && mark[i] == 0) i++;
  return i;
}
} // namespace

/* MODE 0: forces, 1: forces and virial, 2: accept (damage, breaks), 3: energy (returned).
   With F_n = (1 - D) L k_n <delta_n>, F_t = (1 - D) L k_t delta_t and F = F_n n + F_t t: force -F on
   the node, (1 - lambda) F + q n on a and lambda F - q n on b, q = (F_t g.n - F_n g.t) / |e| (the
   derivative of the bar's frame: the couple that makes the torque zero). */
template <int MODE>
PetscReal Glue::Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const PetscReal *x    = in.x;
  const size_t     n    = bonds_.size();
  PetscReal        w[4] = {0, 0, 0, 0}, E = 0;
  if (MODE >= 2) {
    BondRange<MODE>(in, 0, n, 0, &E);
    return E;
  }
  /* every bond's force as if undamaged, vectorised, with a mark on the bonds the accepted step may
     change; then, in bond order, the record of the marked bonds (AcceptStep at this state commits
     from it instead of scanning every bond), a damaged bond's force (past its peak) again with its
     damage; then the forces added into f. Block by block of bonds, so that the block's forces,
     openings and marks are still in the cache for the second and third passes (a large tissue's
     bonds stream tens of MB a pass). */
  PetscCheckAbort(geometry_.Size() == n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "glue: the bonds' geometry arrays are out of date");
  const size_t            block = std::min(n, block_bonds_);
  const GlueLawParameters P     = LawParameters();
  trial_.resize(n); /* room for every bond; the first trial_n_ are recorded below */
  push_.resize(4 * block);
  opening_.resize(3 * block);
  const PetscReal        *dnp = opening_.data(), *dt = opening_.data() + block, *mark = opening_.data() + 2 * block;
  const PetscReal        *push    = push_.data();
  Trial                  *trial   = trial_.data();
  size_t                  nt      = 0;
  const ForceGrain       &grain   = in.Grain();
  const bool              rounded = grain.On(); /* once: f's stores could alias the grain */
  const GlueBondGeometry &G       = geometry_;
  for (size_t lo = 0; lo < n; lo += block) {
    const size_t hi = std::min(n, lo + block);
    GlueUndamagedForces(G, lo, hi, x, P, push_.data(), opening_.data(), opening_.data() + block, opening_.data() + 2 * block);
    for (size_t k = lo; k < hi; k++) {
      k += UnmarkedRun(mark + (k - lo), hi - k);
      if (k == hi) break;
      if (P.law == SOFTENING) nt = BondRange<0>(in, k, k + 1, nt, nullptr, lo); /* damaged: again with its damage, and recorded there */
      else trial[nt++] = {k, dnp[k - lo], dt[k - lo]};                          /* broken by the accepted step */
    }
    /* Scatter apart from the evaluation: consecutive bonds share bar nodes, and adding into f inside
       the loop above chains every bond's square root and division behind the previous bond's stores. */
    if (MODE == 0 && !rounded) {
      ScatterBlock(G, lo, hi, push, f);
      continue;
    }
    for (size_t k = lo; k < hi; k++) {
      if (G.intact[k] == 0) continue;
      const PetscInt   p = G.p[k], a = G.a[k], b = G.b[k];
      const PetscReal *F  = push + 4 * (k - lo);
      PetscReal        Fx = F[0], Fy = F[1], ax = F[2], ay = F[3];
      if (rounded) grain(Fx, Fy), grain(ax, ay);
      const PetscReal bx = Fx - ax, by = Fy - ay; /* lambda F - q n = F - (1 - lambda) F - q n */
      f[2 * p] -= Fx;
      f[2 * p + 1] -= Fy;
      f[2 * a] += ax;
      f[2 * a + 1] += ay;
      f[2 * b] += bx;
      f[2 * b + 1] += by;
      if (MODE == 1) { /* -sum f (x) x, relative to the node: a at x_a - x_p, b at x_b - x_p */
        const PetscReal rax = x[2 * a] - x[2 * p], ray = x[2 * a + 1] - x[2 * p + 1], rbx = x[2 * b] - x[2 * p], rby = x[2 * b + 1] - x[2 * p + 1];
        w[0] -= ax * rax + bx * rbx;
        w[1] -= ax * ray + bx * rby;
        w[2] -= ay * rax + by * rbx;
        w[3] -= ay * ray + by * rby;
      }
    }
  }
  trial_n_ = nt, trial_bonds_ = n;
  if (MODE == 1)
    for (int q = 0; q < 4; q++) virial[q] += w[q];
  return E;
}

/* Commit bond k at the accepted state where its opening is (<delta_n>, delta_t): the softening law's
   largest opening and dissipation, the break and its record. */
void Glue::Commit(const ForceInput &in, size_t k, PetscReal dnp, PetscReal dt)
{
  Bond           &B  = bonds_[k];
  const PetscReal kn = normal_stiffness, kt = kt_, l2 = Opening2(dnp, dt), e = 0.5 * kn * l2; /* stored energy per length, undamaged */
  bool            breaks;
  if (law == SOFTENING) {
    if (BeforePeak(B, l2)) return;
    const PetscReal lm = std::max(B.lmax, std::sqrt(l2));
    dissipated_ += B.L * (Dissipated(lm) - Dissipated(B.lmax));
    B.lmax = geometry_.lmax[k] = lm;
    breaks                     = Damage(lm) >= 1;
  } else breaks = GlueBrittleBreaks(law == ENERGY, kn, kt, fracture_energy, sigma_, tau_, l2, dnp, dt);
  if (!breaks) return;
  const PetscReal *x = in.x, en = 0.5 * kn * dnp * dnp, et = 0.5 * kt * dt * dt, released = law == SOFTENING ? fracture_energy * B.L : e * B.L;
  if (law != SOFTENING) dissipated_ += released;
  B.intact            = false;
  geometry_.intact[k] = 0;
  intact_--;
  const PetscReal c[2] = {(1 - B.lam) * x[2 * B.a] + B.lam * x[2 * B.b], (1 - B.lam) * x[2 * B.a + 1] + B.lam * x[2 * B.b + 1]};
  const BondInfo &I    = info_[k];
  breaks_.push_back({in.t, 0.5 * (c[0] + x[2 * B.p]), 0.5 * (c[1] + x[2 * B.p + 1]), released, B.L, I.cell_p, I.cell_s, in.P->gid[B.p], I.s,
                     en >= 9 * et   ? "tension"
                     : et >= 9 * en ? "shear"
                                    : "mixed"});
}

PetscErrorCode Glue::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  if (!have_bonds_ && start_time == 0) PetscCall(CreateBonds(*in.P, in.x));
  if (virial) Kernel<1>(in, f, virial);
  else Kernel<0>(in, f, NULL);
  PetscCall(PetscLogFlops(60.0 * intact_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Glue::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  if (!have_bonds_ && start_time == 0) PetscCall(CreateBonds(*in.P, in.x));
  *E   = Kernel<3>(in, NULL, NULL);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Glue::AcceptStep(const ForceInput &in)
{
  PetscFunctionBeginUser;
  if (!have_bonds_ && in.t >= start_time * (1 - 1e-12)) {
    PetscCall(CreateBonds(*in.P, in.x));
    PetscFunctionReturn(PETSC_SUCCESS); /* made at this state: nothing to commit yet */
  }
  if (in.same_x && trial_bonds_ == bonds_.size()) /* the openings of the evaluation at these positions */
    for (size_t i = 0; i < trial_n_; i++) Commit(in, trial_[i].k, trial_[i].dnp, trial_[i].dt);
  else Kernel<2>(in, NULL, NULL);
  accepted_++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<Glue::Break> Glue::TakeBreaks()
{
  std::vector<Break> out;
  out.swap(breaks_);
  return out;
}

/* A bond is a spring of stiffness k L between the node and its bar point (lever weights 1 - lambda,
   lambda): Gershgorin row sums 2 k L, 2 k L (1 - lambda), 2 k L lambda on its three nodes. */
PetscErrorCode Glue::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  const bool provisional = !have_bonds_ && start_time > 0; /* the bonds this state would have bound the step; made for real later */
  if (!have_bonds_) PetscCall(CreateBonds(*in.P, in.x));
  /* a node's row sums its bonds and the bonds that hold its bars, which the owners of other nodes
     may compute: the halo copies' shares go to the owners first, so that the bound (and the step)
     does not depend on the ranks */
  std::vector<PetscReal> row(2 * in.P->n, 0.0); /* [row, 0] per particle: the halo's exchange pairs two values */
  const PetscReal        k = std::max(normal_stiffness, kt_);
  for (const Bond &B : bonds_) {
    if (!B.intact) continue;
    row[2 * B.p] += 2 * k * B.L;
    row[2 * B.a] += 2 * k * B.L * (1 - B.lam);
    row[2 * B.b] += 2 * k * B.L * B.lam;
  }
  if (in.sum_halo_shares) PetscCall(in.sum_halo_shares(row.data()));
  const PetscInt n  = in.sum_halo_shares ? in.P->NumOwned() : in.P->n;
  PetscReal      w2 = 0;
  for (PetscInt i = 0; i < n; i++) w2 = std::max(w2, row[2 * i] / in.P->mass[i]);
  if (w2 > 0) {
    char why[160];
    PetscCall(PetscSNPrintf(why, sizeof why, "glue: omega_max <= %.4g /µs (%" PetscInt_FMT " bonds, Gershgorin)", (double)std::sqrt(w2), intact_));
    limits.push_back({2.0 / std::sqrt(w2), why});
  }
  if (provisional) { /* none made: the records, their arrays and the counts as before */
    bonds_.clear();
    info_.clear();
    CopyGeometry();
    intact_     = 0;
    unbonded_   = 0;
    have_bonds_ = false;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The bonds as line segments from each node to its bar point, with their state. */
PetscErrorCode Glue::OutputSegments(const ForceInput &in, TermSegments *segments)
{
  PetscFunctionBeginUser;
  if (!have_bonds_ && start_time == 0) PetscCall(CreateBonds(*in.P, in.x));
  if (!have_bonds_) PetscFunctionReturn(PETSC_SUCCESS); /* not yet made (-glue_start_time): no segments yet */
  segments->name = "bonds";
  segments->xy.resize(4 * bonds_.size());
  segments->id.resize(bonds_.size());
  TermField intact{TermField::BAR, "intact", "1 intact, 0 broken", {}}, damage{TermField::BAR, "damage", "1", {}}, opening{TermField::BAR, "opening", "µm", {}},
    length{TermField::BAR, "length_share", "µm", {}};
  for (size_t k = 0; k < bonds_.size(); k++) {
    const Bond &B = bonds_[k];
    PetscReal   dn, dt;
    Opening((PetscInt)k, in.x, &dn, &dt);
    const PetscReal dnp     = dn > 0 ? dn : 0;
    segments->id[k]         = PairKey((std::uint64_t)in.P->gid[B.p], (std::uint64_t)in.P->SpringGid(info_[k].s)); /* as the checkpoint keys the bond */
    segments->xy[4 * k]     = in.x[2 * B.p];
    segments->xy[4 * k + 1] = in.x[2 * B.p + 1];
    segments->xy[4 * k + 2] = (1 - B.lam) * in.x[2 * B.a] + B.lam * in.x[2 * B.b];
    segments->xy[4 * k + 3] = (1 - B.lam) * in.x[2 * B.a + 1] + B.lam * in.x[2 * B.b + 1];
    intact.values.push_back(B.intact ? 1 : 0);
    damage.values.push_back(B.intact ? Damage(std::max(B.lmax, std::sqrt(Opening2(dnp, dt)))) : 1.0);
    opening.values.push_back(std::sqrt(dn * dn + dt * dt));
    length.values.push_back(B.L);
  }
  segments->fields = {intact, damage, opening, length};
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Glue::OutputFields(const ForceInput &in, std::vector<TermField> &fields)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Glue::RecordFiles(std::vector<std::pair<std::string, std::vector<std::string>>> &files) const
{
  files.push_back({
    "breaks.csv", {"time", "bond", "cell_node", "cell_bar", "node", "bar", "x", "y", "mode", "energy_released", "length_share"}
  });
}

void Glue::TakeRecords(std::vector<std::pair<std::string, std::vector<std::string>>> &rows)
{
  /* the tissue's numbers of cells and bars (a distributed run numbers them per rank); a bond is named
     by its node and bar ("node:bar"), whatever the ranks */
  auto PolygonId = [&](PetscInt c) { return P_ && !P_->polygon_gid.empty() && c >= 0 ? P_->polygon_gid[c] : c; };
  auto SpringId  = [&](PetscInt s) { return P_ && !P_->spring_gid.empty() && s >= 0 ? P_->spring_gid[s] : s; };
  char buf[64];
  auto num = [&](PetscReal v) {
    PetscCallAbort(PETSC_COMM_SELF, PetscSNPrintf(buf, sizeof buf, "%.17g", (double)v));
    return std::string(buf);
  };
  for (const Break &b : TakeBreaks())
    rows.push_back({
      "breaks.csv",
      {num(b.time), std::to_string(b.node) + ":" + std::to_string(SpringId(b.bar)), std::to_string(PolygonId(b.cell_node)),
        std::to_string(PolygonId(b.cell_bar)), std::to_string(b.node), std::to_string(SpringId(b.bar)), num(b.x), num(b.y), b.mode, num(b.energy),
        num(b.length)}
    });
}

void Glue::Statistics(std::vector<TermStatistic> &stats) const
{
  PetscReal L = 0;
  for (const Bond &B : bonds_) L += B.L;
  stats.push_back({"bonds_created", (PetscReal)bonds_.size()});
  stats.push_back({"bonds_intact", (PetscReal)intact_});
  stats.push_back({"bonds_broken", (PetscReal)(bonds_.size() - intact_)});
  stats.push_back({"glue_interface_length", L});
  if (has_unbonded_box) stats.push_back({"bonds_unbonded_box", (PetscReal)unbonded_});
  stats.push_back({"glue_fracture_dissipation", dissipated_});
}

PetscErrorCode Glue::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  char when[64] = "the first evaluation", box[160] = "";
  if (start_time > 0) PetscCall(PetscSNPrintf(when, sizeof when, "the first accepted state at t >= %g µs", (double)start_time));
  if (has_unbonded_box)
    PetscCall(PetscSNPrintf(box, sizeof box, "; none in the box %g,%g,%g,%g (-glue_unbonded_box)", (double)unbonded_box[0], (double)unbonded_box[1],
                            (double)unbonded_box[2], (double)unbonded_box[3]));
  PetscCall(
    PetscViewerASCIIPrintf(viewer,
                           "glue: law %s, eps = %g µm, k_n = %g, k_t = %g N/m per µm, G_c = %g µN, sigma_c = %g N/m, tau_c = %g N/m%s (bonds made at %s%s)\n",
                           kLaws[law], (double)distance, (double)normal_stiffness, (double)kt_, (double)fracture_energy, (double)sigma_, (double)tau_,
                           open_cells ? ", open cells glued" : "", when, box));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Glue::DeclareState(const ParticleSet &P, StateDeclaration &d)
{
  d.Scalar("have_bonds", &have_bonds_, Combine::Owner);
  d.Scalar("accepted_steps", &accepted_, Combine::Owner);
  d.Scalar("unbonded", &unbonded_, Combine::Sum);
  d.Scalar("fracture_dissipation", &dissipated_, Combine::Sum);
  d.Scalar("time", &time_, Combine::Owner);
  d.Table("bonds", StateEntity::Particle)
    .Records([this] { return bonds_.size(); },
             [this, &P](size_t k) { return PairKey((std::uint64_t)P.gid[bonds_[k].p], (std::uint64_t)P.SpringGid(info_[k].s)); },
             [this](size_t n) {
               bonds_.resize(n);
               info_.resize(n);
             },
             "node")
    .Ref("node", bonds_, &Bond::p, StateEntity::Particle)
    .Ref("bar_end_a", bonds_, &Bond::a, StateEntity::Particle)
    .Ref("bar_end_b", bonds_, &Bond::b, StateEntity::Particle)
    .Ref("bar", info_, &BondInfo::s, StateEntity::Bar)
    .Ref("cell_node", info_, &BondInfo::cell_p, StateEntity::Cell)
    .Ref("cell_bar", info_, &BondInfo::cell_s, StateEntity::Cell)
    .Field("intact", bonds_, &Bond::intact)
    .Field("lambda", bonds_, &Bond::lam)
    .Field("gn0", bonds_, &Bond::gn0)
    .Field("gt0", bonds_, &Bond::gt0)
    .Field("side", bonds_, &Bond::sign)
    .Field("length_share", bonds_, &Bond::L)
    .Field("largest_opening", bonds_, &Bond::lmax);
}

/* The bonds in the order CreateBonds makes them (by node, then the bar's cell), whatever order the
   checkpoint holds them in; nothing from an evaluation before the restart. */
PetscErrorCode Glue::AfterStateRead(const ForceInput &in)
{
  PetscFunctionBeginUser;
  std::vector<size_t> order(bonds_.size());
  for (size_t k = 0; k < order.size(); k++) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](size_t i, size_t j) { return bonds_[i].p != bonds_[j].p ? bonds_[i].p < bonds_[j].p : info_[i].cell_s < info_[j].cell_s; });
  std::vector<Bond>     bonds(bonds_.size());
  std::vector<BondInfo> info(info_.size());
  intact_ = 0;
  for (size_t k = 0; k < order.size(); k++) {
    bonds[k] = bonds_[order[k]], info[k] = info_[order[k]];
    intact_ += bonds[k].intact != 0;
  }
  bonds_.swap(bonds);
  info_.swap(info);
  trial_.clear();
  trial_bonds_ = SIZE_MAX;
  push_.clear();
  breaks_.clear();
  CopyGeometry();
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
