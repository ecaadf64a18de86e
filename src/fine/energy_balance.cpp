#include <turgor/fine/energy_balance.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode EnergyBalance::SetUp(ForceModel &model, const Controls &controls, const ParticleSet &P)
{
  PetscFunctionBeginUser;
  model_    = &model;
  controls_ = &controls;
  P_        = &P;
  model.KeepTermForces(true);
  stored_.clear(), loads_.clear(), timed_.clear(), dissipative_.clear(), counting_.clear(), dashpots_.clear();
  /* roles: a load does work from outside (the body force); a dissipative term only removes energy
     (its work is its dissipation); the others store energy, and may count their own dissipation */
  for (size_t t = 0; t < model.NumTerms(); t++) {
    const ForceTerm &T = model.TermAt(t);
    if (T.IsLoad()) loads_.push_back(t);
    else if (T.Dissipative()) dissipative_.push_back(t);
    else {
      stored_.push_back(t);
      if (T.HasInternalState()) counting_.push_back(t); /* plasticity, friction, fracture */
      if (T.TimeDependent()) timed_.push_back(t);       /* a turgor ramp */
      if (T.HasDashpotForce()) dashpots_.push_back(t);  /* contact's normal damping */
    }
  }
  W_.assign(model.NumTerms(), 0.0);
  W_dashpot_.assign(dashpots_.size(), 0.0);
  W_time_.assign(model.NumTerms(), 0.0);
  W_controls_ = 0, worst_relative_ = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<std::string> EnergyBalance::Columns() const
{
  std::vector<std::string> c = {"kinetic"};
  for (size_t t : stored_) c.push_back(std::string("energy_") + model_->TermAt(t).Name());
  c.push_back("work_controls");
  for (size_t t : loads_) c.push_back(std::string("work_") + model_->TermAt(t).Name());
  for (size_t t : timed_) c.push_back(std::string("work_") + model_->TermAt(t).Name() + "_ramp");
  for (size_t t : dissipative_) c.push_back(std::string("dissipated_") + model_->TermAt(t).Name());
  for (size_t t : counting_) c.push_back(std::string("dissipated_") + model_->TermAt(t).Name());
  for (size_t t : dashpots_) c.push_back(std::string("dissipated_") + model_->TermAt(t).Name() + "_dashpot");
  c.push_back("residual");
  c.push_back("residual_relative");
  return c;
}

PetscReal EnergyBalance::Kinetic(const PetscReal *v) const
{
  PetscReal K = 0;
  for (PetscInt i = 0; i < P_->NumOwned(); i++) K += 0.5 * P_->mass[i] * (v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]);
  return K;
}

/* Every term's force at (x, v): the model's last evaluation where it was at these positions (the
   forces the integrator used), otherwise a new evaluation; and the controls' forces. */
