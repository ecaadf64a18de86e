#include <turgor/core/errors.h>
#include <turgor/core/finite_scan.h>
#include <turgor/fine/fine_equations.h>
#include <turgor/parallel/rank_reductions.h>
#include <turgor/ts/low_storage_rk.h>
#include <turgor/ts/velocity_verlet.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace turgor {

void FineEquations::SetUp(ForceModel &model, Controls &controls, TissueDistribution *halo, const ParticleSet &P, ParticleFields &fields)
{
  model_    = &model;
  controls_ = &controls;
  halo_     = halo;
  P_        = &P;
  n_owned_  = P.NumOwned();
  fixed_.clear(); /* the clamps, set with the tissue */
  for (PetscInt i = 0; i < n_owned_; i++)
    if (P.fixed[i]) fixed_.push_back(i);
  n_all_ = P.n;
  /* the state's fields: the model reads them on the halo too (the halo's exchange pairs two
     components per particle) */
  fields.Declare("position", "µm", 2, kHalo | kSnapshot | kCheckpoint, [this] { return x_local_; });
  fields.Declare("velocity", "µm/µs", 2, kHalo | kSnapshot | kCheckpoint, [this] { return v_local_; });
  halo_fields_ = fields.With(kHalo);
}

PetscErrorCode FineEquations::SetTS(TS ts, IS is_x, IS is_v, std::function<PetscErrorCode(PetscReal, Vec, Vec, PetscBool *)> observe)
{
  PetscFunctionBeginUser;
  ts_      = ts;
  observe_ = std::move(observe);
  PetscCall(TSSetRHSFunction(ts, NULL, RHSFunction, this));
  PetscCall(TSRHSSplitSetIS(ts, "position", is_x));
  PetscCall(TSRHSSplitSetIS(ts, "momentum", is_v));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "position", NULL, RHSPosition, this));
  PetscCall(TSRHSSplitSetRHSFunction(ts, "momentum", NULL, RHSMomentum, this));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::ConfigureIntegrator(TS ts, ParticleFields &fields, bool predict_velocity)
{
  PetscBool symplectic, kdk;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSBASICSYMPLECTIC, &symplectic));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &kdk));
  PetscCheck(!predict_velocity || kdk, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_INCOMP,
             "Option -fine_predict_velocity: only -ts_type verlet predicts the velocity its forces see (this run's integrator is another)");
  predict_ = predict_velocity;
  held_    = false;
  kdk_     = kdk;
  model_->SetCallerKnowsAcceptedState(kdk);
  /* a stage with non-finite values is rejected; TS verlet checks its step's end itself, as it writes it */
  PetscCall(TSSetFunctionDomainError(ts, kdk ? NULL : CheckDomain));
  PetscBool lsrk;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSLSRK, &lsrk));
  if (lsrk && halo_) { /* the rates carry room for the halo's forces after their accelerations (Accelerations) */
    PetscCall(TSLSRKSetRateRoom(ts, 2 * (n_all_ - n_owned_)));
    rate_room_ = true;
  }
  if (!symplectic && !kdk) PetscFunctionReturn(PETSC_SUCCESS);
  /* the split integrators' velocities of the last position update; a distributed run without
     controls gathers the halo's into their tail (LocalState: no copy of the velocities) */
  v_stale_.assign(2 * (halo_ && !controls_->Active() ? n_all_ : n_owned_), 0);
  split_ = true;
  fields.Declare("drift_velocity", "µm/µs", 2, kCheckpoint, [this] { return v_stale_.data(); });
  if (predict_) {
    a_last_.assign(2 * n_owned_, 0);
    fields.Declare("last_acceleration", "µm/µs²", 2, kCheckpoint, [this] { return a_last_.data(); });
  }
  if (kdk) {
    drift_fraction_ = 1.0; /* one drift of h per step */
    if (controls_->Active()) {
      PetscCall(TSVerletSetConstraints(ts, ImposeControls, this));
      held_ = true;
    }
    if (halo_) { /* its accelerations carry room for the halo's forces (Accelerations) */
      PetscCall(TSVerletSetAccelerationRoom(ts, 2 * (n_all_ - n_owned_)));
      acceleration_room_ = true;
      if (v_stale_.size() == (size_t)(2 * n_all_)) std::vector<PetscReal>().swap(vw_); /* the set-up's copy: the force evaluations gather into v_stale_ */
    }
  } else {
    /* PETSc's basicsymplectic defaults to first-order symplectic Euler; velocity Verlet unless asked */
    const char *prefix;
    PetscBool   chosen;
    PetscCall(TSGetOptionsPrefix(ts, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_basicsymplectic_type", &chosen));
    if (!chosen) PetscCall(TSBasicSymplecticSetType(ts, TSBASICSYMPLECTICVELVERLET));
    /* PETSc 3.18's schemes: velocity Verlet drifts twice by h/2, symplectic Euler once by h; for the
       others a controlled velocity is taken at the start of each drift (first order in time) */
    TSBasicSymplecticType scheme;
    PetscBool             verlet, euler;
    PetscCall(TSBasicSymplecticGetType(ts, &scheme));
    PetscCall(PetscStrcmp(scheme, TSBASICSYMPLECTICVELVERLET, &verlet));
    PetscCall(PetscStrcmp(scheme, TSBASICSYMPLECTICSIEULER, &euler));
    drift_fraction_ = verlet ? 0.5 : euler ? 1.0 : 0.0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::LocalState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc)
{
  PetscFunctionBeginUser;
  if (!controls_->Active() && !halo_) { /* the state's own arrays (read only: the halo fields are not gathered here) */
    x_local_ = const_cast<PetscReal *>(x), v_local_ = const_cast<PetscReal *>(v);
    *xc = x, *vc = v;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  const PetscInt n2 = 2 * n_owned_;
  xw_.resize(2 * n_all_);
  std::copy(x, x + n2, xw_.begin());
  x_local_ = xw_.data();
  if (!controls_->Active() && v == v_stale_.data() && v_stale_.size() == (size_t)(2 * n_all_)) v_local_ = v_stale_.data(); /* room for the halo: in place */
  else {
    vw_.resize(2 * n_all_);
    std::copy(v, v + n2, vw_.begin());
    v_local_ = vw_.data();
  }
  if (halo_) {
    halo_arrays_.clear();
    for (const ParticleField *f : halo_fields_) halo_arrays_.push_back(f->values());
    PetscCall(halo_->Gather(halo_arrays_));
  }
  controls_->Impose(t, x_local_, v_local_);
  if (halo_) PetscCall(halo_->Check(x_local_));
  *xc = x_local_, *vc = v_local_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::IntegratorState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc)
{
  PetscFunctionBeginUser;
  if (!held_ || halo_) PetscCall(LocalState(t, x, v, xc, vc));
  else {
    x_local_ = const_cast<PetscReal *>(x), v_local_ = const_cast<PetscReal *>(v);
    *xc = x, *vc = v;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::AcceptStep(PetscReal t, const PetscReal *x, const PetscReal *v)
{
  PetscFunctionBeginUser;
  if (!kdk_) { /* the model compares the positions with its last evaluation's */
    PetscCall(model_->AcceptStep(x, v, t));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  Vec       A1;
  PetscBool have;
  PetscCall(TSVerletGetLastAcceleration(ts_, &A1, &have)); /* the step ended with an evaluation at its positions */
  const bool here = have && model_->EvaluationStamp() == step_end_stamp_;
  PetscCall(model_->AcceptStep(x, v, t, &here));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TS verlet's constraints: the controlled components of the owned particles at t, in the state */
PetscErrorCode FineEquations::ImposeControls(TS ts, PetscReal t, Vec X, Vec V, void *ctx)
{
  FineEquations *eq = (FineEquations *)ctx;
  PetscScalar   *x, *v;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(X, &x));
  PetscCall(VecGetArray(V, &v));
  eq->controls_->Impose(t, x, v, eq->n_owned_);
  PetscCall(VecRestoreArray(V, &v));
  PetscCall(VecRestoreArray(X, &x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void FineEquations::SetReproducibleSums(bool on)
{
  reproducible_ = on;
  if (on) model_->Grain().SetFor(1.0); /* any grain: the first evaluation finds its own */
  else model_->Grain().Clear();
}

/* With reproducible sums, the evaluation is repeated when its largest share asks for another grain
   than the one it was made with (force_grain.h); the shares do not depend on the grain, so the
   second pass agrees with itself. Every rank takes the same decision (the largest share over all). */
PetscErrorCode FineEquations::TotalForces(const PetscReal *x, const PetscReal *v, PetscReal *f)
{
  ForceGrain &grain = model_->Grain();
  PetscFunctionBeginUser;
  for (int pass = 0;; pass++) {
    PetscCall(model_->ComputeForces(x, v, f, NULL));
    if (halo_) PetscCall(halo_->Return(f));
    if (!reproducible_) break;
    PetscReal largest = std::isfinite(grain.Largest()) ? grain.Largest() : PETSC_INFINITY;
    if (halo_) PetscCall(MaxOverRanks(halo_->Comm(), &largest));
    if (!std::isfinite(largest) || grain.Fits(largest)) break; /* a non-finite force: the state is rejected by its checks */
    PetscCheck(pass == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "reproducible sums: the largest share %g changed between two evaluations of one state",
               (double)largest);
    grain.SetFor(largest);
    regrains_++;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::Accelerations(const PetscReal *x, const PetscReal *v, PetscScalar *a, bool a_has_halo_room)
{
  PetscFunctionBeginUser;
  if (!halo_) { /* the state's array holds every particle: no copy */
    if (reproducible_) {
      PetscCall(TotalForces(x, v, a));
      model_->DivideByMass(a, a, n_owned_);
    } else PetscCall(model_->ComputeAcceleration(x, v, a));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (a_has_halo_room) { /* the halo's forces in a's spare tail, returned from there */
    PetscCall(TotalForces(x, v, a));
    model_->DivideByMass(a, a, n_owned_);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  fw_.resize(2 * n_all_);
  PetscCall(TotalForces(x, v, fw_.data()));
  model_->DivideByMass(fw_.data(), a, n_owned_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A distributed run: every rank's limits, the smallest of each kind (the text before its ':', e.g.
   "wall springs") kept, the same on every rank (each rank bounds only its own particles). */
static PetscErrorCode SmallestLimits(MPI_Comm comm, std::vector<TimeStepLimit> &limits)
{
  TextRows mine, all;
  char     num[64];
  PetscFunctionBeginUser;
  for (const TimeStepLimit &l : limits) {
    PetscCall(PetscSNPrintf(num, sizeof num, "%.17g", (double)l.dt));
    mine.push_back({num, l.why});
  }
  PetscCall(GatherRows(comm, true, mine, &all));
  std::vector<TimeStepLimit> merged;
  for (const auto &row : all) {
    const TimeStepLimit l{(PetscReal)std::strtod(row[0].c_str(), nullptr), row[1]};
    const std::string   kind = l.why.substr(0, l.why.find(':'));
    auto                it   = std::find_if(merged.begin(), merged.end(), [&](const TimeStepLimit &m) { return m.why.substr(0, m.why.find(':')) == kind; });
    if (it == merged.end()) merged.push_back(l);
    else if (l.dt < it->dt) *it = l;
  }
  limits = merged;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::StabilityLimits(Vec U, std::vector<TimeStepLimit> &limits, PetscReal *dt)
{
  const PetscScalar *u;
  const PetscReal   *x, *v;
  MPI_Comm           comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)U, &comm));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(LocalState(0, u, &x, &v));
  if (halo_) PetscCall(model_->TimeStepLimits(x, v, limits, [this](PetscReal *f) { return halo_->Return(f); }));
  else PetscCall(model_->TimeStepLimits(x, v, limits));
  PetscCall(VecRestoreArrayRead(U, &u));
  if (halo_) PetscCall(SmallestLimits(comm, limits));
  std::sort(limits.begin(), limits.end(), [](const TimeStepLimit &a, const TimeStepLimit &b) { return a.dt < b.dt; });
  *dt = limits.empty() ? PETSC_MAX_REAL : limits[0].dt;
  PetscCall(MinOverRanks(comm, dt));
  if (*dt == PETSC_MAX_REAL) *dt = 1e-3; /* no forces at all */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineEquations::RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  return TURGOR_GUARDED({
    FineEquations     *eq = (FineEquations *)ctx;
    const PetscInt     n2 = 2 * eq->n_owned_;
    const PetscScalar *u;
    PetscScalar       *f;
    PetscBool          answered = PETSC_FALSE;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    if (eq->observe_) PetscCall(eq->observe_(t, U, F, &answered)); /* a restart's first derivative, the FSAL stage */
    if (answered) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(VecGetArrayRead(U, &u));
    PetscCall(VecGetArray(F, &f));
    eq->model_->SetTime(t);
    /* with controls, the controlled components: x and v imposed, dx/dt = v_c(t), v not integrated */
    const PetscReal *x, *v;
    PetscCall(eq->LocalState(t, u, u + n2, &x, &v));
    std::copy(v, v + n2, f);
    for (PetscInt i : eq->fixed_) f[2 * i] = f[2 * i + 1] = 0;
    PetscCall(eq->Accelerations(x, v, f + n2, eq->rate_room_));
    if (eq->controls_->Active()) eq->controls_->AdjustAccelerations(t, f + n2);
    PetscCall(VecRestoreArray(F, &f));
    PetscCall(VecRestoreArrayRead(U, &u));
    eq->rhs_evals_++;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FineEquations::RHSPosition(TS ts, PetscReal t, Vec V, Vec Xdot, void *ctx)
{
  return TURGOR_GUARDED({
    FineEquations     *eq = (FineEquations *)ctx;
    const PetscScalar *v;
    PetscScalar       *xd;
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(V, &v));
    PetscCall(VecGetArray(Xdot, &xd));
    std::copy(v, v + 2 * eq->n_owned_, xd);
    if (eq->predict_) { /* v_{n+1/2} + h/2 a_n = v_n + h a_n: the step's end to O(h^2) */
      PetscReal h;
      PetscCall(TSGetTimeStep(eq->ts_, &h));
      for (PetscInt k = 0; k < 2 * eq->n_owned_; k++) eq->v_stale_[k] = v[k] + 0.5 * h * eq->a_last_[k];
    } else std::copy(v, v + 2 * eq->n_owned_, eq->v_stale_.begin());
    for (PetscInt i : eq->fixed_) xd[2 * i] = xd[2 * i + 1] = 0;
    if (eq->controls_->Active()) {
      PetscReal h;
      PetscCall(TSGetTimeStep(eq->ts_, &h));
      eq->controls_->PositionRates(t, eq->drift_fraction_ * h, xd);
    }
    PetscCall(VecRestoreArray(Xdot, &xd));
    PetscCall(VecRestoreArrayRead(V, &v));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FineEquations::RHSMomentum(TS ts, PetscReal t, Vec X, Vec Vdot, void *ctx)
{
  return TURGOR_GUARDED({
    FineEquations     *eq = (FineEquations *)ctx;
    const PetscScalar *x;
    PetscScalar       *a;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArray(Vdot, &a));
    eq->model_->SetTime(t);
    const PetscReal *xc, *vc;
    if (eq->held_) eq->controls_->Impose(t, nullptr, eq->v_stale_.data(), eq->n_owned_); /* the drift's velocities: the controlled ones in place */
    PetscCall(eq->IntegratorState(t, x, eq->v_stale_.data(), &xc, &vc));
    PetscCall(eq->Accelerations(xc, vc, a, eq->acceleration_room_));
    eq->step_end_stamp_ = eq->model_->EvaluationStamp();
    if (eq->controls_->Active()) eq->controls_->AdjustAccelerations(t, a);
    if (eq->predict_) std::copy(a, a + 2 * eq->n_owned_, eq->a_last_.begin());
    const bool finite = AllFinite(a, 2 * eq->n_owned_); /* a branch-free scan first */
    for (PetscInt k = 0; k < 2 * eq->n_owned_ && !finite; k++) {
      /* before any step the step cannot be the cause: the scene itself leaves double precision */
      PetscCheck(std::isfinite(a[k]) || eq->rhs_evals_ > 0, PETSC_COMM_SELF, PETSC_ERR_FP,
                 "Non-finite acceleration of particle %" PetscInt_FMT " at (%g, %g) µm in the starting state (t = %g µs, before any step): the scene's "
                 "lengths or parameters are beyond double precision (the tissue's coordinates and size, its stiffnesses, masses and pressures)",
                 k / 2, (double)xc[k - k % 2], (double)xc[k - k % 2 + 1], (double)t);
      PetscCheck(std::isfinite(a[k]), PETSC_COMM_SELF, PETSC_ERR_FP,
                 "Non-finite acceleration of particle %" PetscInt_FMT
                 " at t = %g µs: the fixed step is above the stability limit (lower -ts_dt or -fine_dt_safety)",
                 k / 2, (double)t);
    }
    PetscCall(VecRestoreArray(Vdot, &a));
    PetscCall(VecRestoreArrayRead(X, &x));
    eq->rhs_evals_++;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* A stage with non-finite values is rejected, so an adaptive integrator retries with a smaller step. */
PetscErrorCode FineEquations::CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept)
{
  return TURGOR_GUARDED({
    const PetscScalar *u;
    PetscInt           n;
    PetscFunctionBeginUser;
    /* a scan without branches (core/finite_scan.h) and one flag over the ranks: VecNorm's logging
       costs more than the scan on a small tissue */
    PetscCall(VecGetLocalSize(U, &n));
    PetscCall(VecGetArrayRead(U, &u));
    PetscMPIInt finite = AllFinite(u, n);
    PetscCall(VecRestoreArrayRead(U, &u));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &finite, 1, MPI_INT, MPI_LAND, PetscObjectComm((PetscObject)U)));
    *accept = finite ? PETSC_TRUE : PETSC_FALSE;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

} // namespace turgor
