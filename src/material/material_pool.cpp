#include <turgor/material/material_pool.h>
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

PetscErrorCode MaterialPointPool::SetFromOptions()
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
    PetscCall(PetscOptionsString("-material", help.c_str(), "MaterialPointPool", name, name, sizeof name, &set));
    PetscOptionsEnd();
    type_ = name;
    PetscCall(MaterialModelCreate(comm_, type_, &model_));
    if (default_tol_ > 0) model_->SetDefaultTolerance(default_tol_);
    PetscCall(model_->SetFromOptions(comm_));
  }
  PetscOptionsBegin(comm_, NULL, "Renamed options of the material-point pool", "turgor");
  PetscCall(PetscOptionsDeprecated("-rve_comm_size", "-material_comm_size", "0.2", NULL));
  PetscCall(PetscOptionsDeprecated("-rve_tangent", "-material_tangent", "0.2", NULL));
  PetscCall(PetscOptionsDeprecated("-rve_tangent_fdot_typ", "-material_tangent_fdot_typ", "0.2", NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(comm_, "material_", "Material-point groups and tangents", "turgor");
  PetscCall(PetscOptionsInt("-comm_size", "MPI ranks per material-point group (sub-communicator)", "MaterialPointPool", comm_size_, &comm_size_, NULL));
  PetscCall(PetscOptionsEList("-tangent",
                              "Material tangents D^e, D^v: forward or central differences (eqs 46-53: perturbed material evaluations) or implicit (exact: "
                              "an RVE differentiates its relaxed state, dw/dF from G_w dw/dF = -G_F with the relaxation's LU factor; no perturbed solves)",
                              "MaterialPointPool", tangents, 3, tangents[tangent], &tangent, NULL));
  PetscCall(PetscOptionsReal("-tangent_fdot_typ", "Typical velocity gradient Fdot_typ of eq 53 [1/µs]", "MaterialPointPool", tangent_.Fdot_typ,
                             &tangent_.Fdot_typ, NULL));
  PetscOptionsEnd();
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
  for (PetscInt g = begin_; g < end_; g++) {
    std::unique_ptr<MaterialPoint> p;
    PetscCall(model_->CreatePoint(group, &p));
    points_.push_back(std::move(p));
  }

  /* every rank of a group receives its block's inputs; only the group's first rank sends results */
  const PetscInt           nblock = end_ - begin_;
  std::vector<PetscSFNode> remote(nblock);
  PetscInt                 n_remote = 0;
  for (PetscInt k = 0; k < nblock; k++) {
    const PetscInt g = begin_ + k;
    int            r = 0;
    while (offsets[r + 1] <= g) r++;
    remote[k].rank  = r;
    remote[k].index = g - offsets[r];
    n_remote += r != rank;
  }
  PetscCall(PetscSFCreate(comm_, &in_sf_));
  PetscCall(PetscSFSetGraph(in_sf_, n_local_, nblock, NULL, PETSC_OWN_POINTER, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(in_sf_));
  PetscCall(PetscSFCreate(comm_, &out_sf_));
  PetscCall(PetscSFSetGraph(out_sf_, n_local_, group_rank_ == 0 ? nblock : 0, NULL, PETSC_OWN_POINTER, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(out_sf_));
  PetscCall(ContiguousType(sizeof(PointInput) / sizeof(PetscReal), MPIU_REAL, &in_type_));
  PetscCall(ContiguousType(sizeof(PointResult) / sizeof(PetscReal), MPIU_REAL, &out_type_));
  PetscCall(ContiguousType(sizeof(PointReason), MPI_CHAR, &reason_type_));
  remote_bytes_ = n_remote * (PetscInt)(sizeof(PointInput) + (group_rank_ == 0 ? sizeof(PointResult) : 0));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &remote_bytes_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::Evaluate(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, Tangents *D, EvaluationKind kind)
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
    if (r.ok && D) {
      PetscCall(PetscLogEventBegin(ev_tangents_, 0, 0, 0, 0));
      /* tangents for output leave the work counters as they are, like the output evaluation itself */
      PetscCall(ComputeTangents(mp, Fg, Fdg, r, tangent_, &T, &status, kind == EvaluationKind::Output ? EvaluationKind::Output : EvaluationKind::Perturbed));
      PetscCall(PetscLogEventEnd(ev_tangents_, 0, 0, 0, 0));
      PetscCall(PetscTime(&t2));
      time_tangents_ += t2 - t1;
      if (!status.ok) {
        r.ok     = false;
        r.reason = "tangent: " + status.reason;
      }
      r.iterations += status.iterations;
    }
    reasons[k] = r.reason;
    failed += !r.ok;
    if (group_rank_ != 0) continue; /* the group's other ranks hold the same values */
    PointResult &s = done[k];
    for (int c = 0; c < 4; c++) s.sigma[c] = r.sigma.a[c / 2][c % 2];
    s.rho        = r.rho;
    s.residual   = r.residual;
    s.ok         = r.ok ? 1 : 0;
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
    out[k].rho        = s.rho;
    out[k].ok         = s.ok != 0;
    out[k].iterations = (PetscInt)s.iterations;
    out[k].snes_its   = (PetscInt)s.snes_its;
    out[k].ksp_its    = (PetscInt)s.ksp_its;
    out[k].residual   = s.residual;
    if (!out[k].ok) out[k].reason = why[k].text;
    if (D)
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
PetscErrorCode MaterialPointPool::SaveState(StateBlob &state)
{
  PetscFunctionBeginUser;
  state.Put((PetscReal)begin_);
  state.Put((PetscReal)end_);
  for (auto &p : points_) {
    StateBlob b;
    PetscCall(p->SaveState(b));
    state.Put(b.data);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::LoadState(StateBlob &state)
{
  PetscInt b = -1, e = -1;
  PetscFunctionBeginUser;
  PetscCheck(state.Get(&b) && state.Get(&e), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "the checkpoint's material points are missing");
  PetscCheck(b == begin_ && e == end_, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's material points of this rank's group are [%" PetscInt_FMT ", %" PetscInt_FMT "), this run's [%" PetscInt_FMT ", %" PetscInt_FMT
             ") (another -material_comm_size?)",
             b, e, begin_, end_);
  for (size_t k = 0; k < points_.size(); k++) {
    StateBlob pb;
    PetscCheck(state.Get(pb.data), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "the checkpoint's state of material point %" PetscInt_FMT " is missing",
               begin_ + (PetscInt)k);
    PetscCall(points_[k]->LoadState(pb));
    PetscCheck(pb.Done(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint's state of material point %" PetscInt_FMT " has %zu numbers more than it reads", begin_ + (PetscInt)k, pb.data.size() - pb.pos);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::GlobalCounters(MaterialCounters *c) const
{
  MaterialCounters k;
  PetscFunctionBeginUser;
  if (group_rank_ == 0)
    for (const auto &p : points_) p->AddCounters(k);
  PetscInt v[12] = {k.solves,        k.failures,       k.iterations,         k.snes_its,           k.ksp_its, k.jacobians, k.force_evals, k.tangent_solves,
                    k.output_solves, k.exact_tangents, k.tangent_linear_its, k.tangent_force_evals};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 12, MPIU_INT, MPI_SUM, comm_));
  *c = MaterialCounters{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]};
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
