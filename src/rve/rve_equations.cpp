#include <turgor/rve/rve_equations.h>
#include <algorithm>
#include <cstring>
#include <limits>
#include <set>

namespace turgor {

PetscErrorCode RVEEquations::SetUp(MPI_Comm comm, const PeriodicCell &cell, const PhysicsSpec &physics, PetscReal fluid_density)
{
  const ParticleSet &P = cell.GetTissue().particles;
  PetscFunctionBeginUser;
  cell_ = &cell;
  PetscCallMPI(MPI_Comm_rank(comm, &rank_));
  PetscCall(model_.SetUp(physics, P));
  x_.assign(2 * P.n, 0);
  v_.assign(2 * P.n, 0);
  f_.assign(2 * P.n, 0);
  r_.assign(cell.NumUnknowns(), 0);
  /* scales: lengths by the cell size, forces by a characteristic force of the physics (k_w x cell
     size, or the fluid's c_s^2 rho x cell size) */
  force_scale_ = physics.CharacteristicForce(cell.LengthScale(), fluid_density);
  if (force_scale_ == 0) force_scale_ = cell.LengthScale(); /* no term sets one: forces in µN */
  PetscCheck(force_scale_ > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "RVE: the force scale must be > 0 (check -wall_stiffness / -sph_sound_speed)");
  SetDeformation(Tensor2::Identity(), Tensor2::Zero());
  PetscFunctionReturn(PETSC_SUCCESS);
}

void RVEEquations::SetDeformation(const Tensor2 &F, const Tensor2 &Fdot)
{
  F_    = F;
  Fdot_ = Fdot;
  cell_->Deform(F, Fdot, x_.data(), v_.data());
  model_.SetPeriodicImages(cell_->ModelImages(F, Fdot));
  version_++;
}

PetscErrorCode RVEEquations::Compute(Vec W)
{
  PetscObjectId    id;
  PetscObjectState state;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetId((PetscObject)W, &id));
  PetscCall(PetscObjectStateGet((PetscObject)W, &state));
  if (id == kept_id_ && state == kept_state_ && version_ == kept_version_) PetscFunctionReturn(PETSC_SUCCESS);
  if (rank_ == 0) {
    const PetscScalar           *w;
    const std::vector<PetscInt> &free = cell_->Free();
    PetscCall(VecGetArrayRead(W, &w));
    cell_->Place(F_, w, x_.data());
    PetscCall(VecRestoreArrayRead(W, &w));
    const PetscInt rebuilds = model_.Neighbours().Rebuilds();
    if (cell_->InvertedCell(x_.data()) >= 0) { /* outside the forces' domain (a gas law's p0 A0 / A): a domain error for the relaxation */
      std::fill(f_.begin(), f_.end(), std::numeric_limits<PetscReal>::quiet_NaN());
      for (PetscReal &w : virial_) w = std::numeric_limits<PetscReal>::quiet_NaN();
    } else {
      PetscCall(model_.ComputeForces(x_.data(), v_.data(), f_.data(), virial_));
      cell_->ReturnHaloForces(f_.data());
    }
    force_evals_++;
    if (model_.Neighbours().Rebuilds() != rebuilds) { /* the lists were built at this lattice */
      build_F_    = F_;
      build_Fdot_ = Fdot_;
    }
    for (size_t k = 0; k < free.size(); k++) {
      r_[2 * k]     = -f_[2 * free[k]] / force_scale_;
      r_[2 * k + 1] = -f_[2 * free[k] + 1] / force_scale_;
    }
  }
  kept_id_      = id;
  kept_state_   = state;
  kept_version_ = version_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEEquations::Residual(Vec W, Vec R)
{
  PetscFunctionBeginUser;
  PetscCall(Compute(W));
  if (R) {
    PetscScalar *r;
    PetscInt     n;
    PetscCall(VecGetLocalSize(R, &n));
    PetscCall(VecGetArray(R, &r));
    if (n) std::memcpy(r, r_.data(), n * sizeof(PetscScalar));
    PetscCall(VecRestoreArray(R, &r));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEEquations::ResidualNorm(Vec W, Vec R, PetscReal *norm)
{
  PetscFunctionBeginUser;
  PetscCall(Residual(W, R));
  PetscCall(VecNorm(R, NORM_2, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEEquations::Virial(Vec W, PetscReal virial[4])
{
  PetscFunctionBeginUser;
  PetscCall(Compute(W));
  for (int c = 0; c < 4; c++) virial[c] = rank_ == 0 ? virial_[c] : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The force evaluations, the deformation the lists were last built at, the force model's state. */
void RVEEquations::DeclareState(StateDeclaration &d)
{
  d.Scalar("force_evals", &force_evals_, Combine::Owner);
  d.Array("build_F", &build_F_.a[0][0], 4, Combine::Owner);
  d.Array("build_Fdot", &build_Fdot_.a[0][0], 4, Combine::Owner);
  DeclareTermState(d);
}

/* The lists restored where and on the lattice they were built last; the deformation back at the
   identity (the next evaluation sets its own). */
PetscErrorCode RVEEquations::AfterStateRead()
{
  PetscFunctionBeginUser;
  model_.SetPeriodicImages(cell_->ModelImages(build_F_, build_Fdot_));
  /* the group's other ranks never evaluate the forces: the terms' state read (the first rank's) is
     not theirs to take up */
  if (rank_ == 0) PetscCall(model_.AfterStateRead(x_.data(), v_.data(), 0, true));
  SetDeformation(Tensor2::Identity(), Tensor2::Zero());
  kept_version_ = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool RVEEquations::Admissible(std::string *why) const
{
  return cell_->Admissible(x_.data(), F_, model_.Images(), why);
}

PetscErrorCode RVEEquations::AcceptStep(Vec W)
{
  PetscFunctionBeginUser;
  PetscCall(Compute(W));
  if (rank_ == 0) PetscCall(model_.AcceptStep(x_.data(), v_.data(), 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void RVEEquations::DeclareTermState(StateDeclaration &d)
{
  std::deque<StateDeclaration> model;
  model_.DeclareState(model);
  for (StateDeclaration &m : model) d.Include(std::move(m));
}

PetscErrorCode RVEEquations::AfterTermStateRead()
{
  PetscFunctionBeginUser;
  PetscCall(model_.AfterStateRead(x_.data(), v_.data(), 0, true));
  kept_version_ = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode RVEEquations::PatternColumns(std::vector<std::vector<PetscInt>> &cols) const
{
  const ParticleSet              &P    = cell_->GetTissue().particles;
  const NeighbourSearch          &nb   = model_.Neighbours();
  const std::vector<PetscInt>    &free = cell_->Free();
  std::vector<std::set<PetscInt>> adj(P.n);
  PetscFunctionBeginUser;
  if (cell_->HasHalo()) {
    cell_->PolygonCouplings(x_.data(), cols);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  auto link = [&](PetscInt i, PetscInt j) {
    adj[i].insert(j);
    adj[j].insert(i);
  };
  for (PetscInt i = 0; i < P.n; i++) adj[i].insert(i);
  for (const Spring &s : P.springs) link(s.i, s.j);
  const PointSegmentList &ps = nb.ParticleSpringPairs();
  for (size_t q = 0; q < ps.size(); q++) {
    link(ps.p[q], P.springs[ps.s[q]].i);
    link(ps.p[q], P.springs[ps.s[q]].j);
  }
  const PairList &fp = nb.FluidPairs();
  for (PetscInt i = 0; i < fp.Rows(); i++)
    for (PetscInt q = fp.start[i]; q < fp.start[i + 1]; q++) link(i, fp.j[q]);
  std::vector<PetscInt> dof(P.n, -1);
  for (size_t k = 0; k < free.size(); k++) dof[free[k]] = (PetscInt)k;
  cols.assign(free.size(), {});
  for (size_t k = 0; k < free.size(); k++) {
    std::set<PetscInt> two;
    for (PetscInt j : adj[free[k]])
      for (PetscInt l : adj[j])
        if (dof[l] >= 0) two.insert(dof[l]);
    cols[k].assign(two.begin(), two.end());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