PetscErrorCode EnergyBalance::Forces(const PetscReal *x, const PetscReal *v, std::vector<std::vector<PetscReal>> &F, std::vector<std::vector<PetscReal>> &D,
                                     std::vector<PetscReal> &reaction)
{
  const PetscInt n2 = 2 * P_->n;
  PetscFunctionBeginUser;
  if (!model_->EvaluatedAt(x) || model_->TermForcesTaken()) {
    F_work_total_.resize(n2);
    PetscCall(model_->ComputeForces(x, v, F_work_total_.data(), NULL));
  }
  model_->TakeTermForces(F, D); /* no copy: the buffers change places */
  std::vector<PetscReal> total(n2, 0.0);
  for (size_t t = 0; t < model_->NumTerms(); t++)
    for (PetscInt k = 0; k < n2; k++) total[k] += F[t][k];
  reaction.resize(n2);
  controls_->ControlForces(t_, total.data(), reaction.data(), P_->n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EnergyBalance::Start(MPI_Comm comm, PetscReal t, const PetscReal *x, const PetscReal *v)
{
  std::vector<PetscReal> E;
  std::vector<bool>      has;
  PetscFunctionBeginUser;
  t_ = t;
  PetscCall(Forces(x, v, F_prev_, D_prev_, R_prev_));
  v_prev_.assign(v, v + 2 * P_->n);
  PetscCall(model_->TermEnergies(x, E, has));
  PetscReal s[2] = {Kinetic(v), 0};
  for (size_t q : stored_) s[1] += has[q] ? E[q] : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPIU_SUM, comm));
  K0_ = s[0], E0_ = s[1];
  std::fill(W_.begin(), W_.end(), 0.0);
  std::fill(W_dashpot_.begin(), W_dashpot_.end(), 0.0);
  std::fill(W_time_.begin(), W_time_.end(), 0.0);
  W_controls_ = 0;
  model_->SetTime(t);
  PetscCall(model_->ExplicitTimePower(x, P_time_prev_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EnergyBalance::Step(PetscReal t, const PetscReal *x, const PetscReal *v)
{
  const PetscInt  n2 = 2 * P_->n;
  const PetscReal h  = t - t_;
  PetscFunctionBeginUser;
  t_ = t;
  PetscCall(Forces(x, v, F_work_, D_work_, R_work_));
  const auto work = [&](const std::vector<PetscReal> &F0, const std::vector<PetscReal> &F1) {
    PetscReal w = 0;
    for (PetscInt k = 0; k < n2; k++) w += (F0[k] + F1[k]) * (v_prev_[k] + v[k]);
    return 0.25 * h * w;
  };
  for (size_t q = 0; q < F_work_.size(); q++) W_[q] += work(F_prev_[q], F_work_[q]);
  for (size_t q = 0; q < dashpots_.size(); q++) W_dashpot_[q] += work(D_prev_[dashpots_[q]], D_work_[dashpots_[q]]);
  W_controls_ += work(R_prev_, R_work_);
  if (!timed_.empty()) { /* the work of the explicit time dependence, trapezoidal */
    std::vector<PetscReal> P;
    model_->SetTime(t);
    PetscCall(model_->ExplicitTimePower(x, P));
    for (size_t q : timed_) W_time_[q] += 0.5 * h * (P_time_prev_[q] + P[q]);
    P_time_prev_ = P;
  }
  std::swap(F_prev_, F_work_);
  std::swap(D_prev_, D_work_);
  std::swap(R_prev_, R_work_);
  v_prev_.assign(v, v + n2);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscReal EnergyBalance::ExternalWork() const
{
  PetscReal w = W_controls_;
  for (size_t q : loads_) w += W_[q];
  for (size_t q : timed_) w += W_time_[q];
  return w;
}

PetscErrorCode EnergyBalance::Row(MPI_Comm comm, const PetscReal *x, const PetscReal *v, std::vector<PetscReal> &row, PetscReal *relative)
{
  std::vector<PetscReal> E;
  std::vector<bool>      has;
  PetscFunctionBeginUser;
  PetscCall(model_->TermEnergies(x, E, has));
  /* rank sums: kinetic, energies, works, dissipations (the term counters are each rank's own) */
  std::vector<PetscReal> s;
  s.push_back(Kinetic(v));
  for (size_t q : stored_) s.push_back(has[q] ? E[q] : 0);
  s.push_back(W_controls_);
  for (size_t q : loads_) s.push_back(W_[q]);
  for (size_t q : timed_) s.push_back(W_time_[q]);
  for (size_t q : dissipative_) s.push_back(-W_[q]);
  for (size_t q : counting_) s.push_back(model_->TermAt(q).Dissipation());
  for (PetscReal w : W_dashpot_) s.push_back(-w);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s.data(), (PetscMPIInt)s.size(), MPIU_REAL, MPIU_SUM, comm));
  size_t    k = 0;
  PetscReal K = s[k++], Es = 0, Wext = 0, Wabs = 0, D = 0, Etot_abs = std::fabs(s[0]);
  for (size_t q = 0; q < stored_.size(); q++) Es += s[k], Etot_abs += std::fabs(s[k]), k++;
  for (size_t q = 0; q < 1 + loads_.size() + timed_.size(); q++) Wext += s[k], Wabs += std::fabs(s[k]), k++;
  for (size_t q = 0; q < dissipative_.size() + counting_.size() + dashpots_.size(); q++) D += s[k++];
  const PetscReal residual = (K + Es) - (K0_ + E0_) - Wext + D;
  /* relative to the external works' magnitudes summed (the controls' and a turgor ramp's works may
     have opposite signs: their sum could cancel and inflate the ratio), or to the energies in play
     where they are larger (a load that has just begun has done next to no work yet), or to the
     round-off's energy where both are below it */
  const PetscReal scale = std::max({Wabs, Etot_abs, round_off_});
  *relative             = scale > 0 ? residual / scale : 0;
  worst_relative_       = std::max(worst_relative_, std::fabs(*relative));
  row                   = s;
  row.push_back(residual);
  row.push_back(*relative);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void EnergyBalance::DeclareState(StateDeclaration &d)
{
  d.Scalar("work_controls", &W_controls_, Combine::Sum);
  d.Scalar("kinetic_start", &K0_, Combine::Owner);
  d.Scalar("stored_start", &E0_, Combine::Owner);
  d.Scalar("time", &t_, Combine::Owner);
  d.Scalar("largest_residual", &worst_relative_, Combine::Max);
  d.Scalar("round_off_energy", &round_off_, Combine::Max);
  d.Vector("work", &W_, Combine::Sum);
  d.Vector("work_dashpot", &W_dashpot_, Combine::Sum);
  d.Vector("work_ramp", &W_time_, Combine::Sum);
  d.Vector("ramp_power", &P_time_prev_, Combine::Sum);
  StateTable &t = d.Table("particles", StateEntity::Particle);
  t.Rows([this] { return (size_t)P_->n; }).Column("velocity", v_prev_, 2, Combine::Copy).Column("control_force", R_prev_, 2, Combine::Sum);
  for (size_t q = 0; q < F_prev_.size(); q++) t.Column(std::string("force_") + model_->TermAt(q).Name(), F_prev_[q], 2, Combine::Sum);
  D_prev_.resize(model_->NumTerms());
  for (size_t term : dashpots_) t.Column(std::string("dashpot_force_") + model_->TermAt(term).Name(), D_prev_[term], 2, Combine::Sum);
}

} // namespace turgor
