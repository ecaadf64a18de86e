#include <turgor/fine/energy_balance.h>
#include <turgor/particles/local_numbering.h>
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
  stored_.clear(), loads_.clear(), timed_.clear(), dissipative_.clear(), counting_.clear();
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
    }
  }
  W_.assign(model.NumTerms(), 0.0);
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
PetscErrorCode EnergyBalance::Forces(const PetscReal *x, const PetscReal *v, std::vector<std::vector<PetscReal>> &F, std::vector<PetscReal> &reaction)
{
  const PetscInt n2 = 2 * P_->n;
  PetscFunctionBeginUser;
  if (!model_->EvaluatedAt(x)) {
    F_work_total_.resize(n2);
    PetscCall(model_->ComputeForces(x, v, F_work_total_.data(), NULL));
  }
  F.resize(model_->NumTerms());
  std::vector<PetscReal> total(n2, 0.0);
  for (size_t t = 0; t < model_->NumTerms(); t++) {
    F[t] = model_->TermForce(t);
    for (PetscInt k = 0; k < n2; k++) total[k] += F[t][k];
  }
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
  PetscCall(Forces(x, v, F_prev_, R_prev_));
  v_prev_.assign(v, v + 2 * P_->n);
  PetscCall(model_->TermEnergies(x, E, has));
  PetscReal s[2] = {Kinetic(v), 0};
  for (size_t q : stored_) s[1] += has[q] ? E[q] : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s, 2, MPIU_REAL, MPIU_SUM, comm));
  K0_ = s[0], E0_ = s[1];
  std::fill(W_.begin(), W_.end(), 0.0);
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
  PetscCall(Forces(x, v, F_work_, R_work_));
  for (size_t q = 0; q < F_work_.size(); q++) {
    PetscReal w = 0;
    for (PetscInt k = 0; k < n2; k++) w += (F_prev_[q][k] + F_work_[q][k]) * (v_prev_[k] + v[k]);
    W_[q] += 0.25 * h * w;
  }
  PetscReal w = 0;
  for (PetscInt k = 0; k < n2; k++) w += (R_prev_[k] + R_work_[k]) * (v_prev_[k] + v[k]);
  W_controls_ += 0.25 * h * w;
  if (!timed_.empty()) { /* the work of the explicit time dependence, trapezoidal */
    std::vector<PetscReal> P;
    model_->SetTime(t);
    PetscCall(model_->ExplicitTimePower(x, P));
    for (size_t q : timed_) W_time_[q] += 0.5 * h * (P_time_prev_[q] + P[q]);
    P_time_prev_ = P;
  }
  std::swap(F_prev_, F_work_);
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
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, s.data(), (PetscMPIInt)s.size(), MPIU_REAL, MPIU_SUM, comm));
  size_t    k = 0;
  PetscReal K = s[k++], Es = 0, Wext = 0, Wabs = 0, D = 0, Etot_abs = std::fabs(s[0]);
  for (size_t q = 0; q < stored_.size(); q++) Es += s[k], Etot_abs += std::fabs(s[k]), k++;
  for (size_t q = 0; q < 1 + loads_.size() + timed_.size(); q++) Wext += s[k], Wabs += std::fabs(s[k]), k++;
  for (size_t q = 0; q < dissipative_.size() + counting_.size(); q++) D += s[k++];
  const PetscReal residual = (K + Es) - (K0_ + E0_) - Wext + D;
  /* relative to the external works' magnitudes summed (the controls' and a turgor ramp's works may
     have opposite signs: their sum could cancel and inflate the ratio), or (none done) to the
     energies in play */
  const PetscReal scale = Wabs > 0 ? Wabs : Etot_abs;
  *relative             = scale > 0 ? residual / scale : 0;
  worst_relative_       = std::max(worst_relative_, std::fabs(*relative));
  row                   = s;
  row.push_back(residual);
  row.push_back(*relative);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void EnergyBalance::SaveState(StateBlob &state) const
{
  for (PetscReal v : {W_controls_, K0_, E0_, t_, worst_relative_}) state.Put(v);
  for (const std::vector<PetscReal> *w : {&W_time_, &P_time_prev_, &W_, &v_prev_, &R_prev_, &F_work_total_, &R_work_}) state.Put(*w);
  state.Put((PetscReal)F_prev_.size());
  for (const auto &f : F_prev_) state.Put(f);
  state.Put((PetscReal)F_work_.size());
  for (const auto &f : F_work_) state.Put(f);
}

