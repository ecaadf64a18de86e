#include <turgor/core/options.h>
#include <turgor/fine/controls.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

namespace turgor {

PetscReal ControlGroup::Scale(PetscReal t) const
{
  t -= delay;
  if (t < 0 || (duration > 0 && t >= duration)) return 0;
  switch (profile) {
  case CONTROL_RAMP:
    return t < ramp_time ? t / ramp_time : 1;
  case CONTROL_CYCLIC:
    return ((long long)std::floor(t / half_period)) % 2 == 0 ? 1 : -1;
  default:
    return 1;
  }
}

PetscReal ControlGroup::Integral(PetscReal t) const
{
  t -= delay;
  if (t <= 0) return 0;
  if (duration > 0) t = std::min(t, duration);
  switch (profile) {
  case CONTROL_RAMP:
    return t < ramp_time ? 0.5 * t * t / ramp_time : 0.5 * ramp_time + (t - ramp_time);
  case CONTROL_CYCLIC: { /* a triangle wave: up for a half period, down for the next */
    const PetscReal m = std::fmod(t, 2 * half_period);
    return m < half_period ? m : 2 * half_period - m;
  }
  default:
    return t;
  }
}

PetscReal ControlGroup::Rate(PetscReal t) const
{
  t -= delay;
  return profile == CONTROL_RAMP && t >= 0 && t < ramp_time && (duration <= 0 || t < duration) ? 1 / ramp_time : 0;
}

/* The number of comma-separated values of option `name` (0 if not given), so that the list is read
   into a buffer one longer than that and a value too many cannot go unseen. */
static PetscErrorCode CountValues(const std::string &name, PetscInt *count)
{
  const char *value;
  PetscBool   set;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsFindPair(NULL, NULL, name.c_str(), &value, &set));
  *count = 0;
  if (set && value) *count = 1 + (PetscInt)std::count(value, value + std::strlen(value), ',');
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode ReadGroup(MPI_Comm comm, const std::string &name, bool help_only, ControlGroup *g, ParameterList *params)
{
  const std::string pre = "-control_" + name + "_";
  PetscInt          nn = 0, nc = 0, nf = 2, nv = 2, np = 5;
  PetscBool         set_nodes = PETSC_FALSE, set_cells = PETSC_FALSE, set_plates = PETSC_FALSE, set_v = PETSC_FALSE, set_f = PETSC_FALSE, set_ramp, set_half;
  char             *vel[3]    = {NULL, NULL, NULL};
  char             *plates[5] = {NULL, NULL, NULL, NULL, NULL};
  /* In the order of ControlProfile, read as a PetscInt (PETSc 3.18's PetscEnum holds only 0 and 1). */
  const char *const profiles[] = {"step", "ramp", "cyclic"};
  PetscInt          profile    = (PetscInt)g->profile;
  PetscReal         force[3]   = {0, 0, 0};
  BoxOption         box(g->box);
  PetscFunctionBeginUser;
  PetscCall(CountValues(pre + "nodes", &nn));
  PetscCall(CountValues(pre + "cells", &nc));
  std::vector<PetscInt> nodes(nn + 1), cells(nc + 1);
  nn++, nc++;
  nv = 3, nf = 3;
  PetscOptionsBegin(comm, ("control_" + name + "_").c_str(), ("Load control group '" + name + "'").c_str(), "turgor");
  PetscCall(TurgorOptionsIntArray(params, "-nodes", "Particle ids of the group", "Controls", nodes.data(), &nn, &set_nodes));
  PetscCall(TurgorOptionsIntArray(params, "-cells", "Cells whose nodes (polygon nodes, or the square grid's wall particles) join the group", "Controls",
                                  cells.data(), &nc, &set_cells));
  PetscCall(TurgorOptionsStringArray(params, "-plates", "Plates (-tissue_plates) whose nodes join the group: any of bottom,right,top,left", "Controls", plates,
                                     &np, &set_plates));
  PetscCall(TurgorOptionsRealArray(params, "-box", "xmin,ymin,xmax,ymax: wall particles whose reference position is inside join the group [µm]", "Controls",
                                   box.value, &box.n, &box.set));
  PetscCall(TurgorOptionsStringArray(params, "-velocity", "vx,vy imposed velocity [µm/µs]; a component may be 'free'", "Controls", vel, &nv, &set_v));
  PetscCall(TurgorOptionsRealArray(params, "-force", "fx,fy total force on the group [µN], shared by mass", "Controls", force, &nf, &set_f));
  PetscCall(TurgorOptionsEList(params, "-profile", "Time profile: step (constant), ramp (0 to full over -ramp_time), cyclic (sign reverses every -half_period)",
                               "Controls", profiles, 3, profiles[profile], &profile, NULL));
  PetscCall(TurgorOptionsReal(params, "-ramp_time", "Ramp duration [µs] (profile ramp)", "Controls", g->ramp_time, &g->ramp_time, &set_ramp));
  PetscCall(TurgorOptionsReal(params, "-half_period", "Half period [µs] (profile cyclic)", "Controls", g->half_period, &g->half_period, &set_half));
  PetscCall(TurgorOptionsReal(params, "-delay", "The profile starts at this time [µs]; before it a velocity group holds still and a force group pushes nothing",
                              "Controls", g->delay, &g->delay, NULL));
  PetscCall(TurgorOptionsReal(params, "-duration",
                              "The profile stops this long after its delay [µs]: a velocity group then holds still where it got to, a force group lets go "
                              "(0: never)",
                              "Controls", g->duration, &g->duration, NULL));
  PetscOptionsEnd();
  if (help_only) PetscFunctionReturn(PETSC_SUCCESS);
  g->name    = name;
  g->profile = (ControlProfile)profile;
  PetscCall(CheckNotEmpty(comm, (pre + "nodes").c_str(), "particle ids"));
  PetscCall(CheckNotEmpty(comm, (pre + "cells").c_str(), "cell ids"));
  PetscCall(CheckNotEmpty(comm, (pre + "plates").c_str(), "plates: bottom, right, top, left"));
  PetscCall(CheckNotEmpty(comm, (pre + "velocity").c_str(), "vx,vy (numbers or free)"));
  PetscCall(CheckNotEmpty(comm, (pre + "force").c_str(), "fx,fy"));
  if (set_nodes) g->node_ids.assign(nodes.begin(), nodes.begin() + nn);
  if (set_cells) g->cells.assign(cells.begin(), cells.begin() + nc);
  if (set_plates) {
    PetscCheck(np < 5, comm, PETSC_ERR_ARG_SIZ, "Option %splates: more than 4 plates listed", pre.c_str());
    g->named.clear();
    for (PetscInt k = 0; k < np; k++) {
      g->named.push_back(plates[k]);
      PetscCall(PetscFree(plates[k]));
    }
  }
  PetscCall(box.Take(comm, (pre + "box").c_str(), BoxShape::MayBeFlat, g->box, &g->has_box));
  PetscCheck(set_nodes || set_cells || set_plates || box.set || !g->node_ids.empty() || !g->cells.empty() || !g->named.empty() || g->has_box, comm,
             PETSC_ERR_ARG_WRONG, "Control group '%s' selects no nodes: give %snodes, %scells, %splates or %sbox", name.c_str(), pre.c_str(), pre.c_str(),
             pre.c_str(), pre.c_str());
  PetscCheck(!(set_v && set_f), comm, PETSC_ERR_ARG_INCOMP, "Options %svelocity and %sforce: a group imposes either a velocity or a force, not both",
             pre.c_str(), pre.c_str());
  PetscCheck(set_v || set_f, comm, PETSC_ERR_ARG_WRONG, "Control group '%s' imposes nothing: give %svelocity vx,vy or %sforce fx,fy", name.c_str(), pre.c_str(),
             pre.c_str());
  if (set_v) {
    std::string given;
    for (PetscInt k = 0; k < nv; k++) given += (k ? "," : "") + std::string(vel[k]);
    PetscCheck(nv == 2, comm, PETSC_ERR_ARG_SIZ, "Option %svelocity = %s: expected 2 components vx,vy (a number or free)", pre.c_str(), given.c_str());
    g->velocity = true;
    for (int d = 0; d < 2; d++) {
      char *end;
      g->free[d] = std::string(vel[d]) == "free";
      if (!g->free[d]) {
        g->value[d] = std::strtod(vel[d], &end);
        PetscCheck(end != vel[d] && *end == 0 && std::isfinite(g->value[d]), comm, PETSC_ERR_ARG_OUTOFRANGE,
                   "Option %svelocity = %s: component '%s' is neither a finite number nor free", pre.c_str(), given.c_str(), vel[d]);
      } else g->value[d] = 0;
    }
    PetscCheck(!(g->free[0] && g->free[1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %svelocity = free,free: imposes nothing (constrain a component)",
               pre.c_str());
    for (PetscInt k = 0; k < nv; k++) PetscCall(PetscFree(vel[k]));
  }
  if (set_f) {
    PetscCheck(nf == 2, comm, PETSC_ERR_ARG_SIZ, "Option %sforce: %" PetscInt_FMT " values given, expected 2 (fx,fy)", pre.c_str(), nf);
    PetscCheck(std::isfinite(force[0]) && std::isfinite(force[1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %sforce = %g,%g: must be finite", pre.c_str(),
               (double)force[0], (double)force[1]);
    g->velocity = false;
    g->value[0] = force[0], g->value[1] = force[1];
  }
  PetscCheck(std::isfinite(g->delay) && g->delay >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %sdelay = %g: must be finite and >= 0", pre.c_str(),
             (double)g->delay);
  PetscCheck(std::isfinite(g->duration) && g->duration >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option %sduration = %g: must be finite and >= 0 (0: never stops)",
             pre.c_str(), (double)g->duration);
  if (g->profile == CONTROL_RAMP)
    PetscCheck(std::isfinite(g->ramp_time) && g->ramp_time > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option %sramp_time = %g: profile ramp needs a finite ramp time > 0", pre.c_str(), (double)g->ramp_time);
  else PetscCheck(!set_ramp, comm, PETSC_ERR_ARG_WRONG, "Option %sramp_time is only used with %sprofile ramp", pre.c_str(), pre.c_str());
  if (g->profile == CONTROL_CYCLIC)
    PetscCheck(std::isfinite(g->half_period) && g->half_period > 0, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option %shalf_period = %g: profile cyclic needs a finite half period > 0", pre.c_str(), (double)g->half_period);
  else PetscCheck(!set_half, comm, PETSC_ERR_ARG_WRONG, "Option %shalf_period is only used with %sprofile cyclic", pre.c_str(), pre.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Controls::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char     *names[65];
  PetscInt  n = 65;
  PetscBool set, help;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Load controls of the fine run", "turgor");
  PetscCall(
    PetscOptionsStringArray("-controls", "Names of the control groups, each configured by -control_<name>_* (none by default)", "Controls", names, &n, &set));
  PetscOptionsEnd();
  PetscCall(CheckNotEmpty(comm, "-controls", "group names, e.g. -controls left,right"));
  PetscCheck(!set || n < 65, comm, PETSC_ERR_ARG_SIZ, "Option -controls: more than 64 groups listed");
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (!set) {
    ControlGroup g;
    if (help) PetscCall(ReadGroup(comm, "<name>", true, &g, nullptr)); /* list the options once */
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  std::vector<std::string> list;
  std::string              all;
  for (PetscInt k = 0; k < n; k++) {
    list.push_back(names[k]);
    all += (k ? "," : "") + list.back();
    PetscCall(PetscFree(names[k]));
  }
  if (params) params->Set("-controls", all);
  groups_.clear();
  for (size_t k = 0; k < list.size(); k++) {
    const std::string &name = list[k];
    bool               ok   = !name.empty();
    for (char c : name) ok = ok && (std::isalnum((unsigned char)c) || c == '_');
    PetscCheck(ok, comm, PETSC_ERR_ARG_WRONG, "Option -controls: group name '%s' must be letters, digits and '_'", name.c_str());
    for (size_t j = 0; j < k; j++) PetscCheck(list[j] != name, comm, PETSC_ERR_ARG_WRONG, "Option -controls: group '%s' is listed twice", name.c_str());
    ControlGroup g;
    PetscCall(ReadGroup(comm, name, false, &g, params));
    groups_.push_back(g);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Controls::SetUp(MPI_Comm comm, const Tissue &tissue, bool owner)
{
  const ParticleSet &P = tissue.particles;
  std::vector<int>   group_of(P.n, -1);
  PetscFunctionBeginUser;
  comp_.clear();
  comp_group_.clear();
  node_mass_.assign(groups_.empty() ? P.mass.end() : P.mass.begin(), P.mass.end()); /* read for the groups' nodes only */
  for (size_t gi = 0; gi < groups_.size(); gi++) {
    ControlGroup     &g   = groups_[gi];
    const std::string pre = "-control_" + g.name + "_";
    std::vector<char> in(P.n, 0);
    for (PetscInt id : g.node_ids) {
      PetscCheck(id >= 0 && id < P.n, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "Option %snodes: particle %" PetscInt_FMT " does not exist (the tissue has %" PetscInt_FMT " particles)", pre.c_str(), id, P.n);
      in[id] = 1;
    }
    const bool     polygons = !P.polygons.empty();
    const PetscInt ncells   = polygons ? (PetscInt)P.polygons.size() : tissue.NumCells();
    for (PetscInt c : g.cells) {
      PetscCheck(c >= 0 && c < ncells, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "Option %scells: cell %" PetscInt_FMT " does not exist (the tissue has %" PetscInt_FMT " cells)", pre.c_str(), c, ncells);
      for (PetscInt i : polygons ? P.polygons[c].nodes : tissue.cell_walls[c]) in[i] = 1;
    }
    for (const std::string &name : g.named) {
      auto        it = std::find_if(tissue.named_cells.begin(), tissue.named_cells.end(), [&](const auto &nc) { return nc.first == name; });
      std::string known;
      for (const auto &nc : tissue.named_cells) known += (known.empty() ? "" : ", ") + nc.first;
      PetscCheck(it != tissue.named_cells.end(), comm, PETSC_ERR_ARG_WRONG,
                 "Option %splates: the tissue has no plate '%s' (it has: %s; add plates with -tissue_plates)", pre.c_str(), name.c_str(),
                 known.empty() ? "none" : known.c_str());
      for (PetscInt i : P.polygons[it->second].nodes) in[i] = 1;
    }
    if (g.has_box)
      for (PetscInt i = 0; i < P.n; i++)
        if (P.kind[i] == KIND_WALL && tissue.X[2 * i] >= g.box[0] && tissue.X[2 * i] <= g.box[2] && tissue.X[2 * i + 1] >= g.box[1] &&
            tissue.X[2 * i + 1] <= g.box[3])
          in[i] = 1;
    g.nodes.clear();
    g.X0.clear();
    g.mass = 0;
    for (PetscInt i = 0; i < P.n; i++) {
      if (!in[i]) continue;
      PetscCheck(!P.fixed[i], comm, PETSC_ERR_ARG_INCOMP,
                 "Control group '%s': particle %" PetscInt_FMT " at (%g, %g) is clamped by -fine_clamp (use -fine_clamp none, or leave it out of the group)",
                 g.name.c_str(), i, (double)tissue.X[2 * i], (double)tissue.X[2 * i + 1]);
      PetscCheck(group_of[i] < 0, comm, PETSC_ERR_ARG_INCOMP, "Control groups '%s' and '%s' share particle %" PetscInt_FMT ": a node may be in one group only",
                 groups_[group_of[i]].name.c_str(), g.name.c_str(), i);
      group_of[i] = (int)gi;
      g.nodes.push_back(i);
      g.X0.push_back(tissue.X[2 * i]);
      g.X0.push_back(tissue.X[2 * i + 1]);
      g.mass += P.mass[i];
    }
    PetscCheck(!g.nodes.empty(), comm, PETSC_ERR_ARG_WRONG, "Control group '%s' is empty: its %snodes/%scells/%sbox select no particle", g.name.c_str(),
               pre.c_str(), pre.c_str(), pre.c_str());
    if (!owner) {
      g.nodes.clear();
      g.X0.clear();
    }
    if (g.velocity)
      for (PetscInt i : g.nodes)
        for (int d = 0; d < 2; d++)
          if (!g.free[d]) {
            comp_.push_back(2 * i + d);
            comp_group_.push_back((PetscInt)gi);
          }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void Controls::Localize(const std::vector<PetscInt> &local_of, const ParticleSet &P)
{
  n_owned_ = P.NumOwned();
  node_mass_.assign(groups_.empty() ? P.mass.end() : P.mass.begin(), P.mass.end());
  comp_.clear();
  comp_group_.clear();
  for (size_t gi = 0; gi < groups_.size(); gi++) {
    ControlGroup          &g = groups_[gi];
    std::vector<PetscInt>  nodes;
    std::vector<PetscReal> X0;
    for (size_t k = 0; k < g.nodes.size(); k++) {
      const PetscInt l = local_of[g.nodes[k]];
      if (l < 0) continue;
      nodes.push_back(l);
      X0.push_back(g.X0[2 * k]);
      X0.push_back(g.X0[2 * k + 1]);
    }
    g.nodes = std::move(nodes);
    g.X0    = std::move(X0);
    if (g.velocity)
      for (PetscInt i : g.nodes)
        for (int d = 0; d < 2; d++)
          if (!g.free[d] && i < n_owned_) { /* the state holds the owned particles only */
            comp_.push_back(2 * i + d);
            comp_group_.push_back((PetscInt)gi);
          }
  }
}

void Controls::Impose(PetscReal t, PetscReal *x, PetscReal *v, PetscInt n) const
{
  for (size_t g = 0; g < groups_.size(); g++) {
    const ControlGroup &G = groups_[g];
    if (!G.velocity) continue;
    const PetscReal s = G.Scale(t), S = G.Integral(t);
    for (size_t k = 0; k < G.nodes.size(); k++)
      for (int d = 0; d < 2; d++) {
        if (G.free[d] || G.nodes[k] >= n) continue;
        const PetscInt c = 2 * G.nodes[k] + d;
        if (x) x[c] = G.X0[2 * k + d] + G.value[d] * S;
        if (v) v[c] = G.value[d] * s;
      }
  }
}

void Controls::PositionRates(PetscReal t, PetscReal tau, PetscReal *xdot) const
{
  size_t    last = groups_.size(); /* the group whose rate q holds: once per group, not per node (a grip's hundreds) */
  PetscReal q    = 0;
  for (size_t k = 0; k < comp_.size(); k++) {
    const ControlGroup &G = groups_[comp_group_[k]];
    const int           d = (int)(comp_[k] % 2);
    /* the mean over the drift: its sum over the drifts of a step telescopes to the exact S */
    if ((size_t)comp_group_[k] != last) q = tau > 0 ? (G.Integral(t + tau) - G.Integral(t)) / tau : G.Scale(t), last = comp_group_[k];
    xdot[comp_[k]] = G.value[d] * q;
  }
}

void Controls::AdjustAccelerations(PetscReal t, PetscReal *a) const
{
  for (PetscInt c : comp_) a[c] = 0;
  for (const ControlGroup &G : groups_) {
    if (G.velocity) continue;
    const PetscReal s = G.Scale(t) / G.mass;
    for (PetscInt i : G.nodes)
      if (i < n_owned_)
        for (int d = 0; d < 2; d++) a[2 * i + d] += G.value[d] * s;
  }
}

void Controls::ControlForces(PetscReal t, const PetscReal *f, PetscReal *r, PetscInt n) const
{
  for (PetscInt k = 0; k < 2 * n; k++) r[k] = 0;
  /* a distributed run: f on a halo copy is this rank's share of its force, so that the reaction's
     power summed over the ranks is whole; the node's own part (m a, a force group's) is its owner's */
  for (const ControlGroup &G : groups_)
    for (PetscInt i : G.nodes)
      for (int d = 0; d < 2; d++) {
        const PetscInt c = 2 * i + d;
        if (!G.velocity) r[c] = i < n_owned_ ? G.value[d] * G.Scale(t) * node_mass_[i] / G.mass : 0;
        else if (!G.free[d]) r[c] = (i < n_owned_ ? node_mass_[i] * G.value[d] * G.Rate(t) : 0) - f[c];
      }
}

PetscErrorCode Controls::Observe(MPI_Comm comm, PetscReal t, const PetscReal *x, const PetscReal *f, std::vector<PetscReal> &row, bool inertia) const
{
  const size_t ng = groups_.size();
  const int    K  = 8; /* per group: sum ux, uy, fx, fy, count, m x, m y, and (second pass) mz */
  PetscFunctionBeginUser;
  row.assign(5 * ng, 0);
  std::vector<PetscReal> sums(K * ng, 0);
  for (size_t g = 0; g < ng; g++) {
    const ControlGroup &G = groups_[g];
    for (size_t k = 0; k < G.nodes.size(); k++) {
      const PetscInt i = G.nodes[k];
      if (i >= n_owned_) continue; /* a halo copy: its owner counts it */
      for (int d = 0; d < 2; d++) {
        sums[K * g + d] += x[2 * i + d] - G.X0[2 * k + d];
        sums[K * g + 2 + d] += f[2 * i + d];
        sums[K * g + 5 + d] += node_mass_[i] * x[2 * i + d];
      }
      sums[K * g + 4] += 1;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums.data(), (PetscMPIInt)sums.size(), MPIU_REAL, MPIU_SUM, comm));
  /* the moment about the centre of mass c: a velocity group's reaction on node i is m_i a_c - f_i on
     its constrained components (a_c is uniform, so sum m_i (x_i - c) x a_c = 0), a force group's
     applied force m_i F s / M (its moment about c is 0) */
  std::vector<PetscReal> mz(ng, 0);
  for (size_t g = 0; g < ng; g++) {
    const ControlGroup &G = groups_[g];
    if (!G.velocity) continue;
    const PetscReal cx = sums[K * g + 5] / G.mass, cy = sums[K * g + 6] / G.mass;
    for (PetscInt i : G.nodes) {
      if (i >= n_owned_) continue;
      const PetscReal rx = G.free[0] ? 0 : -f[2 * i], ry = G.free[1] ? 0 : -f[2 * i + 1];
      mz[g] += (x[2 * i] - cx) * ry - (x[2 * i + 1] - cy) * rx;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mz.data(), (PetscMPIInt)mz.size(), MPIU_REAL, MPIU_SUM, comm));
  for (size_t g = 0; g < ng; g++) {
    const ControlGroup &G = groups_[g];
    const PetscReal     n = sums[K * g + 4] > 0 ? sums[K * g + 4] : 1;
    for (int d = 0; d < 2; d++) {
      row[5 * g + d] = sums[K * g + d] / n;
      if (!G.velocity) row[5 * g + 2 + d] = G.value[d] * G.Scale(t);
      else if (!G.free[d]) row[5 * g + 2 + d] = (inertia ? G.mass * G.value[d] * G.Rate(t) : 0) - sums[K * g + 2 + d];
    }
    row[5 * g + 4] = mz[g];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<std::string> Controls::Columns() const
{
  std::vector<std::string> c;
  for (const ControlGroup &G : groups_)
    for (const char *q : {"ux", "uy", "fx", "fy", "mz"}) c.push_back(G.name + "_" + q);
  return c;
}

std::vector<std::string> Controls::Names() const
{
  std::vector<std::string> c;
  for (const ControlGroup &G : groups_) c.push_back(G.name);
  return c;
}

PetscErrorCode Controls::View(MPI_Comm comm) const
{
  static const char *const profiles[] = {"step", "ramp", "cyclic"};
  PetscFunctionBeginUser;
  for (const ControlGroup &G : groups_) {
    char comp[2][32];
    for (int d = 0; d < 2; d++) {
      if (G.velocity && G.free[d]) PetscCall(PetscSNPrintf(comp[d], sizeof comp[d], "free"));
      else PetscCall(PetscSNPrintf(comp[d], sizeof comp[d], "%g", (double)G.value[d]));
    }
    PetscCall(PetscPrintf(comm, "control '%s': %s (%s, %s) %s, profile %s", G.name.c_str(), G.velocity ? "velocity" : "force", comp[0], comp[1],
                          G.velocity ? "µm/µs" : "µN (total, shared by mass)", profiles[G.profile]));
    if (G.profile == CONTROL_RAMP) PetscCall(PetscPrintf(comm, " over %g µs", (double)G.ramp_time));
    if (G.profile == CONTROL_CYCLIC) PetscCall(PetscPrintf(comm, ", half period %g µs", (double)G.half_period));
    if (G.delay > 0) PetscCall(PetscPrintf(comm, ", from t = %g µs", (double)G.delay));
    if (G.duration > 0) PetscCall(PetscPrintf(comm, ", until t = %g µs", (double)(G.delay + G.duration)));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ClampFromOptions(MPI_Comm comm, std::vector<std::string> *clamp, ParameterList *params)
{
  char     *sides[8];
  PetscInt  nsides = 8;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "fine_", "Boundary conditions of the fine modes (-mode fine, fine_static)", "turgor");
  PetscCall(PetscOptionsStringArray("-clamp", "Tissue sides whose wall particles are fixed: left,right,bottom,top or none (default: left)", "Controls", sides,
                                    &nsides, &set));
  PetscOptionsEnd();
  std::vector<std::string> listed;
  for (PetscInt k = 0; set && k < nsides; k++) { /* taken at once: an error below must not leave them allocated */
    listed.push_back(sides[k]);
    PetscCall(PetscFree(sides[k]));
  }
  PetscCheck(!set || nsides < 8, comm, PETSC_ERR_ARG_SIZ, "Option -fine_clamp: more than 7 sides listed");
  PetscCall(CheckNotEmpty(comm, "-fine_clamp", "sides: left, right, bottom, top, or none"));
  if (set) *clamp = listed;
  if (params) {
    std::string all;
    for (const std::string &c : *clamp) all += (all.empty() ? "" : ",") + c;
    params->Set("-fine_clamp", all.empty() ? "none" : all);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
