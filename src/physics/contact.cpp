#include <turgor/physics/contact.h>
#include <algorithm>
#include <unordered_map>
#include <cmath>

namespace turgor {

PetscErrorCode Contact::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "contact_", "Node-bar contact of polygonal cells with Coulomb friction", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-stiffness", "Normal stiffness k_n [N/m]", "Contact", stiffness, &stiffness, NULL));
  PetscCall(
    TurgorOptionsReal(ctx.params, "-damping", "Normal dashpot on the normal relative velocity [ng/µs] (only pushes)", "Contact", damping, &damping, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-friction", "Coulomb friction coefficient mu; 0 = frictionless", "Contact", friction, &friction, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-tangential_stiffness", "Tangential spring k_t [N/m]; negative = k_n", "Contact", tangential_stiffness,
                              &tangential_stiffness, NULL));
  PetscOptionsEnd();
  PetscCheck(stiffness > 0 && std::isfinite(stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -contact_stiffness = %g: must be finite and > 0",
             (double)stiffness);
  PetscCheck(damping >= 0 && std::isfinite(damping), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -contact_damping = %g: must be finite and >= 0", (double)damping);
  PetscCheck(friction >= 0 && std::isfinite(friction), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -contact_friction = %g: must be finite and >= 0",
             (double)friction);
  PetscCheck(std::isfinite(tangential_stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -contact_tangential_stiffness = %g: must be finite",
             (double)tangential_stiffness);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Contact::ForgetLists()
{
  cand_.clear();
  hist_.clear();
  live_.clear();
  trial_.clear();
  trial_lists_   = -1;
  seen_rebuilds_ = -1;
}

PetscErrorCode Contact::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  /* (a rank without particles, -fine_distribute 0's others, has nothing to check) */
  PetscCheck(P.n == 0 || P.bar_radius > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "contact needs a bar radius > 0 (-tissue_bar_radius), got %g",
             (double)P.bar_radius);
  PetscCheck(P.n == 0 || (!P.polygons.empty() && P.node_polygon.size() == (size_t)P.n), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
             "contact needs a polygonal tissue (cells of nodes and bars: -tissue_type node_file, voronoi or polyline)");
  r_         = P.bar_radius;
  kt_        = tangential_stiffness < 0 ? stiffness : tangential_stiffness;
  n_springs_ = std::max<size_t>(P.springs.size(), 1);
  bar_poly_.assign(P.springs.size(), -1);
  bar_pos_.assign(P.springs.size(), -1);
  node_pos_.assign(P.n, -1);
  node_bars_.assign(2 * P.n, -1);
  for (size_t c = 0; c < P.polygons.size(); c++) {
    const PolygonCell &C = P.polygons[c];
    for (size_t k = 0; k < C.nodes.size(); k++) node_pos_[C.nodes[k]] = (PetscInt)k;
    for (size_t k = 0; k < C.bars.size(); k++) {
      const PetscInt s = C.bars[k];
      bar_poly_[s]     = (PetscInt)c;
      bar_pos_[s]      = (PetscInt)k;
      for (PetscInt e : {P.springs[s].i, P.springs[s].j}) node_bars_[2 * e + (node_bars_[2 * e] >= 0)] = s;
    }
  }
  nb.RequestParticleSpringPairs(2 * r_);
  ForgetLists();
  near_.clear();
  near_cand_.clear();
  evaluations_ = max_active_ = 0;
  dissipated_                = 0;
  sum_active_ = sum_near_ = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Bar k of a closed N-gon joins nodes k and k+1: node k's own bars are k-1 and k, their neighbours
   k-2 and k+1; those four never touch it (they meet it at a node or fold with it at a hinge). */
inline bool Contact::Eligible(const ParticleSet &P, PetscInt p, PetscInt s) const
{
  const PetscInt cb = bar_poly_[s], cp = P.node_polygon[p];
  if (cb < 0 || cp < 0) return false;
  if (cb != cp) return true;
  const PolygonCell &C = P.polygons[cb];
  if (C.open) return false;
  const PetscInt N = (PetscInt)C.bars.size(), d = ((bar_pos_[s] - node_pos_[p]) % N + N) % N;
  return !(d == 0 || d == 1 || d == N - 1 || d == N - 2);
}

/* Pair (p, s) with the bars next to s at its ends: at end q the other bar s2 at q, if it may touch p
   (not one of p's own or adjacent bars), by its far end o. */
Contact::Candidate Contact::MakeCandidate(const ParticleSet &P, PetscInt p, PetscInt s) const
{
  Candidate C{p, P.springs[s].i, P.springs[s].j, s, -1, -1, false, false};
  for (int end = 0; end < 2; end++) {
    const PetscInt q  = end ? C.b : C.a;
    const PetscInt s2 = node_bars_[2 * q] == s ? node_bars_[2 * q + 1] : node_bars_[2 * q];
    if (s2 < 0 || s2 == s || !Eligible(P, p, s2)) continue;
    (end ? C.ob : C.oa)           = P.springs[s2].i == q ? P.springs[s2].j : P.springs[s2].i;
    (end ? C.lower_b : C.lower_a) = s2 < s;
  }
  return C;
}

/* Node p is closest to bar s at its end q (a corner); s2 the bar next to s at q (far end o, or -1:
   none that may touch p; `lower`: s2 numbered below s). The seed counts such a contact from both
   bars at q; here exactly one counts it: s2 if p projects inside s2 (s2 is closer or as close), the
   lower-numbered of the two if p is closest to q on both, otherwise s. Without s2, s. */
inline bool Contact::CornerOwner(const PetscReal *x, PetscInt p, PetscInt q, PetscInt o, bool lower)
{
  if (o < 0) return true;
  const PetscReal ex = x[2 * o] - x[2 * q], ey = x[2 * o + 1] - x[2 * q + 1];
  const PetscReal t = ((x[2 * p] - x[2 * q]) * ex + (x[2 * p + 1] - x[2 * q + 1]) * ey) / (ex * ex + ey * ey);
  if (t <= 0) return !lower; /* closest to q on both bars */
  if (t < 1) return false;   /* inside s2: s2 counts it */
  return true;
}

/* Node p projects inside bar s and lies within the slab of s2, the bar next to s at its end q (far
   end o, -1: none that may touch p), too (the inner side of a joint): is it nearer to s2 (ties: the
   lower-numbered bar)? Then s2 alone counts it. The seed counts such a node from both bars, and that
   count jumps by a whole contact's energy when the node leaves one slab while touching (on a nearly
   straight wall pushed in, at every joint a node slides past): with the nearer bar alone the touching
   energy is k_n/2 (2 r - dist)^2 with dist the distance to the wall, continuous everywhere (its
   gradient turns at the bisector). */
inline bool Contact::NearerNeighbour(const PetscReal *x, PetscInt p, PetscInt q, PetscInt o, bool lower, PetscReal d2)
{
  if (o < 0) return false;
  /* the geometry first: a node along a bar's middle is outside its neighbours' spans (one product) */
  const PetscReal ex = x[2 * o] - x[2 * q], ey = x[2 * o + 1] - x[2 * q + 1], L2 = ex * ex + ey * ey;
  const PetscReal wx = x[2 * p] - x[2 * q], wy = x[2 * p + 1] - x[2 * q + 1], proj = wx * ex + wy * ey;
  if (proj <= 0 || proj >= L2) return false;
  const PetscReal t = proj / L2, dx = wx - t * ex, dy = wy - t * ey, e2 = dx * dx + dy * dy;
  return e2 < d2 || (e2 == d2 && lower);
}

inline bool Contact::Counts(const PetscReal *x, const Candidate &C, Geometry &g) const
{
  const PetscInt  p = C.p, a = C.a, b = C.b;
  const PetscReal R = 2 * r_;
  g.ex = x[2 * b] - x[2 * a], g.ey = x[2 * b + 1] - x[2 * a + 1];
  const PetscReal px = x[2 * p] - x[2 * a], py = x[2 * p + 1] - x[2 * a + 1];
  const PetscReal L2 = g.ex * g.ex + g.ey * g.ey, proj = px * g.ex + py * g.ey;
  g.iL2 = 1 / L2, g.lam = proj <= 0 ? 0 : proj >= L2 ? 1 : proj * g.iL2;
  g.dx = px - g.lam * g.ex, g.dy = py - g.lam * g.ey, g.d2 = g.dx * g.dx + g.dy * g.dy;
  if (g.d2 == 0 || g.d2 >= R * R) return false;
  if (g.lam == 0) return CornerOwner(x, p, a, C.oa, C.lower_a);
  if (g.lam == 1) return CornerOwner(x, p, b, C.ob, C.lower_b);
  return !NearerNeighbour(x, p, a, C.oa, C.lower_a, g.d2) && !NearerNeighbour(x, p, b, C.ob, C.lower_b, g.d2);
}

/* The neighbour search's node-spring candidates filtered to eligible pairs, each with its history
   entry found once per rebuild (the map is keyed by (node gid, bar), not by list position); then
   the near list. Between rebuilds the near list is rebuilt when some node has moved more than half
   the near skin since it was built: a pair left out was farther than 2 r + near skin, and neither
   its node nor its bar's ends has moved half of that, so it is still apart. */
PetscErrorCode Contact::Refresh(const ForceInput &in)
{
  PetscFunctionBeginUser;
  const PetscReal *x = in.x;
  const PetscInt   n = in.P->n;
  if (in.nb->Rebuilds() != seen_rebuilds_) {
    const PointSegmentList &L = in.nb->ParticleSpringPairs();
    const ParticleSet      &P = *in.P;
    /* the live histories, by key, carried over to the new list */
    std::unordered_map<std::uint64_t, History> keep;
    for (size_t k = 0; k < cand_.size(); k++)
      if (hist_[k].live) keep.emplace(Key(P, cand_[k].p, cand_[k].s), hist_[k]);
    cand_.clear();
    hist_.clear();
    for (size_t k = 0; k < L.size(); k++) {
      if (!Eligible(P, L.p[k], L.s[k])) continue;
      cand_.push_back(MakeCandidate(P, L.p[k], L.s[k]));
      auto it = keep.find(Key(P, L.p[k], L.s[k]));
      hist_.push_back(it == keep.end() ? History() : it->second);
    }
    live_.clear();
    for (size_t k = 0; k < hist_.size(); k++)
      if (hist_[k].live) live_.push_back((PetscInt)k);
    seen_rebuilds_ = in.nb->Rebuilds();
    list_builds_++;
    near_skin_ = 0.25 * in.nb->Skin();
    BuildNearList(in, x, n);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* the largest move since the near list was built, from the neighbour search's pass */
  const PetscReal d2 = in.nb->MaxMoveSinceMark2();
  if (4 * d2 > near_skin_ * near_skin_ || (near_skin_ == 0 && d2 > 0)) BuildNearList(in, x, n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Contact::BuildNearList(const ForceInput &in, const PetscReal *x, PetscInt n)
{
  const PetscReal R = 2 * r_ + near_skin_, R2 = R * R;
  near_.clear();
  near_cand_.clear();
  for (size_t k = 0; k < cand_.size(); k++) {
    const Candidate &c  = cand_[k];
    const PetscReal  ex = x[2 * c.b] - x[2 * c.a], ey = x[2 * c.b + 1] - x[2 * c.a + 1];
    const PetscReal  px = x[2 * c.p] - x[2 * c.a], py = x[2 * c.p + 1] - x[2 * c.a + 1];
    const PetscReal  L2 = ex * ex + ey * ey, proj = px * ex + py * ey;
    bool             near;
    if (proj <= 0) near = px * px + py * py < R2;
    else if (proj >= L2) near = (px - ex) * (px - ex) + (py - ey) * (py - ey) < R2;
    else {
      const PetscReal cr = px * ey - py * ex;
      near               = cr * cr < R2 * L2;
    }
    if (near || hist_[k].live) { /* a pair with history is kept until AcceptStep drops it */
      near_.push_back({2 * (std::uint32_t)c.p, 2 * (std::uint32_t)c.a, 2 * (std::uint32_t)c.b});
      near_cand_.push_back((PetscInt)k);
    }
  }
  in.nb->Mark(x, n);
  near_builds_++;
}

/* Energy dissipated by a step of a pair whose tangential spring went from xi_old (committed) through
   the trial xi_trial = xi_old + slip increment to xi_new (the capped value): the work of the
   tangential force on the relative motion (trapezoidal, as the energy balance sums works) less the
   spring's energy change, k_t (xi_old + xi_new)/2 (xi_trial - xi_new); 0 while it sticks. */
static inline PetscReal SlipDissipation(PetscReal kt, PetscReal xi_old, PetscReal xi_trial, PetscReal xi_new)
{
  return 0.5 * kt * (xi_old + xi_new) * (xi_trial - xi_new);
}

/* MODE 0: forces, 1: forces and virial, 2: trial values only (the accepted state), 3: energy (returned).
   Geometry: e = x_b - x_a, lambda = clamp((x_p - x_a).e / |e|^2, 0, 1), c = x_a + lambda e,
   d = x_p - c, delta = 2 r - |d|, n = d / |d|. The tangential direction t is n turned a quarter,
   with the sense of the bar; the slip is the change of the contact's material coordinate on the bar,
   |e| d(lambda) (a rigid motion of node and bar together, or the bar stretching under a node that
   rests on it, does not change it). With friction, every touching pair leaves its trial values
   (the capped tangential displacement, lambda, the slip's dissipation) for CommitTrial. */
template <int MODE>
PetscReal Contact::Kernel(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const PetscReal  *x = in.x, *v = in.v;
  const PetscReal   R = 2 * r_, R2 = R * R, kn = stiffness, cn = damping, mu = friction, kt = kt_;
  const bool        tangential = Tangential();
  const ForceGrain &grain      = in.Grain();
  const bool        rounded    = grain.On(); /* once: f's stores could alias the grain */
  PetscReal         w[4] = {0, 0, 0, 0}, E = 0;
  PetscInt          active = 0;
  /* pass 1, branch-free (most near pairs do not touch, and a branch per pair mispredicts): the
     pairs closer than 2 r, by |(x_p - x_a)|e|^2 - t e|^2 < (2 r)^2 |e|^4 with t = clamp(proj, 0, |e|^2) */
  touch_.resize(near_.size());
  const size_t nt = ContactTouchingPairs(near_.data(), near_.size(), x, R2, touch_.data());
  if (MODE <= 2 && tangential) trial_.clear();
  /* pass 2: the touching pairs */
  for (size_t i = 0; i < nt; i++) {
    const PetscInt   k = near_cand_[touch_[i]];
    const Candidate &C = cand_[k];
    const PetscInt   p = C.p, a = C.a, b = C.b;
    Geometry         g;
    if (!Counts(x, C, g)) continue;
    const PetscReal ex = g.ex, ey = g.ey, dx = g.dx, dy = g.dy, d2 = g.d2, lam = g.lam, iL2 = g.iL2, L2 = ex * ex + ey * ey;
    active++;
    const History  &h    = hist_[k];
    const PetscReal dist = std::sqrt(d2), id = 1 / dist, nx = dx * id, ny = dy * id, delta = R - dist;
    const PetscReal l  = 1 - lam;
    const PetscReal vx = v[2 * p] - l * v[2 * a] - lam * v[2 * b], vy = v[2 * p + 1] - l * v[2 * a + 1] - lam * v[2 * b + 1];
    PetscReal       fn = kn * delta - cn * (vx * nx + vy * ny);
    if (fn < 0) fn = 0;
    if (MODE <= 1 && in.f_dashpot) { /* the dashpot's part, fn - k_n delta along n, for the energy balance */
      const PetscReal fd = fn - kn * delta, Dx = fd * nx, Dy = fd * ny;
      PetscReal      *g = in.f_dashpot;
      g[2 * p] += Dx, g[2 * p + 1] += Dy;
      g[2 * a] -= l * Dx, g[2 * a + 1] -= l * Dy;
      g[2 * b] -= lam * Dx, g[2 * b + 1] -= lam * Dy;
    }
    PetscReal ft = 0, tx = 0, ty = 0, xi = 0;
    if (tangential) {
      const PetscReal sg = (ny * ex - nx * ey) >= 0 ? 1 : -1; /* t = sg (n_y, -n_x), along e */
      tx                 = sg * ny;
      ty                 = -sg * nx;
      /* the slip is the node's move relative to the bar's material point it touches: |e| dlambda
         (a bar stretching under a resting node, or a rigid motion of both, is no slip) */
      xi                  = h.live ? h.xi + (lam - h.lam_ref) * L2 * std::sqrt(iL2) : 0;
      ft                  = -kt * xi;
      const PetscReal cap = mu * fn;
      if (std::fabs(ft) > cap) ft = ft > 0 ? cap : -cap;
      if (MODE <= 2) trial_.push_back({k, -ft / kt, lam, SlipDissipation(kt, h.live ? h.xi : 0, xi, -ft / kt)});
    }
    if (MODE == 2) continue;
    if (MODE == 3) {
      E += 0.5 * kn * delta * delta + (tangential ? 0.5 * ft * ft / kt : 0);
      continue;
    }
    const PetscReal Fx = fn * nx + ft * tx, Fy = fn * ny + ft * ty;
    /* the tangential force acts at distance |d| from the contact point c: its torque
       tau = d x (ft t) is balanced by a couple -tau on the bar, alpha = -tau / |e| along perp(e)/|e| */
    const PetscReal tau = ft * (dx * ty - dy * tx), al = -tau * iL2; /* force alpha (-e_y, e_x)/|e| = al (-e_y, e_x) */
    const PetscReal qx = -al * ey, qy = al * ex;
    PetscReal       gpx = Fx, gpy = Fy, gax = l * Fx + qx, gay = l * Fy + qy, gbx = qx - lam * Fx, gby = qy - lam * Fy;
    if (rounded) grain(gpx, gpy), grain(gax, gay), grain(gbx, gby);
    f[2 * p] += gpx;
    f[2 * p + 1] += gpy;
    f[2 * a] -= gax;
    f[2 * a + 1] -= gay;
    f[2 * b] += gbx;
    f[2 * b + 1] += gby;
    if (MODE == 1) { /* -sum f (x) x = -(F (x) d + q (x) e) */
      w[0] -= Fx * dx + qx * ex;
      w[1] -= Fx * dy + qx * ey;
      w[2] -= Fy * dx + qy * ex;
      w[3] -= Fy * dy + qy * ey;
    }
  }
  if (MODE <= 2 && tangential) trial_lists_ = list_builds_;
  active_ = active;
  if (MODE == 1)
    for (int q = 0; q < 4; q++) virial[q] += w[q];
  return E;
}

/* The history at the accepted state, from the trial values of an evaluation there: touching pairs
   take their capped tangential displacement (and the slip's dissipation); a pair that was live and
   touches no more opened, and its tangential spring's energy is lost (dissipated). Cost: the
   touching pairs and the previously live ones, not the near list. */
void Contact::CommitTrial()
{
  stamp_++;
  for (const Trial &T : trial_) {
    hist_[T.k] = {T.xi, T.lam, true, stamp_};
    dissipated_ += T.slip;
  }
  for (PetscInt k : live_) {
    History &h = hist_[k];
    if (h.live && h.stamp != stamp_) {
      dissipated_ += 0.5 * kt_ * h.xi * h.xi;
      h.live = false;
    }
  }
  live_.clear();
  for (const Trial &T : trial_) live_.push_back(T.k);
}

PetscErrorCode Contact::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  PetscCall(Refresh(in));
  if (virial) Kernel<1>(in, f, virial);
  else Kernel<0>(in, f, NULL);
  evaluations_++;
  sum_active_ += active_;
  sum_near_ += near_.size();
  max_active_ = std::max(max_active_, active_);
  PetscCall(PetscLogFlops(40.0 * near_.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Contact::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  PetscCall(Refresh(in));
  *E   = Kernel<3>(in, NULL, NULL);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Commit the tangential history at the accepted state; drop pairs that separated (in contact no
   more, or gone from the lists: farther than 2 r + near skin). */
PetscErrorCode Contact::AcceptStep(const ForceInput &in)
{
  PetscFunctionBeginUser;
  if (!Tangential()) PetscFunctionReturn(PETSC_SUCCESS); /* no history to keep */
  /* velocity Verlet and DOPRI accept the positions they last evaluated: commit that evaluation's
     trial values (what the step used) instead of recomputing the geometry. The velocities may differ
     (Verlet's last evaluation saw the half-step velocity, which enters the normal force through the
     damping): the history is that of the forces the integrator applied. */
  if (!(in.same_x && trial_lists_ == list_builds_)) { /* evaluate the trial values at this state */
    PetscCall(Refresh(in));
    Kernel<2>(in, NULL, NULL);
  }
  CommitTrial();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A normal contact is a spring k_n between the node and the bar's contact point: per node at most
   a few contacts; we bound omega^2 by 4 (k_n + k_t) / m_min (the node and the two bar ends). */
PetscErrorCode Contact::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscReal mmin = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < in.P->n; i++) mmin = std::min(mmin, in.P->mass[i]);
  const PetscReal w2 = 4 * (stiffness + (friction > 0 ? kt_ : 0)) / mmin, c = 4 * damping / mmin;
  const PetscReal lam = 0.5 * c + std::sqrt(0.25 * c * c + w2);
  char            why[160];
  PetscCall(PetscSNPrintf(why, sizeof why, "contact: omega_max <= %.4g /µs, damping rate <= %.4g /µs", (double)std::sqrt(w2), (double)c));
  limits.push_back({2.0 / lam, why});
  PetscFunctionReturn(PETSC_SUCCESS);
}

size_t Contact::HistoryEntries() const
{
  return (size_t)std::count_if(hist_.begin(), hist_.end(), [](const History &h) { return h.live; });
}

void Contact::Statistics(std::vector<TermStatistic> &stats) const
{
  const PetscReal n = evaluations_ > 0 ? (PetscReal)evaluations_ : 1;
  stats.push_back({"contact_mean_contacts", sum_active_ / n});
  /* the ranks' largest counts summed: the whole tissue's largest on one rank, an upper bound of it
     on several (their largest need not fall in the same evaluation) */
  stats.push_back({"contact_max_contacts", (PetscReal)max_active_});
  stats.push_back({"contact_mean_near_pairs", sum_near_ / n});
  stats.push_back({"contact_pair_lists", (PetscReal)list_builds_, TermStatistic::MAX}); /* every rank rebuilds its own lists */
  stats.push_back({"contact_near_lists", (PetscReal)near_builds_, TermStatistic::MAX});
  stats.push_back({"contact_history_entries", (PetscReal)HistoryEntries()});
  if (friction > 0) stats.push_back({"contact_friction_dissipation", dissipated_});
}

PetscErrorCode Contact::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "contact: r = %g µm, k_n = %g N/m, damping %g ng/µs, mu = %g, k_t = %g N/m\n", (double)r_, (double)stiffness,
                                   (double)damping, (double)friction, (double)kt_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Contact::DeclareState(const ParticleSet &P, StateDeclaration &d)
{
  if (!HasInternalState()) return;
  saved_.clear();
  for (size_t k = 0; k < cand_.size(); k++)
    if (hist_[k].live) saved_.push_back({cand_[k].p, cand_[k].s, hist_[k].xi, hist_[k].lam_ref, stamp_ - hist_[k].stamp});
  d.Scalar("commits", &stamp_, Combine::Max); /* every rank commits once per accepted step */
  d.Scalar("friction_dissipation", &dissipated_, Combine::Sum);
  d.Table("histories", StateEntity::Particle)
    .Records([this] { return saved_.size(); },
             [this, &P](size_t r) { return PairKey((std::uint64_t)P.gid[saved_[r].node], (std::uint64_t)P.SpringGid(saved_[r].bar)); },
             [this](size_t n) { saved_.resize(n); }, "node")
    .Ref("node", saved_, &SavedHistory::node, StateEntity::Particle)
    .Ref("bar", saved_, &SavedHistory::bar, StateEntity::Bar)
    .Field("xi", saved_, &SavedHistory::xi)
    .Field("lam_ref", saved_, &SavedHistory::lam_ref)
    .Field("age", saved_, &SavedHistory::age);
}

PetscErrorCode Contact::AfterStateRead(const ForceInput &in)
{
  std::unordered_map<std::uint64_t, History> saved;
  PetscFunctionBeginUser;
  if (!HasInternalState()) PetscFunctionReturn(PETSC_SUCCESS);
  for (const SavedHistory &h : saved_) saved.emplace(Key(*in.P, h.node, h.bar), History{h.xi, h.lam_ref, true, stamp_ - h.age});
  std::vector<SavedHistory>().swap(saved_);
  PetscCall(AttachHistories(in, saved));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Contact::AttachHistories(const ForceInput &in, const std::unordered_map<std::uint64_t, History> &saved)
{
  PetscFunctionBeginUser;
  ForgetLists();
  PetscCall(Refresh(in));
  size_t found = 0;
  for (size_t k = 0; k < cand_.size(); k++) {
    auto it = saved.find(Key(*in.P, cand_[k].p, cand_[k].s));
    if (it == saved.end()) continue;
    hist_[k] = it->second;
    live_.push_back((PetscInt)k);
    found++;
  }
  PetscCheck(found == saved.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "contact: %zu of the checkpoint's %zu contact histories have no pair in the neighbour lists at its state", saved.size() - found, saved.size());
  BuildNearList(in, in.x, in.P->n); /* with the live pairs */
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
