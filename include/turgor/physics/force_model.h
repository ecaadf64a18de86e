#pragma once
/* The fine-scale physics: PhysicsSpec is what a scene enables (-physics and each listed term's
   parameters, read once); ForceModel evaluates its own copy of those terms with one neighbour
   search shared by them, on plain arrays. The full fine-scale run has one ForceModel; every RVE has
   its own, built from one PhysicsSpec shared by all of them. */
#include <turgor/particles/neighbour_search.h>
#include <turgor/physics/force_term.h>
#include <algorithm>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace turgor {

class PhysicsSpec {
public:
  /* API defaults, overridden by -physics (comma-separated, in evaluation order; "none": no forces)
     and -neighbour_skin. */
  std::vector<std::string> names          = {"springs", "repulsion", "sph", "body_force"};
  PetscReal                neighbour_skin = 1.0; /* Verlet skin [µm] */
  /* false for a material (an RVE): terms that are loads (IsLoad) are accepted in the list but left
     out -- the coarse model applies the loads. */
  bool with_loads = true;

  /* Read -physics and -neighbour_skin, then create and configure every listed term. */
  PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx);
  /* Add a configured term (tests, custom physics) after the listed ones; it stays when
     SetFromOptions is called later. */
  void Add(std::unique_ptr<ForceTerm> term)
  {
    added_.push_back(term->Clone());
    terms_.push_back(std::move(term));
  }
  const std::vector<std::unique_ptr<ForceTerm>> &Terms() const { return terms_; }
  std::vector<std::string>                       ActiveTerms() const;
  /* A typical force of a cell (the first term that defines one; 0 if none does). */
  PetscReal CharacteristicForce(PetscReal length, PetscReal density) const;

private:
  std::vector<std::unique_ptr<ForceTerm>> terms_, added_;
};

class ForceModel {
public:
  /* Copies of the spec's terms, set up for these particles. */
  PetscErrorCode SetUp(const PhysicsSpec &physics, const ParticleSet &P);

  /* f[2n] = sum of all terms' forces; virial[4] (may be NULL) = -sum f_k (x) x_k of internal forces. */
  PetscErrorCode ComputeForces(const PetscReal *x, const PetscReal *v, PetscReal *f, PetscReal *virial);
  /* a[2n] = f / m, zero for fixed particles (whose flags are read at SetUp). */
  PetscErrorCode ComputeAcceleration(const PetscReal *x, const PetscReal *v, PetscReal *a);
  /* a[2i] = f[2i] / m_i for the first n particles, zero for fixed ones (a distributed run divides
     once the halo's forces have come back). */
  void DivideByMass(const PetscReal *f, PetscReal *a, PetscInt n) const;
  /* Sum of the conservative terms' energies; *complete = PETSC_FALSE if some active term has none. */
  PetscErrorCode PotentialEnergy(const PetscReal *x, PetscReal *E, PetscBool *complete);
  /* Every term's AcceptStep at the accepted state (x, v) of time t (integrators call it after each step).
     evaluated_here: whether the last ComputeForces was at these positions, where the caller knows
     it (SetCallerKnowsAcceptedState); otherwise the positions are compared with that evaluation's. */
  PetscErrorCode AcceptStep(const PetscReal *x, const PetscReal *v, PetscReal t = 0, const bool *evaluated_here = nullptr);
  /* The integrator tells AcceptStep whether its last evaluation was at the accepted positions: no
     copy of the positions is kept per evaluation for the comparison (unless the term forces are kept,
     for EvaluatedAt). */
  void SetCallerKnowsAcceptedState(bool on) { caller_knows_ = on; }
  /* ComputeForces calls so far, every one counted (Evaluations() leaves out the stability limits') */
  std::uint64_t EvaluationStamp() const { return stamp_; }
  bool          HasInternalState() const; /* some term has: the integrator must call AcceptStep */
  /* Stability bounds of an explicit step at state (x, v), every term's. */
  PetscErrorCode TimeStepLimits(const PetscReal *x, const PetscReal *v, std::vector<TimeStepLimit> &limits,
                                const std::function<PetscErrorCode(PetscReal *)> &sum_halo_shares = nullptr);

