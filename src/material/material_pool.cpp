#include <turgor/material/material_pool.h>
#include <turgor/material/neo_hookean.h>
#include <cstring>

namespace turgor {

MaterialPointPool::~MaterialPointPool()
{
  points_.clear(); /* before the sub-communicator they live on */
  (void)PetscSubcommDestroy(&subcomm_);
}

PetscErrorCode MaterialPointPool::SetFromOptions()
{
  const char *const tangents[] = {"forward", "central"};
  PetscInt          tangent    = 0;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm_, NULL, "Material points of the coarse model", "turgor");
  PetscCall(PetscOptionsString("-material", "Material point: rve (fine-scale RVE) or neo_hookean (closed form, verification)", "MaterialPointPool", material_, material_, sizeof material_, NULL));
  PetscCall(PetscOptionsInt("-rve_comm_size", "MPI ranks per material-point group (sub-communicator)", "MaterialPointPool", comm_size_, &comm_size_, NULL));
  PetscCall(PetscOptionsEList("-rve_tangent", "Finite differences of the tangents (eqs 46-53)", "MaterialPointPool", tangents, 2, tangents[tangent], &tangent, NULL));
  PetscCall(PetscOptionsReal("-rve_tangent_fdot_typ", "Typical velocity gradient Fdot_typ of eq 53 [1/µs]", "MaterialPointPool", tangent_.Fdot_typ, &tangent_.Fdot_typ, NULL));
  PetscOptionsEnd();
  tangent_.central = tangent == 1;
  PetscCheck(!strcmp(material_, "rve") || !strcmp(material_, "neo_hookean"), comm_, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option -material = %s: unknown material (known: rve, neo_hookean)", material_);
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCheck(comm_size_ >= 1 && size % comm_size_ == 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_comm_size = %" PetscInt_FMT ": must divide the number of MPI ranks (%d)", comm_size_, size);
  PetscCheck(tangent_.Fdot_typ > 0, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option -rve_tangent_fdot_typ = %g: must be > 0", (double)tangent_.Fdot_typ);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MaterialPointPool::SetUp(PetscInt n_local)
{
  PetscMPIInt size, color;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgMaterialPoints", PETSC_OBJECT_CLASSID, &ev_evaluate_));
  PetscCall(PetscLogEventRegister("TgTangents", PETSC_OBJECT_CLASSID, &ev_tangents_));
  n_local_ = n_local;
  offset_  = 0;
  PetscCallMPI(MPI_Exscan(&n_local_, &offset_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(&n_local_, &n_global_, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  n_groups_ = size / comm_size_;
  PetscCall(PetscSubcommCreate(comm_, &subcomm_));
  PetscCall(PetscSubcommSetNumber(subcomm_, n_groups_));
  PetscCall(PetscSubcommSetType(subcomm_, PETSC_SUBCOMM_CONTIGUOUS));
  color  = subcomm_->color;
  begin_ = (color * n_global_) / n_groups_;
  end_   = ((color + 1) * n_global_) / n_groups_;
  MPI_Comm group = PetscSubcommChild(subcomm_);
  for (PetscInt g = begin_; g < end_; g++) {
    if (!strcmp(material_, "rve")) {
      auto rve = std::make_unique<RVE>(group);
      PetscCall(rve->SetFromOptions());
      PetscCall(rve->SetUp());
      points_.push_back(std::move(rve));
    } else {
      auto nh = std::make_unique<NeoHookean>();
      PetscCall(nh->SetFromOptions(group));
      points_.push_back(std::move(nh));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Per point: sigma (4), rho, ok, iterations, snes, ksp, residual, De (9), Dv (9). */
static const int kSlot = 28;

PetscErrorCode MaterialPointPool::Evaluate(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, Tangents *D)
{
  std::vector<PetscReal> in(8 * n_local_), all(8 * n_global_), res(kSlot * n_global_, 0.0);
  std::vector<int>       counts, displs;
  PetscMPIInt            size, grank, n8 = (PetscMPIInt)(8 * n_local_);
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(ev_evaluate_, 0, 0, 0, 0));
  for (PetscInt k = 0; k < n_local_; k++)
    for (int c = 0; c < 4; c++) {
      in[8 * k + c]     = F[k].a[c / 2][c % 2];
      in[8 * k + 4 + c] = Fdot[k].a[c / 2][c % 2];
    }
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  counts.resize(size);
  displs.resize(size);
  PetscCallMPI(MPI_Allgather(&n8, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_));
  displs[0] = 0;
  for (int r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
  PetscCallMPI(MPI_Allgatherv(in.data(), n8, MPIU_REAL, all.data(), counts.data(), displs.data(), MPIU_REAL, comm_));

  /* this group's block; only the group's first rank reports (the others hold the same values) */
  PetscCallMPI(MPI_Comm_rank(PetscSubcommChild(subcomm_), &grank));
  std::vector<std::string> reasons(end_ - begin_);
  for (PetscInt g = begin_; g < end_; g++) {
    Tensor2 Fg, Fdg;
    for (int c = 0; c < 4; c++) {
      Fg.a[c / 2][c % 2]  = all[8 * g + c];
      Fdg.a[c / 2][c % 2] = all[8 * g + 4 + c];
    }
    MaterialPoint   &mp = *points_[g - begin_];
    MaterialResponse r, status;
    Tangents         T;
    PetscLogDouble t0, t1, t2;
    PetscCall(PetscTime(&t0));
    PetscCall(mp.Evaluate(Fg, Fdg, EvaluationKind::Trial, &r));
    PetscCall(PetscTime(&t1));
    time_trial_ += t1 - t0;
    if (r.ok && D) {
      PetscCall(PetscLogEventBegin(ev_tangents_, 0, 0, 0, 0));
      PetscCall(ComputeTangents(mp, Fg, Fdg, r, tangent_, &T, &status));
      PetscCall(PetscLogEventEnd(ev_tangents_, 0, 0, 0, 0));
      PetscCall(PetscTime(&t2));
      time_tangents_ += t2 - t1;
      if (!status.ok) {
        r.ok     = false;
        r.reason = "tangent: " + status.reason;
      }
      r.iterations += status.iterations;
    }
    reasons[g - begin_] = r.reason;
    if (grank != 0) continue;
    PetscReal *s = &res[kSlot * g];
    for (int c = 0; c < 4; c++) s[c] = r.sigma.a[c / 2][c % 2];
    s[4] = r.rho;
    s[5] = r.ok ? 1 : 0;
    s[6] = r.iterations;
    s[7] = r.snes_its;
    s[8] = r.ksp_its;
    s[9] = r.residual;
    for (int i = 0; i < 9; i++) {
      s[10 + i] = T.De[i / 3][i % 3];
      s[19 + i] = T.Dv[i / 3][i % 3];
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, res.data(), (PetscMPIInt)res.size(), MPIU_REAL, MPI_SUM, comm_));

  /* failure reasons travel only when something failed */
  PetscInt nfail = 0;
  for (PetscInt g = 0; g < n_global_; g++) nfail += res[kSlot * g + 5] == 0;
  std::vector<char> why;
  if (nfail) {
    why.assign(160 * n_global_, 0);
    if (grank == 0)
      for (PetscInt g = begin_; g < end_; g++) strncpy(&why[160 * g], reasons[g - begin_].c_str(), 159);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, why.data(), (PetscMPIInt)why.size(), MPI_CHAR, MPI_SUM, comm_));
  }
  for (PetscInt k = 0; k < n_local_; k++) {
    const PetscInt   g = offset_ + k;
    const PetscReal *s = &res[kSlot * g];
    out[k]             = MaterialResponse();
    out[k].sigma       = {{{s[0], s[1]}, {s[2], s[3]}}};
    out[k].rho         = s[4];
    out[k].ok          = s[5] != 0;
    out[k].iterations  = (PetscInt)s[6];
    out[k].snes_its    = (PetscInt)s[7];
    out[k].ksp_its     = (PetscInt)s[8];
    out[k].residual    = s[9];
    if (!out[k].ok) out[k].reason = std::string(&why[160 * g]);
    if (D)
      for (int i = 0; i < 9; i++) {
        D[k].De[i / 3][i % 3] = s[10 + i];
        D[k].Dv[i / 3][i % 3] = s[19 + i];
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

PetscErrorCode MaterialPointPool::GlobalCounters(RVECounters *c) const
{
  PetscMPIInt grank;
  PetscInt    v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscSubcommChild(subcomm_), &grank));
  if (grank == 0)
    for (const auto &p : points_)
      if (auto *rve = dynamic_cast<const RVE *>(p.get())) {
        const RVECounters &k = rve->Counters();
        const PetscInt     w[8] = {k.solves, k.failures, k.iterations, k.snes_its, k.ksp_its, k.jacobians, k.force_evals, k.tangent_solves};
        for (int i = 0; i < 8; i++) v[i] += w[i];
      }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 8, MPIU_INT, MPI_SUM, comm_));
  *c = RVECounters{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]};
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
