#include <turgor/material/material_pool.h>
#include <turgor/material/skipping_point.h>
#include <turgor/io/output.h>
#include <algorithm>
#include <unordered_map>
#include <cmath>
#include <cstring>

namespace turgor {

PetscErrorCode MaterialModelRegister(const char name[], MaterialModelCreator create)
{
  return Registry<MaterialModel>::Instance().Add(name, create);
}

PetscErrorCode MaterialModelCreate(MPI_Comm comm, const std::string &name, std::unique_ptr<MaterialModel> *model)
{
  return Registry<MaterialModel>::Instance().Create(comm, name, "-material", "material", model);
}

std::string MaterialModelNames()
{
  return Registry<MaterialModel>::Instance().Names();
}

namespace {

/* What travels per point. Counts ride as reals (exact below 2^53) so that each struct is one
   contiguous MPI type of PetscReal. */
struct PointInput {
  PetscReal F[4], Fdot[4];
};
struct PointResult {
  PetscReal sigma[4], rho, residual;
  PetscReal De[9], Dv[9];
  PetscReal ok, iterations, snes_its, ksp_its;
};
struct PointReason {
  char text[160];
};
static_assert(sizeof(PointInput) % sizeof(PetscReal) == 0 && sizeof(PointResult) % sizeof(PetscReal) == 0, "structs of PetscReal only");

PetscErrorCode ContiguousType(int count, MPI_Datatype base, MPI_Datatype *type)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Type_contiguous(count, base, type));
  PetscCallMPI(MPI_Type_commit(type));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

MaterialPointPool::~MaterialPointPool()
{
  points_.clear(); /* before the sub-communicator they live on */
  PetscCallVoid(PetscSFDestroy(&in_sf_));
  PetscCallVoid(PetscSFDestroy(&out_sf_));
  for (MPI_Datatype *t : {&in_type_, &out_type_, &reason_type_})
    if (*t != MPI_DATATYPE_NULL) PetscCallVoid(MPI_Type_free(t) == MPI_SUCCESS ? PETSC_SUCCESS : PETSC_ERR_MPI);
  PetscCallVoid(PetscSubcommDestroy(&subcomm_));
}

PetscErrorCode MaterialPointPool::SetFromOptions(ParameterList *params)
{
  const char *const tangents[] = {"forward", "central", "implicit"};
  PetscInt          tangent    = (PetscInt)tangent_.method;
  char              name[64];
  PetscBool         set;
  PetscFunctionBeginUser;
  if (!model_) {
    const std::string help = "Material point: " + MaterialModelNames();
    PetscCall(PetscStrncpy(name, type_.c_str(), sizeof name));
    PetscOptionsBegin(comm_, NULL, "Material points of the coarse model", "turgor");
    PetscCall(TurgorOptionsString(params, "-material", help.c_str(), "MaterialPointPool", name, name, sizeof name, &set));
    PetscOptionsEnd();
    type_ = name;
    PetscCall(MaterialModelCreate(comm_, type_, &model_));
    if (default_tol_ > 0) model_->SetDefaultTolerance(default_tol_);
    PetscCall(model_->SetFromOptions(comm_, params));
  }
  PetscOptionsBegin(comm_, NULL, "Renamed options of the material-point pool", "turgor");
  PetscCall(PetscOptionsDeprecated("-rve_comm_size", "-material_comm_size", "0.2", NULL));
  PetscCall(PetscOptionsDeprecated("-rve_tangent", "-material_tangent", "0.2", NULL));
  PetscCall(PetscOptionsDeprecated("-rve_tangent_fdot_typ", "-material_tangent_fdot_typ", "0.2", NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(comm_, "material_", "Material-point groups and tangents", "turgor");
  PetscCall(PetscOptionsInt("-comm_size", "MPI ranks per material-point group (sub-communicator)", "MaterialPointPool", comm_size_, &comm_size_, NULL));
  PetscCall(TurgorOptionsEList(params, "-tangent",
                               "Material tangents D^e, D^v: forward or central differences (eqs 46-53: perturbed material evaluations) or implicit (exact: "
                               "an RVE differentiates its relaxed state, dw/dF from G_w dw/dF = -G_F with the relaxation's LU factor; no perturbed solves)",
                               "MaterialPointPool", tangents, 3, tangents[tangent], &tangent, NULL));
  PetscCall(TurgorOptionsReal(params, "-tangent_fdot_typ", "Typical velocity gradient Fdot_typ of eq 53 [1/µs]", "MaterialPointPool", tangent_.Fdot_typ,
                              &tangent_.Fdot_typ, NULL));
  PetscCall(TurgorOptionsReal(params, "-skip_tolerance",
                              "Answer a trial evaluation from the point's last solve and its tangents (first order) while the estimated error of that "
                              "is below this stress [N/m]; 0: always solve",
                              "MaterialPointPool", skip_tolerance_, &skip_tolerance_, NULL));
  PetscCall(PetscOptionsInt("-rebalance",
                            "After N material evaluations, deal the points to the groups again in blocks of equal measured cost (the points that "
                            "change group move with their state: the same results); 0: never",
                            "MaterialPointPool", rebalance_after_, &rebalance_after_, NULL));
  PetscOptionsEnd();
  PetscCheck(skip_tolerance_ >= 0 && std::isfinite(skip_tolerance_), comm_, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -material_skip_tolerance = %g: must be >= 0 (0: always solve)", (double)skip_tolerance_);
  PetscCheck(rebalance_after_ >= 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -material_rebalance = %" PetscInt_FMT ": must be >= 0 (0: never)",
             rebalance_after_);
  tangent_.method = (TangentMethod)tangent;
  PetscCheck(tangent_.method != TangentMethod::Implicit || model_->HasStressDerivatives(), comm_, PETSC_ERR_ARG_INCOMP,
             "Option -material_tangent = implicit: the material %s has no exact stress derivatives (use forward or central)", model_->Name());
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCheck(comm_size_ >= 1 && size % comm_size_ == 0, comm_, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -material_comm_size = %" PetscInt_FMT ": must divide the number of MPI ranks (%d)", comm_size_, size);
  PetscCheck(tangent_.Fdot_typ > 0 && std::isfinite(tangent_.Fdot_typ), comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -material_tangent_fdot_typ = %g: must be > 0",
             (double)tangent_.Fdot_typ);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::SetUp(PetscInt n_local)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCheck(model_, comm_, PETSC_ERR_ORDER, "MaterialPointPool::SetFromOptions() must be called before SetUp()");
  PetscCall(PetscLogEventRegister("TgMaterialPoints", PETSC_OBJECT_CLASSID, &ev_evaluate_));
  PetscCall(PetscLogEventRegister("TgTangents", PETSC_OBJECT_CLASSID, &ev_tangents_));
  n_local_ = n_local;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  std::vector<PetscInt> counts(size), offsets(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&n_local_, 1, MPIU_INT, counts.data(), 1, MPIU_INT, comm_));
  for (int r = 0; r < size; r++) offsets[r + 1] = offsets[r] + counts[r];
  n_global_ = offsets[size];
  n_groups_ = size / comm_size_;
  PetscCall(PetscSubcommCreate(comm_, &subcomm_));
  PetscCall(PetscSubcommSetNumber(subcomm_, n_groups_));
  PetscCall(PetscSubcommSetType(subcomm_, PETSC_SUBCOMM_CONTIGUOUS));
  const PetscMPIInt color = subcomm_->color;
  begin_                  = (color * n_global_) / n_groups_;
  end_                    = ((color + 1) * n_global_) / n_groups_;
  MPI_Comm group          = PetscSubcommChild(subcomm_);
  PetscCallMPI(MPI_Comm_rank(group, &group_rank_));
  offsets_ = offsets;
  for (PetscInt g = begin_; g < end_; g++) {
    std::unique_ptr<MaterialPoint> p;
    PetscCall(CreatePoint(group, &p));
    points_.push_back(std::move(p));
  }
  cost_.assign(end_ - begin_, 0.0);
  PetscCall(ContiguousType(sizeof(PointInput) / sizeof(PetscReal), MPIU_REAL, &in_type_));
  PetscCall(ContiguousType(sizeof(PointResult) / sizeof(PetscReal), MPIU_REAL, &out_type_));
  PetscCall(ContiguousType(sizeof(PointReason), MPI_CHAR, &reason_type_));
  PetscCall(BuildTraffic());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const
{
  PetscFunctionBeginUser;
  PetscCall(model_->CreatePoint(group, point));
  if (skip_tolerance_ > 0) *point = std::make_unique<SkippingPoint>(std::move(*point), skip_tolerance_, tangent_.Fdot_typ);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every rank of a group receives its block's inputs; only the group's first rank sends results */
PetscErrorCode MaterialPointPool::BuildTraffic()
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  const PetscInt           nblock = end_ - begin_;
  std::vector<PetscSFNode> remote(nblock);
  PetscInt                 n_remote = 0;
  for (PetscInt k = 0; k < nblock; k++) {
    const PetscInt g = begin_ + k;
    int            r = 0;
    while (offsets_[r + 1] <= g) r++;
    remote[k].rank  = r;
    remote[k].index = g - offsets_[r];
    n_remote += r != rank;
  }
  PetscCall(PetscSFDestroy(&in_sf_));
  PetscCall(PetscSFDestroy(&out_sf_));
  PetscCall(PetscSFCreate(comm_, &in_sf_));
  PetscCall(PetscSFSetGraph(in_sf_, n_local_, nblock, NULL, PETSC_OWN_POINTER, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(in_sf_));
  PetscCall(PetscSFCreate(comm_, &out_sf_));
  PetscCall(PetscSFSetGraph(out_sf_, n_local_, group_rank_ == 0 ? nblock : 0, NULL, PETSC_OWN_POINTER, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(out_sf_));
  remote_bytes_ = n_remote * (PetscInt)(sizeof(PointInput) + (group_rank_ == 0 ? sizeof(PointResult) : 0));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &remote_bytes_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* This group's points become [begin, end): the ones it had stay (with their measured cost), the
   others are created (collectively on the group) and take their state from states[g - begin]
   (none: they start afresh). Collective on the pool. */
PetscErrorCode MaterialPointPool::SetBlock(PetscInt begin, PetscInt end, std::vector<std::vector<PetscReal>> *states)
{
  MPI_Comm                                    group = PetscSubcommChild(subcomm_);
  std::vector<std::unique_ptr<MaterialPoint>> points;
  std::vector<PetscReal>                      cost;
  PetscFunctionBeginUser;
  for (PetscInt g = begin; g < end; g++) {
    if (g >= begin_ && g < end_) {
      points.push_back(std::move(points_[g - begin_]));
      cost.push_back(cost_[g - begin_]);
      continue;
    }
    std::unique_ptr<MaterialPoint> p;
    PetscCall(CreatePoint(group, &p));
    if (states) {
      const std::vector<PetscReal> &b = (*states)[g - begin];
      PetscCall(UnpackPoint(*p, b.data(), b.size()));
    }
    points.push_back(std::move(p));
    cost.push_back(0);
  }
  points_ = std::move(points);
  cost_   = std::move(cost);
  begin_ = begin, end_ = end;
  PetscCall(BuildTraffic());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -material_rebalance: blocks of equal measured cost, the points that change group sent with their
   state from rank j of the old group to rank j of the new one. */
PetscErrorCode MaterialPointPool::Rebalance()
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  const PetscMPIInt color = subcomm_->color;
  /* every point's cost in global order (the groups' first ranks in order hold the blocks in order):
     its force evaluations so far, the bulk of an RVE's work and the same on every run (so the blocks
     are), or for a material without work counters the time it took */
  std::vector<PetscReal> mine;
  PetscInt               counted = 0;
  for (size_t k = 0; group_rank_ == 0 && k < points_.size(); k++) {
    MaterialCounters w;
    points_[k]->AddCounters(w);
    mine.push_back((PetscReal)(w.force_evals + w.tangent_force_evals));
    counted += w.force_evals + w.tangent_force_evals;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &counted, 1, MPIU_INT, MPI_SUM, comm_));
  if (!counted && group_rank_ == 0) mine = cost_;
  PetscMPIInt              n = (PetscMPIInt)mine.size();
  std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  PetscCheck(displs[size] == n_global_, comm_, PETSC_ERR_PLIB, "rebalance: %d costs for %" PetscInt_FMT " points", displs[size], n_global_);
  std::vector<PetscReal> cost(n_global_);
  PetscCallMPI(MPI_Allgatherv(mine.data(), n, MPIU_REAL, cost.data(), counts.data(), displs.data(), MPIU_REAL, comm_));
  /* the old blocks (each group's begin) and the new ones: cuts at equal shares of the total cost */
  std::vector<PetscInt> old_begin(size), ob(n_groups_ + 1, n_global_), nb(n_groups_ + 1, n_global_);
  PetscCallMPI(MPI_Allgather(&begin_, 1, MPIU_INT, old_begin.data(), 1, MPIU_INT, comm_));
  for (PetscInt c = 0; c < n_groups_; c++) ob[c] = old_begin[c * comm_size_];
  std::vector<PetscReal> prefix(n_global_ + 1, 0);
  for (PetscInt g = 0; g < n_global_; g++) prefix[g + 1] = prefix[g] + cost[g];
  const PetscReal total = prefix[n_global_];
  nb[0]                 = 0;
  for (PetscInt c = 1; c < n_groups_; c++) {
    const PetscReal target = total * (PetscReal)c / (PetscReal)n_groups_;
    PetscInt        g      = (PetscInt)(std::lower_bound(prefix.begin(), prefix.end(), target) - prefix.begin());
    if (g > 0 && target - prefix[g - 1] < prefix[g] - target) g--; /* the nearer cut */
    nb[c] = std::max(nb[c - 1], std::min(g, n_global_));
  }
  auto worst = [&](const std::vector<PetscInt> &b) {
    PetscReal w = 0;
    for (PetscInt c = 0; c < n_groups_; c++) w = std::max(w, prefix[b[c + 1]] - prefix[b[c]]);
    return total > 0 ? w * n_groups_ / total : 1.0;
  };
  imbalance_before_ = worst(ob);
  imbalance_after_  = worst(nb);
  auto group_of     = [&](const std::vector<PetscInt> &b, PetscInt g) { return (PetscInt)(std::upper_bound(b.begin(), b.end(), g) - b.begin()) - 1; };
  moved_            = 0;
  for (PetscInt g = 0; g < n_global_; g++) moved_ += group_of(ob, g) != group_of(nb, g);
  /* this rank's part of every point that leaves its group, to rank j of the new group */
  std::vector<std::vector<PetscReal>> out(size);
  for (PetscInt g = begin_; g < end_; g++) {
    const PetscInt c = group_of(nb, g);
    if (c == color) continue;
    std::vector<PetscReal> b;
    PetscCall(PackPoint(*points_[g - begin_], b));
    std::vector<PetscReal> &o = out[c * comm_size_ + group_rank_];
    o.push_back((PetscReal)g);
    o.push_back((PetscReal)b.size());
    o.insert(o.end(), b.begin(), b.end());
  }
  std::vector<PetscMPIInt> scount(size), rcount(size), sdispl(size + 1, 0), rdispl(size + 1, 0);
  for (PetscMPIInt r = 0; r < size; r++) scount[r] = (PetscMPIInt)out[r].size();
  PetscCallMPI(MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm_));
  std::vector<PetscReal> send, recv;
  for (PetscMPIInt r = 0; r < size; r++) {
    sdispl[r + 1] = sdispl[r] + scount[r];
    rdispl[r + 1] = rdispl[r] + rcount[r];
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  recv.resize(rdispl[size]);
  PetscCallMPI(MPI_Alltoallv(send.data(), scount.data(), sdispl.data(), MPIU_REAL, recv.data(), rcount.data(), rdispl.data(), MPIU_REAL, comm_));
  const PetscInt                      begin = nb[color], end = nb[color + 1];
  std::vector<std::vector<PetscReal>> states(end - begin);
  for (size_t at = 0; at + 2 <= recv.size();) {
    const PetscInt g = (PetscInt)recv[at], len = (PetscInt)recv[at + 1];
    PetscCheck(g >= begin && g < end, PETSC_COMM_SELF, PETSC_ERR_PLIB, "rebalance: point %" PetscInt_FMT " sent to the wrong group", g);
    states[g - begin].assign(recv.begin() + at + 2, recv.begin() + at + 2 + len);
    at += 2 + (size_t)len;
  }
  PetscCall(SetBlock(begin, end, &states));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::Evaluate(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, bool tangents, Tangents *D, EvaluationKind kind)
{
  PetscFunctionBeginUser;
  if (rebalance_after_ > 0 && kind == EvaluationKind::Trial && evaluations_++ == rebalance_after_) PetscCall(Rebalance());
  PetscCall(EvaluateBlock(F, Fdot, out, tangents, D, kind));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::EvaluateBlock(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, bool tangents, Tangents *D, EvaluationKind kind)
{
  const PetscInt           nblock = end_ - begin_;
  std::vector<PointInput>  in(n_local_), block(nblock);
  std::vector<PointResult> res(n_local_), done(group_rank_ == 0 ? nblock : 0);
  std::vector<std::string> reasons(nblock);
  PetscInt                 failed = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_evaluate_, 0, 0, 0, 0));
  for (PetscInt k = 0; k < n_local_; k++)
    for (int c = 0; c < 4; c++) {
      in[k].F[c]    = F[k].a[c / 2][c % 2];
      in[k].Fdot[c] = Fdot[k].a[c / 2][c % 2];
    }
  PetscCall(PetscSFBcastBegin(in_sf_, in_type_, in.data(), block.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(in_sf_, in_type_, in.data(), block.data(), MPI_REPLACE));

  for (PetscInt k = 0; k < nblock; k++) {
    Tensor2 Fg, Fdg;
    for (int c = 0; c < 4; c++) {
      Fg.a[c / 2][c % 2]  = block[k].F[c];
      Fdg.a[c / 2][c % 2] = block[k].Fdot[c];
    }
    MaterialPoint   &mp = *points_[k];
    MaterialResponse r, status;
    Tangents         T;
    PetscLogDouble   t0, t1, t2;
    PetscCall(PetscTime(&t0));
    PetscCall(mp.Evaluate(Fg, Fdg, kind, &r));
    PetscCall(PetscTime(&t1));
    time_trial_ += t1 - t0;
    cost_[k] += t1 - t0;
    if (r.ok && tangents) { /* not `D`: a rank without points of its own evaluates the others' */
      PetscCall(PetscLogEventBegin(ev_tangents_, 0, 0, 0, 0));
      /* tangents for output leave the work counters as they are, like the output evaluation itself */
      PetscCall(ComputeTangents(mp, Fg, Fdg, r, tangent_, &T, &status, kind == EvaluationKind::Output ? EvaluationKind::Output : EvaluationKind::Perturbed));
      PetscCall(PetscLogEventEnd(ev_tangents_, 0, 0, 0, 0));
      PetscCall(PetscTime(&t2));
      time_tangents_ += t2 - t1;
      cost_[k] += t2 - t1;
      if (!status.ok) {
        r.ok             = false;
        r.tangent_failed = true;
        r.reason         = "tangent: " + status.reason;
      } else if (kind == EvaluationKind::Trial) mp.KeepTangents(Fg, Fdg, r, T);
      r.iterations += status.iterations;
    }
    reasons[k] = r.reason;
    failed += !r.ok;
    if (group_rank_ != 0) continue; /* the group's other ranks hold the same values */
    PointResult &s = done[k];
    for (int c = 0; c < 4; c++) s.sigma[c] = r.sigma.a[c / 2][c % 2];
    s.rho        = r.rho;
    s.residual   = r.residual;
    s.ok         = r.ok ? 1 : r.tangent_failed ? 2 : 0; /* 2: the stress found, its tangents not */
    s.iterations = r.iterations;
    s.snes_its   = r.snes_its;
    s.ksp_its    = r.ksp_its;
    for (int i = 0; i < 9; i++) {
      s.De[i] = T.De[i / 3][i % 3];
      s.Dv[i] = T.Dv[i / 3][i % 3];
    }
  }
  PetscCall(PetscSFReduceBegin(out_sf_, out_type_, done.data(), res.data(), MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(out_sf_, out_type_, done.data(), res.data(), MPI_REPLACE));

  /* failure reasons travel only when something failed */
  std::vector<PointReason> why;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPIU_INT, MPI_SUM, comm_));
  if (failed) {
    std::vector<PointReason> sent(group_rank_ == 0 ? nblock : 0);
    for (size_t k = 0; k < sent.size(); k++) PetscCall(PetscStrncpy(sent[k].text, reasons[k].c_str(), sizeof sent[k].text));
    why.resize(n_local_);
    PetscCall(PetscSFReduceBegin(out_sf_, reason_type_, sent.data(), why.data(), MPI_REPLACE));
    PetscCall(PetscSFReduceEnd(out_sf_, reason_type_, sent.data(), why.data(), MPI_REPLACE));
  }
  for (PetscInt k = 0; k < n_local_; k++) {
    const PointResult &s = res[k];
    out[k]               = MaterialResponse();
    out[k].sigma         = {
              {{s.sigma[0], s.sigma[1]}, {s.sigma[2], s.sigma[3]}}
    };
    out[k].rho            = s.rho;
    out[k].ok             = s.ok == 1;
    out[k].tangent_failed = s.ok == 2;
    out[k].iterations     = (PetscInt)s.iterations;
    out[k].snes_its       = (PetscInt)s.snes_its;
    out[k].ksp_its        = (PetscInt)s.ksp_its;
    out[k].residual       = s.residual;
    if (!out[k].ok) out[k].reason = why[k].text;
    if (tangents)
      for (int i = 0; i < 9; i++) {
        D[k].De[i / 3][i % 3] = s.De[i];
        D[k].Dv[i / 3][i % 3] = s.Dv[i];
      }
  }
  PetscCall(PetscLogEventEnd(ev_evaluate_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::GlobalTimes(PetscReal *trial_s, PetscReal *tangent_s) const
{
  PetscReal t[2] = {(PetscReal)time_trial_, (PetscReal)time_tangents_};
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, t, 2, MPIU_REAL, MPIU_MAX, comm_));
  *trial_s   = t[0];
  *tangent_s = t[1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::Commit()
{
  PetscFunctionBeginUser;
  for (auto &p : points_) PetscCall(p->Commit());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::Revert()
{
  PetscFunctionBeginUser;
  for (auto &p : points_) PetscCall(p->Revert());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* [group's first point, end, then per point its blob] */
PetscErrorCode MaterialPointPool::PackPoint(MaterialPoint &p, std::vector<PetscReal> &out)
{
  StateDeclaration d("point");
  PetscFunctionBeginUser;
  p.DeclareState(d);
  PetscCall(PackState(d, out));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::UnpackPoint(MaterialPoint &p, const PetscReal *in, size_t n)
{
  StateDeclaration d("point");
  PetscFunctionBeginUser;
  p.DeclareState(d);
  PetscCall(UnpackState(d, in, n));
  PetscCall(p.AfterStateRead());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::DeclareState(StateDeclaration &d, const std::vector<PetscInt> &ids)
{
  PetscFunctionBeginUser;
  if (!prototype_) PetscCall(CreatePoint(PETSC_COMM_SELF, &prototype_));
  StateDeclaration proto("point");
  prototype_->DeclareState(proto);
  const std::vector<std::string> names = NestedColumns(proto);
  saved_.clear();
  /* one state a point, its group's first rank's (which holds the RVE's unknowns; the others hold
     none of their own): a checkpoint then reads back on groups of any size (AfterStateRead) */
  for (size_t k = 0; group_rank_ == 0 && k < points_.size(); k++) {
    StateDeclaration pd("point");
    points_[k]->DeclareState(pd);
    saved_.push_back({begin_ + (PetscInt)k, {}});
    PetscCall(PackNested(pd, saved_.back().columns));
  }
  saved_begin_ = begin_, saved_end_ = end_;
  d.Scalar("block_begin", &saved_begin_, Combine::Local);
  d.Scalar("block_end", &saved_end_, Combine::Local);
  StateTable &t = d.Table("points", StateEntity::MaterialPoint)
                    .Records([this] { return saved_.size(); }, [this, &ids](size_t r) { return (std::uint64_t)ids[saved_[r].point]; },
                             [this, n = names.size()](size_t m) {
                               saved_.assign(m, SavedPoint{-1, std::vector<std::vector<PetscReal>>(n)});
                             },
                             "point")
                    .Ref("point", saved_, &SavedPoint::point, StateEntity::MaterialPoint);
  for (size_t c = 0; c < names.size(); c++)
    t.Ragged(
      names[c], [this, c](size_t r, std::vector<PetscReal> &v) { v = saved_[r].columns[c]; },
      [this, c](size_t r, const PetscReal *v, size_t n) {
        saved_[r].columns[c].assign(v, v + n);
        return PETSC_SUCCESS;
      });
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::AfterStateRead(bool own_layout)
{
  PetscFunctionBeginUser;
  {
    /* a rebalanced run's blocks (-material_rebalance): taken on every rank at once, where every rank
       holds what its writer held */
    PetscInt other = own_layout && (saved_begin_ != begin_ || saved_end_ != end_), all_own = own_layout;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &other, 1, MPIU_INT, MPI_MAX, comm_));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &all_own, 1, MPIU_INT, MPI_MIN, comm_));
    if (other && all_own) {
      PetscCheck(saved_begin_ >= 0 && saved_begin_ <= saved_end_ && saved_end_ <= n_global_, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
                 "the checkpoint's material points of this rank's group are [%" PetscInt_FMT ", %" PetscInt_FMT "), of %" PetscInt_FMT " points", saved_begin_,
                 saved_end_, n_global_);
      PetscCall(SetBlock(saved_begin_, saved_end_, nullptr));
    }
  }
  PetscCall(ShareSavedStates());
  /* every point of the block, in the block's order (the group's ranks together) */
  std::vector<SavedPoint *> of((size_t)(end_ - begin_), nullptr);
  for (SavedPoint &sp : saved_) {
    PetscCheck(sp.point >= begin_ && sp.point < end_, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint's material point %" PetscInt_FMT " is not in this group's block [%" PetscInt_FMT ", %" PetscInt_FMT ")", sp.point, begin_, end_);
    PetscCheck(!of[sp.point - begin_], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint holds material point %" PetscInt_FMT " twice (written with groups of several ranks by an older turgor: continue it on "
               "the same ranks and -material_comm_size)",
               sp.point);
    of[sp.point - begin_] = &sp;
  }
  for (size_t k = 0; k < of.size(); k++) {
    PetscCheck(of[k], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "the checkpoint has no state for material point %" PetscInt_FMT, begin_ + (PetscInt)k);
    StateDeclaration pd("point");
    points_[k]->DeclareState(pd);
    PetscCall(UnpackNested(pd, of[k]->columns));
    PetscCall(points_[k]->AfterStateRead());
  }
  std::vector<SavedPoint>().swap(saved_);
  if (rebalance_after_ > 0) evaluations_ = rebalance_after_ + 1; /* the checkpoint's run had rebalanced, or will not need to now */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The states read are the group roots' (DeclareState): the first rank's, whatever it read, to the
   group's other ranks, each point's columns as [point, columns, then each column's length and
   values]. */
PetscErrorCode MaterialPointPool::ShareSavedStates()
{
  MPI_Comm               group = PetscSubcommChild(subcomm_);
  std::vector<PetscReal> buf;
  PetscFunctionBeginUser;
  if (comm_size_ == 1) PetscFunctionReturn(PETSC_SUCCESS);
  if (group_rank_ == 0)
    for (const SavedPoint &sp : saved_) {
      buf.push_back((PetscReal)sp.point);
      buf.push_back((PetscReal)sp.columns.size());
      for (const std::vector<PetscReal> &c : sp.columns) {
        buf.push_back((PetscReal)c.size());
        buf.insert(buf.end(), c.begin(), c.end());
      }
    }
  PetscInt n = (PetscInt)buf.size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, group));
  PetscCheck(n <= PETSC_MPI_INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP,
             "the material points' states of a group take %" PetscInt_FMT " numbers, more than one message holds", n);
  buf.resize((size_t)n);
  PetscCallMPI(MPI_Bcast(buf.data(), (PetscMPIInt)n, MPIU_REAL, 0, group));
  if (group_rank_ == 0) PetscFunctionReturn(PETSC_SUCCESS);
  saved_.clear();
  for (size_t i = 0; i < buf.size();) {
    SavedPoint sp{(PetscInt)buf[i], std::vector<std::vector<PetscReal>>((size_t)buf[i + 1])};
    i += 2;
    for (std::vector<PetscReal> &c : sp.columns) {
      const size_t m = (size_t)buf[i++];
      c.assign(buf.begin() + (std::ptrdiff_t)i, buf.begin() + (std::ptrdiff_t)(i + m));
      i += m;
    }
    saved_.push_back(std::move(sp));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::GlobalCounters(MaterialCounters *c) const
{
  MaterialCounters k;
  PetscFunctionBeginUser;
  if (group_rank_ == 0)
    for (const auto &p : points_) p->AddCounters(k);
  PetscInt v[17] = {k.solves,           k.failures,       k.iterations,         k.snes_its,
                    k.ksp_its,          k.jacobians,      k.force_evals,        k.tangent_solves,
                    k.output_solves,    k.exact_tangents, k.tangent_linear_its, k.tangent_force_evals,
                    k.predicted_solves, k.skipped_solves, k.bonds_intact,       k.bonds_broken,
                    k.contacts};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 17, MPIU_INT, MPI_SUM, comm_));
  *c = MaterialCounters{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13], v[14], v[15], v[16]};
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::DescribePoints(JsonObject &js, PetscInt points) const
{
  MaterialCounters c;
  PetscFunctionBeginUser;
  PetscCall(GlobalCounters(&c));
  if (model_) model_->Describe(js);
  const std::vector<std::string> terms = model_ ? model_->Physics() : std::vector<std::string>();
  const PetscReal                n     = (PetscReal)PetscMax(points, 1);
  if (std::find(terms.begin(), terms.end(), "glue") != terms.end()) {
    js.Set("rve_bonds_intact_per_point", c.bonds_intact / n);
    js.Set("rve_bonds_broken_per_point", c.bonds_broken / n);
  }
  if (std::find(terms.begin(), terms.end(), "contact") != terms.end()) js.Set("rve_contacts_per_point", c.contacts / n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