  std::vector<std::string> ActiveTerms() const;
  ForceTerm               *Term(const std::string &name) const;
  /* The time of the states evaluated next (time-dependent terms; 0 by default). */
  void      SetTime(PetscReal t) { t_ = t; }
  PetscReal Time() const { return t_; }
  /* sum of the time-dependent terms' dE/dt at x (ForceTerm::ExplicitTimePower), at the model's time */
  PetscErrorCode ExplicitTimePower(const PetscReal *x, std::vector<PetscReal> &P);
  /* Keep each term's own force of every ComputeForces (TermForce(t), [2n]), for the energy balance;
     it costs a zeroing and a sum per term and evaluation. */
  void KeepTermForces(bool keep) { keep_term_forces_ = keep; }
  /* the grain every share is rounded to before it is added (force_grain.h; off unless set) */
  ForceGrain &Grain() { return grain_; }
  /* Hand over the last evaluation's term forces, and their dashpot parts (for a term with one,
     ForceTerm::HasDashpotForce), by swapping buffers: F[t] and Fd[t] get them, no copy; the model
     keeps the caller's old buffers for its next evaluation, and until then TermForcesTaken(). */
  void TakeTermForces(std::vector<std::vector<PetscReal>> &F, std::vector<std::vector<PetscReal>> &Fd)
  {
    std::swap(F, term_f_);
    std::swap(Fd, term_fd_);
    taken_ = true;
  }
  bool TermForcesTaken() const { return taken_; }
  /* Was the last ComputeForces at these positions (bit for bit)? Known when a term has internal
     state or the term forces are kept; false otherwise. */
  bool             EvaluatedAt(const PetscReal *x) const { return !last_x_.empty() && std::equal(last_x_.begin(), last_x_.end(), x); }
  size_t           NumTerms() const { return terms_.size(); }
  const ForceTerm &TermAt(size_t t) const { return *terms_[t]; }
  /* Each term's energy at x (has[t] false for a term without one). */
  PetscErrorCode TermEnergies(const PetscReal *x, std::vector<PetscReal> &E, std::vector<bool> &has);
  /* Every term's log rows since the last call, and the files they go to. */
  void RecordFiles(std::vector<std::pair<std::string, std::vector<std::string>>> &files) const;
  void TakeRecords(std::vector<std::pair<std::string, std::vector<std::string>>> &rows);
  /* Every term's snapshot segments at (x, v) (those that draw any). */
  PetscErrorCode OutputSegments(const PetscReal *x, const PetscReal *v, std::vector<TermSegments> &segments);
  /* Every term's snapshot fields at (x, v). */
  PetscErrorCode OutputFields(const PetscReal *x, const PetscReal *v, std::vector<TermField> &fields);
  /* Every term's Statistics(), in term order. */
  std::vector<TermStatistic> Statistics() const;
  NeighbourSearch           &Neighbours() { return nb_; }
  const NeighbourSearch     &Neighbours() const { return nb_; }
  /* Periodic lattice for RVEs (positions and rates of the image shifts); default: not periodic. */
  void                  SetPeriodicImages(const PeriodicImages &images) { images_ = images; }
  const PeriodicImages &Images() const { return images_; }
  PetscInt              Evaluations() const { return evaluations_; }
  PetscErrorCode        View(PetscViewer viewer) const;
  /* Declared state: the neighbour lists' last build ("<prefix>neighbours": the positions it was
     made at and the rebuilds, which only the layout that wrote them can use) and every term's
     ("<prefix><term>"), appended to `decls`. AfterStateRead, once a checkpoint is read into them:
     the lists as they were (`own_layout`: this rank holds what its writer held) or built afresh at x,
     then every term's AfterStateRead at the state (x, v) of time t. */
  void           DeclareState(std::deque<StateDeclaration> &decls, const std::string &prefix = "");
  PetscErrorCode AfterStateRead(const PetscReal *x, const PetscReal *v, PetscReal t, bool own_layout);

private:
  const ParticleSet                      *P_ = nullptr;
  std::vector<std::unique_ptr<ForceTerm>> terms_;
  std::vector<PetscLogEvent>              events_;
  NeighbourSearch                         nb_;
  PeriodicImages                          images_;
  std::vector<PetscReal>                  last_x_;             /* the last ComputeForces' positions, when a term has internal state */
  PetscInt                                last_rebuilds_ = -1; /* the neighbour lists' rebuilds at that evaluation */
  bool                                    has_state_ = false, keep_term_forces_ = false, taken_ = false, caller_knows_ = false;
  std::uint64_t                           stamp_ = 0;
  ForceGrain                              grain_;
  std::vector<std::vector<PetscReal>>     term_f_, term_fd_; /* per term, with KeepTermForces: force, dashpot part */
  PetscInt                                evaluations_ = 0;
  PetscReal                               t_           = 0;
  PetscLogEvent                           ev_forces_ = 0, ev_neighbours_ = 0;
  std::vector<PetscReal>                  nb_ref_;          /* DeclareState's view of the lists' build positions */
  PetscInt                                nb_rebuilds_ = 0; /* ... and of their rebuilds */
};

} // namespace turgor
