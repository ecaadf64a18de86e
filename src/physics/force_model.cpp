#include <turgor/physics/force_model.h>
#include <turgor/physics/body_force.h>
#include <turgor/physics/repulsion.h>
#include <turgor/physics/sph_fluid.h>
#include <turgor/physics/wall_springs.h>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace turgor {

const std::vector<std::string> &KnownPhysicsTerms()
{
  static const std::vector<std::string> known = {"springs", "repulsion", "sph", "body_force"};
  return known;
}

PetscErrorCode CreateForceTerm(MPI_Comm comm, const std::string &name, const char *option, std::unique_ptr<ForceTerm> *term)
{
  PetscFunctionBeginUser;
  if (name == "springs") term->reset(new WallSprings());
  else if (name == "repulsion") term->reset(new Repulsion());
  else if (name == "sph") term->reset(new SPHFluid());
  else if (name == "body_force") term->reset(new BodyForce());
  else {
    std::string list;
    for (const std::string &k : KnownPhysicsTerms()) list += (list.empty() ? "" : ", ") + k;
    SETERRQ(comm, PETSC_ERR_ARG_UNKNOWN_TYPE, "Option %s: unknown physics term '%s' (known: %s)", option, name.c_str(), list.c_str());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::SetFromOptions(MPI_Comm comm, const std::vector<std::string> &skip)
{
  char      *names[16];
  PetscInt   n = 16;
  PetscBool  set;
  PetscReal  skin = nb_.Skin();

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Fine-scale physics", "turgor");
  PetscCall(PetscOptionsStringArray("-physics", "Physics terms to simulate, comma-separated, from springs,repulsion,sph,body_force (default: all four; none: no forces)", "ForceModel", names, &n, &set));
  PetscCall(PetscOptionsReal("-neighbour_skin", "Verlet skin of the neighbour lists [µm]", "ForceModel", skin, &skin, NULL));
  PetscOptionsEnd();
  PetscCheck(skin >= 0 && std::isfinite(skin), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -neighbour_skin = %g: must be finite and >= 0", (double)skin);
  nb_.SetSkin(skin);
  std::vector<std::string> list;
  if (set) {
    for (PetscInt k = 0; k < n; k++) {
      list.push_back(names[k]);
      PetscCall(PetscFree(names[k]));
    }
  } else list = KnownPhysicsTerms();
  terms_.clear();
  for (const std::string &name : list) {
    if (name == "none") continue;
    for (const auto &t : terms_) PetscCheck(name != t->Name(), comm, PETSC_ERR_ARG_WRONG, "Option -physics: term '%s' is listed twice", name.c_str());
    std::unique_ptr<ForceTerm> t;
    PetscCall(CreateForceTerm(comm, name, "-physics", &t));
    if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
    PetscCall(t->SetFromOptions(comm));
    terms_.push_back(std::move(t));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::SetUp(const ParticleSet &P)
{
  PetscFunctionBeginUser;
  P_ = &P;
  for (PetscInt i = 0; i < P.n; i++) PetscCheck(P.mass[i] > 0 && std::isfinite(P.mass[i]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Particle %" PetscInt_FMT " has mass %g: every particle mass must be > 0", i, (double)P.mass[i]);
  nb_.Reset();
  events_.clear();
  for (auto &t : terms_) {
    PetscCall(t->SetUp(P, nb_));
    std::string   ename = std::string("Tg_") + t->Name();
    PetscLogEvent ev;
    PetscCall(PetscLogEventRegister(ename.c_str(), PETSC_OBJECT_CLASSID, &ev));
    events_.push_back(ev);
  }
  PetscCall(PetscLogEventRegister("TgForces", PETSC_OBJECT_CLASSID, &ev_forces_));
  PetscCall(PetscLogEventRegister("TgNeighbours", PETSC_OBJECT_CLASSID, &ev_neighbours_));
  inv_mass_.resize(P.n);
  for (PetscInt i = 0; i < P.n; i++) inv_mass_[i] = P.fixed[i] ? 0.0 : 1.0 / P.mass[i];
  evaluations_ = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::ComputeForces(const PetscReal *x, const PetscReal *v, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  PetscCheck(P_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "ForceModel::SetUp() must be called first");
  PetscCall(PetscLogEventBegin(ev_forces_, 0, 0, 0, 0));
  evaluations_++;
  PetscCall(PetscLogEventBegin(ev_neighbours_, 0, 0, 0, 0));
  PetscCall(nb_.Update(*P_, x, images_));
  PetscCall(PetscLogEventEnd(ev_neighbours_, 0, 0, 0, 0));
  for (PetscInt k = 0; k < 2 * P_->n; k++) f[k] = 0;
  if (virial)
    for (int k = 0; k < 4; k++) virial[k] = 0;
  const ForceInput in = {P_, x, v, &nb_, &images_};
  for (size_t t = 0; t < terms_.size(); t++) {
    PetscCall(PetscLogEventBegin(events_[t], 0, 0, 0, 0));
    PetscCall(terms_[t]->AddForces(in, f, virial));
    PetscCall(PetscLogEventEnd(events_[t], 0, 0, 0, 0));
  }
  PetscCall(PetscLogEventEnd(ev_forces_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::ComputeAcceleration(const PetscReal *x, const PetscReal *v, PetscReal *a)
{
  PetscFunctionBeginUser;
  PetscCall(ComputeForces(x, v, a, NULL));
  for (PetscInt i = 0; i < P_->n; i++) {
    a[2 * i] *= inv_mass_[i];
    a[2 * i + 1] *= inv_mass_[i];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ForceModel::PotentialEnergy(const PetscReal *x, PetscReal *E, PetscBool *complete)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  std::vector<PetscReal> v(2 * P_->n, 0.0);
  const ForceInput       in = {P_, x, v.data(), &nb_, &images_};
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

PetscErrorCode ForceModel::TimeStepLimits(const PetscReal *x, const PetscReal *v, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscCall(nb_.Update(*P_, x, images_));
  const ForceInput in = {P_, x, v, &nb_, &images_};
  limits.clear();
  for (auto &t : terms_) PetscCall(t->AddTimeStepLimits(in, limits));
  /* eq 40's force criterion 0.25 sqrt(h / |a|), with h the SPH smoothing length */
  if (auto *sph = dynamic_cast<SPHFluid *>(Term("sph"))) {
    std::vector<PetscReal> a(2 * P_->n);
    PetscCall(ComputeAcceleration(x, v, a.data()));
    evaluations_--; /* not an integrator evaluation */
    PetscReal amax = 0;
    for (PetscInt i = 0; i < P_->n; i++) amax = PetscMax(amax, std::hypot(a[2 * i], a[2 * i + 1]));
    if (amax > 0) limits.push_back({0.25 * std::sqrt(sph->smoothing_length / amax), "largest acceleration: 0.25 sqrt(h / |a|) (eq 40)"});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::vector<std::string> ForceModel::ActiveTerms() const
{
  std::vector<std::string> names;
  for (const auto &t : terms_) names.push_back(t->Name());
  return names;
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
  PetscCall(PetscViewerASCIIPrintf(viewer, "neighbour lists: skin %g µm%s%s\n", (double)nb_.Skin(), nb_.WantsFluidPairs() ? ", fluid pairs" : "", nb_.WantsParticleSpringPairs() ? ", particle-spring pairs" : ""));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
