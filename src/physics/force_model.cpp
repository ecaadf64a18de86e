#include <turgor/core/options.h>
#include <turgor/core/vector_clones.h>
#include <turgor/physics/force_model.h>
#include <algorithm>
#include <cmath>

namespace turgor {

PetscErrorCode ForceTermRegister(const char name[], ForceTermCreator create)
{
  return Registry<ForceTerm>::Instance().Add(name, create);
}

PetscErrorCode ForceTermCreate(MPI_Comm comm, const std::string &name, const char *option, std::unique_ptr<ForceTerm> *term)
{
  return Registry<ForceTerm>::Instance().Create(comm, name, option, "physics term", term);
}

std::string ForceTermNames()
{
  return Registry<ForceTerm>::Instance().Names();
}

PetscErrorCode LoadSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscReal g[3] = {body_acceleration[0], body_acceleration[1], 0}; /* one spare: PETSc drops values beyond the buffer silently */
  PetscInt  n    = 3;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "body_", "External loads", "turgor");
  PetscCall(PetscOptionsRealArray("-force", "Body force: acceleration gx,gy of the tissue [µm/µs^2] (default 0,-0.2)", "LoadSpec", g, &n, &set));
  PetscCall(TurgorOptionsReal(params, "-force_delay", "Fine runs: the body force acts from this time on [µs]", "LoadSpec", body_delay, &body_delay, NULL));
  PetscCall(TurgorOptionsReal(params, "-force_ramp_time", "Fine runs: the body force builds up linearly over this time after its delay [µs]; 0: at once",
                              "LoadSpec", body_ramp_time, &body_ramp_time, NULL));
  PetscOptionsEnd();
  PetscCheck(body_delay >= 0 && std::isfinite(body_delay), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -body_force_delay = %g: must be finite and >= 0",
             (double)body_delay);
  PetscCheck(body_ramp_time >= 0 && std::isfinite(body_ramp_time), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -body_force_ramp_time = %g: must be finite and >= 0",
             (double)body_ramp_time);
  PetscCall(CheckNotEmpty(comm, "-body_force", "two components gx,gy [µm/µs^2]"));
  PetscCheck(!set || n == 2, comm, PETSC_ERR_ARG_SIZ, "Option -body_force needs two components gx,gy (got %s%" PetscInt_FMT ")", n > 2 ? "more than " : "",
             n > 2 ? (PetscInt)2 : n);
  body_acceleration[0] = g[0];
  body_acceleration[1] = g[1];
  PetscCheck(std::isfinite(body_acceleration[0]) && std::isfinite(body_acceleration[1]), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -body_force = %g,%g: must be finite", (double)body_acceleration[0], (double)body_acceleration[1]);
  if (params) params->Set("-body_force", ParameterValue(body_acceleration, 2)); /* the value in effect, given or not */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode LoadSpec::RequireUnscheduled(MPI_Comm comm, const char *mode) const
{
  PetscFunctionBeginUser;
  PetscCheck(!Scheduled(), comm, PETSC_ERR_SUP,
             "Options -body_force_delay = %g, -body_force_ramp_time = %g: -mode %s applies the body force at once (a schedule is for the fine modes)",
             (double)body_delay, (double)body_ramp_time, mode);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PhysicsSpec::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  char       *list[16];
  PetscInt    n = 16;
  PetscBool   set;
  std::string defaults;
  PetscFunctionBeginUser;
  for (const std::string &s : names) defaults += (defaults.empty() ? "" : ",") + s;
  const std::string help = "Physics terms to simulate, comma-separated, in evaluation order, from " + ForceTermNames() + " (default " + defaults +
                           "; none: no forces)";
  PetscOptionsBegin(comm, NULL, "Fine-scale physics", "turgor");
  PetscCall(PetscOptionsStringArray("-physics", help.c_str(), "PhysicsSpec", list, &n, &set));
  PetscCall(TurgorOptionsReal(ctx.params, "-neighbour_skin", "Verlet skin of the neighbour lists [µm]", "PhysicsSpec", neighbour_skin, &neighbour_skin, NULL));
  PetscOptionsEnd();
  PetscCheck(!set || n < 16, comm, PETSC_ERR_ARG_SIZ, "Option -physics: more than 15 terms listed");
  PetscCall(CheckNotEmpty(comm, "-physics", ("terms: " + ForceTermNames() + ", or none").c_str())); /* not "all terms" */
  PetscCheck(neighbour_skin >= 0 && std::isfinite(neighbour_skin), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -neighbour_skin = %g: must be finite and >= 0",
             (double)neighbour_skin);
  if (set) {
    names.clear();
    for (PetscInt k = 0; k < n; k++) {
      names.push_back(list[k]);
      PetscCall(PetscFree(list[k]));
    }
  }
  if (ctx.params) { /* the terms in effect, given or not */
    std::string all;
    for (const std::string &s : names) all += (all.empty() ? "" : ",") + s;
    ctx.params->Set("-physics", all.empty() ? "none" : all);
  }
  terms_.clear();
  std::vector<std::string> seen;
  for (const std::string &name : names) {
    if (name == "none") continue;
    PetscCheck(std::find(seen.begin(), seen.end(), name) == seen.end(), comm, PETSC_ERR_ARG_WRONG, "Option -physics: term '%s' is listed twice", name.c_str());
    seen.push_back(name);
    std::unique_ptr<ForceTerm> t;
    PetscCall(ForceTermCreate(comm, name, "-physics", &t));
    if (!with_loads && t->IsLoad()) continue;
    PetscCall(t->SetFromOptions(comm, ctx));
    terms_.push_back(std::move(t));
  }
  for (const auto &t : added_) terms_.push_back(t->Clone());
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<std::string> PhysicsSpec::ActiveTerms() const
{
  std::vector<std::string> active;
  for (const auto &t : terms_) active.push_back(t->Name());
  return active;
}

PetscReal PhysicsSpec::CharacteristicForce(PetscReal length, PetscReal density) const
{
  for (const auto &t : terms_) {
    const PetscReal f = t->CharacteristicForce(length, density);
    if (f > 0) return f;
  }
  return 0;
}

PetscErrorCode ForceModel::SetUp(const PhysicsSpec &physics, const ParticleSet &P)
{
  PetscFunctionBeginUser;
  P_ = &P;
  for (PetscInt i = 0; i < P.n; i++)
    PetscCheck(P.mass[i] > 0 && std::isfinite(P.mass[i]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Particle %" PetscInt_FMT " has mass %g: every particle mass must be > 0", i, (double)P.mass[i]);
  nb_.Reset();
  nb_.SetSkin(physics.neighbour_skin);
  terms_.clear();
  events_.clear();
  for (const auto &proto : physics.Terms()) {
    terms_.push_back(proto->Clone());
    PetscCall(terms_.back()->SetUp(P, nb_));
    std::string   ename = std::string("Tg_") + terms_.back()->Name();
    PetscLogEvent ev;
    PetscCall(PetscLogEventRegister(ename.c_str(), PETSC_OBJECT_CLASSID, &ev));
    events_.push_back(ev);
  }
  PetscCall(PetscLogEventRegister("TgForces", PETSC_OBJECT_CLASSID, &ev_forces_));
  PetscCall(PetscLogEventRegister("TgNeighbours", PETSC_OBJECT_CLASSID, &ev_neighbours_));
  evaluations_ = 0;
  has_state_   = HasInternalState();
  last_x_.clear();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::ComputeForces(const PetscReal *x, const PetscReal *v, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  PetscCheck(P_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ForceModel::SetUp() must be called first");
  PetscCall(PetscLogEventBegin(ev_forces_, 0, 0, 0, 0));
  evaluations_++;
  stamp_++;
  PetscCall(PetscLogEventBegin(ev_neighbours_, 0, 0, 0, 0));
  PetscCall(nb_.Update(*P_, x, images_));
  PetscCall(PetscLogEventEnd(ev_neighbours_, 0, 0, 0, 0));
  for (PetscInt k = 0; k < 2 * P_->n; k++) f[k] = 0;
  if (virial)
    for (int k = 0; k < 4; k++) virial[k] = 0;
  if ((has_state_ && !caller_knows_) || keep_term_forces_)
    last_x_.assign(x, x + 2 * P_->n); /* AcceptStep tells its terms whether it is called at these positions */
  last_rebuilds_ = nb_.Rebuilds();
  ForceInput in  = {P_, x, v, &nb_, &images_};
  in.t           = t_;
  in.grain       = &grain_;
  grain_.ResetLargest();
  if (keep_term_forces_) term_f_.resize(terms_.size()), term_fd_.resize(terms_.size());
  for (size_t t = 0; t < terms_.size(); t++) {
    PetscCall(PetscLogEventBegin(events_[t], 0, 0, 0, 0));
    if (keep_term_forces_) { /* the term's own force: what it added to the total. Observing must not
                                change what is observed: the total is summed in the same order as
                                without (so the trajectory is the same bit for bit), and the term's
                                share is the difference, exact to the total's round-off */
      std::vector<PetscReal> &ft = term_f_[t];
      ft.assign(f, f + 2 * P_->n);
      if (terms_[t]->HasDashpotForce()) term_fd_[t].assign(2 * P_->n, 0.0), in.f_dashpot = term_fd_[t].data();
      PetscCall(terms_[t]->AddForces(in, f, virial));
      in.f_dashpot = nullptr;
      for (PetscInt k = 0; k < 2 * P_->n; k++) ft[k] = f[k] - ft[k];
    } else PetscCall(terms_[t]->AddForces(in, f, virial));
    PetscCall(PetscLogEventEnd(events_[t], 0, 0, 0, 0));
  }
  taken_ = false;
  PetscCall(PetscLogEventEnd(ev_forces_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::ComputeAcceleration(const PetscReal *x, const PetscReal *v, PetscReal *a)
{
  PetscFunctionBeginUser;
  PetscCall(ComputeForces(x, v, a, NULL));
  DivideByMass(a, a, P_->n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
/* Loops that vectorise (a division per particle, one by one, is a small tissue's largest cost beyond
   its forces and the kicks): f and a apart, or a in place (restrict-qualified both ways, so that no
   overlap test sends the in-place call, the usual one, to the scalar loop). */
TURGOR_VECTOR_CLONES void DivideByMassLoop(const PetscReal *__restrict f, PetscReal *__restrict a, PetscInt n, const PetscReal *__restrict m,
                                           const char *__restrict fixed)
{
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal im = 1.0 / m[i] * (PetscReal)(1 - fixed[i]); /* fixed: 0 or 1; masses > 0: 1/m x 1 is 1/m, x 0 is 0, no branch */
    a[2 * i]           = f[2 * i] * im;
    a[2 * i + 1]       = f[2 * i + 1] * im;
  }
}
TURGOR_VECTOR_CLONES void DivideByMassInPlace(PetscReal *__restrict a, PetscInt n, const PetscReal *__restrict m, const char *__restrict fixed)
{
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal im = 1.0 / m[i] * (PetscReal)(1 - fixed[i]);
    a[2 * i] *= im;
    a[2 * i + 1] *= im;
  }
}
} // namespace

/* 1/m formed here rather than stored (8 B a particle; one division per particle and evaluation,
   the same bits as a stored inverse); 0 for a fixed particle */
void ForceModel::DivideByMass(const PetscReal *f, PetscReal *a, PetscInt n) const
{
  if (f == a) DivideByMassInPlace(a, n, P_->mass.data(), P_->fixed.data());
  else DivideByMassLoop(f, a, n, P_->mass.data(), P_->fixed.data());
}

PetscErrorCode ForceModel::AcceptStep(const PetscReal *x, const PetscReal *v, PetscReal t, const bool *evaluated_here)
{
  PetscFunctionBeginUser;
  t_              = t;
  const size_t n2 = 2 * (size_t)P_->n;
  ForceInput   in = {P_, x, v, &nb_, &images_};
  in.t            = t;
  /* velocity Verlet and DOPRI accept the positions they last evaluated (Verlet's velocities differ:
     the dashpots saw the half-step ones); then, unless a call in between rebuilt them, the neighbour
     lists are those of that evaluation */
  in.same_x = evaluated_here ? *evaluated_here : last_x_.size() == n2 && std::equal(last_x_.begin(), last_x_.end(), x);
  if (!in.same_x || nb_.Rebuilds() != last_rebuilds_) PetscCall(nb_.Update(*P_, x, images_));
  for (auto &t : terms_) PetscCall(t->AcceptStep(in));
  PetscFunctionReturn(PETSC_SUCCESS);
}

bool ForceModel::HasInternalState() const
{
  for (auto &t : terms_)
    if (t->HasInternalState()) return true;
  return false;
}

PetscErrorCode ForceModel::PotentialEnergy(const PetscReal *x, PetscReal *E, PetscBool *complete)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  std::vector<PetscReal> v(2 * P_->n, 0.0);
  ForceInput             in = {P_, x, v.data(), &nb_, &images_};
  in.t                      = t_;
  *E                        = 0;
  *complete                 = PETSC_TRUE;
  for (auto &t : terms_) {
    PetscReal e;
    PetscBool has;
    PetscCall(t->Energy(in, &e, &has));
    if (has) *E += e;
    else *complete = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::TimeStepLimits(const PetscReal *x, const PetscReal *v, std::vector<TimeStepLimit> &limits,
                                          const std::function<PetscErrorCode(PetscReal *)> &sum_halo_shares)
{
  PetscReal a_max = -1;
  PetscFunctionBeginUser;
  if (std::any_of(terms_.begin(), terms_.end(), [](const auto &t) { return t->NeedsAccelerations(); })) {
    std::vector<PetscReal> a(2 * P_->n); /* freed before the terms' own work arrays are made */
    PetscCall(ComputeAcceleration(x, v, a.data()));
    evaluations_--; /* not an integrator evaluation */
    a_max = 0;
    for (PetscInt i = 0; i < P_->n; i++) a_max = PetscMax(a_max, std::hypot(a[2 * i], a[2 * i + 1]));
  }
  PetscCall(nb_.Update(*P_, x, images_));
  ForceInput in      = {P_, x, v, &nb_, &images_};
  in.t               = t_;
  in.a_max           = a_max;
  in.sum_halo_shares = sum_halo_shares;
  limits.clear();
  for (auto &t : terms_) PetscCall(t->AddTimeStepLimits(in, limits));
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<std::string> ForceModel::ActiveTerms() const
{
  std::vector<std::string> names;
  for (const auto &t : terms_) names.push_back(t->Name());
  return names;
}

PetscErrorCode ForceModel::OutputFields(const PetscReal *x, const PetscReal *v, std::vector<TermField> &fields)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  ForceInput in = {P_, x, v, &nb_, &images_};
  in.t          = t_;
  fields.clear();
  for (auto &t : terms_) PetscCall(t->OutputFields(in, fields));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::ExplicitTimePower(const PetscReal *x, std::vector<PetscReal> &P)
{
  PetscFunctionBeginUser;
  std::vector<PetscReal> v(2 * P_->n, 0.0);
  ForceInput             in = {P_, x, v.data(), &nb_, &images_};
  in.t                      = t_;
  P.assign(terms_.size(), 0.0);
  for (size_t t = 0; t < terms_.size(); t++)
    if (terms_[t]->TimeDependent()) P[t] = terms_[t]->ExplicitTimePower(in);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::TermEnergies(const PetscReal *x, std::vector<PetscReal> &E, std::vector<bool> &has)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  std::vector<PetscReal> v(2 * P_->n, 0.0);
  ForceInput             in = {P_, x, v.data(), &nb_, &images_};
  in.t                      = t_;
  E.assign(terms_.size(), 0.0);
  has.assign(terms_.size(), false);
  for (size_t t = 0; t < terms_.size(); t++) {
    PetscBool h;
    PetscCall(terms_[t]->Energy(in, &E[t], &h));
    has[t] = h;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

void ForceModel::RecordFiles(std::vector<std::pair<std::string, std::vector<std::string>>> &files) const
{
  for (const auto &t : terms_) t->RecordFiles(files);
}

void ForceModel::TakeRecords(std::vector<std::pair<std::string, std::vector<std::string>>> &rows)
{
  for (auto &t : terms_) t->TakeRecords(rows);
}

PetscErrorCode ForceModel::OutputSegments(const PetscReal *x, const PetscReal *v, std::vector<TermSegments> &segments)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  ForceInput in = {P_, x, v, &nb_, &images_};
  in.t          = t_;
  segments.clear();
  for (auto &t : terms_) {
    TermSegments s;
    PetscCall(t->OutputSegments(in, &s));
    if (!s.name.empty()) segments.push_back(std::move(s));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<TermStatistic> ForceModel::Statistics() const
{
  std::vector<TermStatistic> stats;
  for (const auto &t : terms_) t->Statistics(stats);
  return stats;
}

ForceTerm *ForceModel::Term(const std::string &name) const
{
  for (const auto &t : terms_)
    if (name == t->Name()) return t.get();
  return nullptr;
}

PetscErrorCode ForceModel::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "Physics terms (%zu):%s\n", terms_.size(), terms_.empty() ? " none" : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  for (const auto &t : terms_) PetscCall(t->View(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "neighbour lists: skin %g µm%s%s\n", (double)nb_.Skin(), nb_.WantsFluidPairs() ? ", fluid pairs" : "",
                                   nb_.WantsParticleSpringPairs() ? ", particle-spring pairs" : ""));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

void ForceModel::DeclareState(std::deque<StateDeclaration> &decls, const std::string &prefix)
{
  nb_ref_      = nb_.ReferencePositions();
  nb_rebuilds_ = nb_.Rebuilds();
  decls.emplace_back(prefix + "neighbours");
  StateDeclaration &d = decls.back();
  d.Scalar("rebuilds", &nb_rebuilds_, Combine::Max);
  d.Sequence("build_positions", &nb_ref_, Combine::Local); /* of every local particle, halo too: this rank's own */
  for (auto &term : terms_) {
    decls.emplace_back(prefix + term->Name());
    term->DeclareState(*P_, decls.back());
  }
}

PetscErrorCode ForceModel::AfterStateRead(const PetscReal *x, const PetscReal *v, PetscReal t, bool own_layout)
{
  PetscFunctionBeginUser;
  /* elsewhere the lists at the checkpoint's state: this rank's particles were never listed together */
  if (!own_layout) nb_ref_.assign(x, x + 2 * P_->n);
  PetscCall(nb_.Restore(*P_, nb_ref_, nb_rebuilds_, images_));
  std::vector<PetscReal>().swap(nb_ref_);
  last_x_.clear();
  last_rebuilds_ = -1;
  t_             = t;
  ForceInput in  = {P_, x, v, &nb_, &images_};
  in.t           = t;
  for (auto &term : terms_) PetscCall(term->AfterStateRead(in));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