PetscErrorCode EnergyBalance::LoadState(StateBlob &state)
{
  PetscReal n;
  bool      ok = state.Get(&W_controls_) && state.Get(&K0_) && state.Get(&E0_) && state.Get(&t_) && state.Get(&worst_relative_);
  PetscFunctionBeginUser;
  for (std::vector<PetscReal> *w : {&W_time_, &P_time_prev_, &W_, &v_prev_, &R_prev_, &F_work_total_, &R_work_}) ok = ok && state.Get(*w);
  ok = ok && state.Get(&n) && n >= 0 && n == (PetscReal)W_.size();
  if (ok) F_prev_.assign((size_t)n, {});
  for (size_t k = 0; ok && k < F_prev_.size(); k++) ok = state.Get(F_prev_[k]);
  ok = ok && state.Get(&n) && n >= 0 && n <= (PetscReal)W_.size();
  if (ok) F_work_.assign((size_t)n, {});
  for (size_t k = 0; ok && k < F_work_.size(); k++) ok = state.Get(F_work_[k]);
  PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint's energy balance does not fit this scene's terms (-fine_energy with other physics?)");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* [W_controls, K0, E0, t, worst; W_time, P_time_prev, W; terms, n, n x (gid, v_prev, R_prev, F_prev per term)] */
void EnergyBalance::SaveGlobalState(StateBlob &state) const
{
  for (PetscReal v : {W_controls_, K0_, E0_, t_, worst_relative_}) state.Put(v);
  for (const std::vector<PetscReal> *w : {&W_time_, &P_time_prev_, &W_}) state.Put(*w);
  state.Put((PetscReal)F_prev_.size());
  state.Put((PetscReal)P_->n);
  for (PetscInt i = 0; i < P_->n; i++) {
    state.Put((PetscReal)P_->gid[i]);
    for (const std::vector<PetscReal> *w : {&v_prev_, &R_prev_})
      for (int d = 0; d < 2; d++) state.Put((*w)[2 * i + d]);
    for (const auto &f : F_prev_)
      for (int d = 0; d < 2; d++) state.Put(f[2 * i + d]);
  }
}

PetscErrorCode EnergyBalance::LoadGlobalState(std::vector<StateBlob> &states, bool first)
{
  const LocalNumbering local(*P_);
  const size_t         nt = model_->NumTerms(), n2 = 2 * (size_t)P_->n;
  PetscFunctionBeginUser;
  W_controls_ = 0;
  for (std::vector<PetscReal> *w : {&W_time_, &P_time_prev_, &W_}) w->assign(nt, 0.0);
  F_prev_.assign(nt, std::vector<PetscReal>(n2, 0.0));
  R_prev_.assign(n2, 0.0);
  v_prev_.assign(n2, 0.0);
  F_work_.clear();
  for (StateBlob &b : states) {
    PetscReal              wc, nf, n;
    std::vector<PetscReal> w[3];
    bool                   ok = b.Get(&wc) && b.Get(&K0_) && b.Get(&E0_) && b.Get(&t_) && b.Get(&worst_relative_) && b.Get(w[0]) && b.Get(w[1]) && b.Get(w[2]);
    ok                        = ok && w[0].size() == nt && w[1].size() == nt && w[2].size() == nt && b.Get(&nf) && (size_t)nf == nt && b.Get(&n) && n >= 0 &&
         b.pos + (size_t)n * (5 + 2 * nt) <= b.data.size();
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED,
               "the checkpoint's energy balance does not fit this scene's terms (-fine_energy with other physics?)");
    if (first) {
      W_controls_ += wc;
      for (size_t q = 0; q < nt; q++) W_time_[q] += w[0][q], P_time_prev_[q] += w[1][q], W_[q] += w[2][q];
    }
    for (size_t e = 0; e < (size_t)n; e++) {
      PetscReal g = 0, v[2] = {0, 0}, r[2] = {0, 0};
      b.Get(&g), b.Get(&v[0]), b.Get(&v[1]), b.Get(&r[0]), b.Get(&r[1]);
      const PetscInt l     = local.Particle((PetscInt)g);
      const bool     owner = l >= 0 && l < P_->NumOwned();
      for (int d = 0; d < 2; d++) {
        if (l >= 0) v_prev_[2 * l + d] = v[d]; /* a halo copy's too: its forces' work is done here */
        if (owner) R_prev_[2 * l + d] += r[d];
      }
      for (size_t q = 0; q < nt; q++)
        for (int d = 0; d < 2; d++) {
          PetscReal f = 0;
          b.Get(&f);
          if (owner) F_prev_[q][2 * l + d] += f;
        }
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
