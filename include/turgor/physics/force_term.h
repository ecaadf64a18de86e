#pragma once
/* One physics term of the fine-scale model. A scene lists the terms it wants (-physics); a term
   not in the list is never constructed, so it costs nothing: no neighbour lists, no passes.

   A new term is one file (a class derived from ForceTermBase<Term>) plus one line in
   src/app/register_all.cpp: ForceTermRegister("name", CreateInstance<ForceTerm, Term>). */
#include <turgor/particles/neighbour_search.h>
#include <turgor/particles/particles.h>
#include <turgor/physics/force_grain.h>
#include <turgor/physics/load_spec.h>
#include <turgor/core/parameters.h>
#include <turgor/io/declared_state.h>
#include <petscviewer.h>
#include <memory>
#include <string>
#include <cstdint>
#include <functional>
#include <vector>

namespace turgor {

/* Everything a kernel reads. Positions/velocities are interleaved [2n] arrays. */
struct ForceInput {
  const ParticleSet     *P;
  const PetscReal       *x, *v;
  const NeighbourSearch *nb;
  const PeriodicImages  *images; /* never NULL; all zero shifts unless periodic */
  /* AddTimeStepLimits: the largest |acceleration| of all terms together over the local particles,
     where a criterion needs it; < 0: not computed */
  PetscReal a_max = -1;
  /* AcceptStep only: the positions are those of the last AddForces, bit for bit, so a term may
     commit what that evaluation computed instead of recomputing it (ForceModel compares once for all
     terms; the velocities may differ: Verlet's last evaluation saw the half-step ones). */
  bool same_x = false;
  /* The time of the state (ForceModel::SetTime; break records, a turgor that builds up). */
  PetscReal t = 0;
  /* AddForces, where not NULL (the energy balance observes): a term whose force has a dashpot part
     (HasDashpotForce) adds that part here too, so that its work is counted as dissipation. */
  PetscReal *f_dashpot = nullptr;
  /* AddTimeStepLimits in a distributed run (else empty): adds the halo copies' values of a
     per-particle array [2 n] to their owners' (collective: every rank's term calls it), so that a
     bound summed over interactions that another rank computes (a Gershgorin row) is complete. */
  std::function<PetscErrorCode(PetscReal *)> sum_halo_shares = nullptr;
  /* AddForces: every share a term adds to f passes through Grain() first (force_grain.h) */
  const ForceGrain *grain = nullptr;
  const ForceGrain &Grain() const { return grain ? *grain : ForceGrain::Off(); }
};

/* A stable-time-step bound for explicit integrators, with its reason (for the start-up report). */
struct TimeStepLimit {
  PetscReal   dt = PETSC_MAX_REAL;
  std::string why;
};

/* What a term may take from the scene besides its own options. */
struct TermContext {
  const LoadSpec *load   = nullptr; /* external loads (the body force); NULL where a scene has none */
  ParameterList  *params = nullptr; /* the run's physics parameters: every option the term reads is recorded here */
};

/* A counter for summary.json; keys start with the term's name. A distributed run reports the sum
   over the ranks (each counts what it computes: its contacts, its bonds) or, for MAX, the largest
   rank's value (how often a rank rebuilt its lists). */
struct TermStatistic {
  enum Reduction {
    SUM,
    MAX
  };
  std::string name;
  PetscReal   value;
  Reduction   reduction = SUM;
};

/* A quantity a term shows in the snapshots: one value per closed polygon (CELL, in
   ParticleSet::polygons order, open cells skipped: a pressure) or per spring (BAR: a bar's force). */
struct TermField {
  enum Where {
    CELL,
    BAR
  } where;
  std::string            name, unit;
  std::vector<PetscReal> values;
};

/* Line segments a term draws in the snapshots (the glue bonds: node to bar point), with their ids
   (unique over the ranks, the same whatever the ranks: a glue bond's PairKey(node, bar); the
   snapshots write the segments in id order) and per-segment fields (TermField::BAR, one value per
   segment). */
struct TermSegments {
  std::string                name; /* empty: none */
  std::vector<PetscReal>     xy;   /* x0 y0 x1 y1 per segment */
  std::vector<std::uint64_t> id;   /* one per segment */
  std::vector<TermField>     fields;
};

class ForceTerm {
public:
  virtual ~ForceTerm()             = default;
  virtual const char *Name() const = 0;
  /* A configured term that has not been set up: every force model (each RVE has one) takes a copy. */
  virtual std::unique_ptr<ForceTerm> Clone() const = 0;
  /* Read this term's parameters (one options block with the term's prefix) and validate them. */
  virtual PetscErrorCode SetFromOptions(MPI_Comm comm, const TermContext &ctx) = 0;
  /* An external load (the body force) rather than a property of the tissue: a material (an RVE)
     does not include it; the coarse model applies the load itself. */
  virtual bool IsLoad() const { return false; }
  /* The farthest a particle's interactions reach into other cells: a particle–spring cutoff, the
     glue's bonding distance (without the neighbour skin; 0: only within its own cell). A distributed
     run keeps every cell within this distance of a rank's cells as its halo. From the tissue's
     constants (the bar radius) and the term's options only: a tissue generated in parts takes it
     from each rank's part without its halo. */
  virtual PetscReal Reach(const ParticleSet &P) const { return 0; }
  /* Precompute per-particle/per-bond data and ask the neighbour search for the lists needed. */
  virtual PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) = 0;
  /* f[2n] += forces. If virial is not NULL, virial[4] += -sum_k f_k (x) x_k over this term's
     interactions (row-major, translation invariant), so that sigma = virial / area (TW 562 eq 30). */
  virtual PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) = 0;
  /* Potential energy of the conservative part; *has = PETSC_FALSE if the term has none. */
  virtual PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
  {
    *E   = 0;
    *has = PETSC_FALSE;
    return PETSC_SUCCESS;
  }
  /* Stability bounds for an explicit step at the current state (TW 562 eq 40 and bond
     frequencies); in.a_max holds the largest acceleration if NeedsAccelerations(). */
  virtual PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) { return PETSC_SUCCESS; }
  virtual bool           NeedsAccelerations() const { return false; }
  /* Internal state (plastic angles, contact history) is updated here, once per accepted step, at
     the accepted state; AddForces reads only the last accepted state, so that a result does not
     depend on how many stages an integrator evaluates. */
  virtual bool           HasInternalState() const { return false; } /* true: AcceptStep must be called */
  virtual PetscErrorCode AcceptStep(const ForceInput &in) { return PETSC_SUCCESS; }
  /* A typical force of a cell of size `length` and fluid density `density` (an RVE scales its
     equations by it); 0 if the term sets none. */
  virtual PetscReal      CharacteristicForce(PetscReal length, PetscReal density) const { return 0; }
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  /* Energy dissipated so far by the term's internal state (plastic rotation, frictional slip,
     fracture), counted in AcceptStep; the energy balance (energy.csv) sets it against the work. */
  virtual PetscReal Dissipation() const { return 0; }
  /* A term whose energy depends on time explicitly (a turgor ramp): dE/dt at fixed positions, which
     the energy balance counts as work done on the tissue from outside. */
  virtual bool      TimeDependent() const { return false; }
  virtual PetscReal ExplicitTimePower(const ForceInput &in) { return 0; }
  /* A purely dissipative force (global viscosity): its work is its dissipation. */
  virtual bool Dissipative() const { return false; }
  /* A stored term with a dashpot inside its force (ForceInput::f_dashpot). */
  virtual bool HasDashpotForce() const { return false; }
  /* Log files a term writes (e.g. glue's breaks.csv): their names and columns, known before the
     run; TakeRecords moves out the rows made since the last call, as (file, cells). */
  virtual void RecordFiles(std::vector<std::pair<std::string, std::vector<std::string>>> &files) const { }
  virtual void TakeRecords(std::vector<std::pair<std::string, std::vector<std::string>>> &rows) { }
  /* Segments for the snapshots (TermSegments). */
  virtual PetscErrorCode OutputSegments(const ForceInput &in, TermSegments *segments) { return PETSC_SUCCESS; }
  /* Fields for the snapshots at the state of `in` (TermField). */
  virtual PetscErrorCode OutputFields(const ForceInput &in, std::vector<TermField> &fields) { return PETSC_SUCCESS; }
  /* Counters for summary.json (TermStatistic; e.g. contact's mean number of contacts per evaluation). */
  virtual void Statistics(std::vector<TermStatistic> &stats) const { }
  /* Declared state (io/declared_state.h): what the term keeps from one accepted step to the next
     (plastic angles, contact histories, glue bonds, dissipation counts), declared by name into `d`
     (which carries the term's name) for checkpoints and restarts on any number of ranks: no checkpoint
     code of its own. `P` numbers the particles, bars and cells its records name (its keys use their
     ids: ParticleSet::gid, SpringGid, PolygonGid). Called at every checkpoint and restart, after
     SetUp; the bindings hold until the next call. AfterStateRead rebuilds what the term derives from
     that state (lists, trial values) at the restored state `in` (the neighbour lists restored). A term
     without state declares nothing. */
  virtual void           DeclareState(const ParticleSet &P, StateDeclaration &d) { }
  virtual PetscErrorCode AfterStateRead(const ForceInput &in) { return PETSC_SUCCESS; }
};

/* Clone() for a term that is copyable while configured and not yet set up. */
template <class Term>
class ForceTermBase : public ForceTerm {
public:
  std::unique_ptr<ForceTerm> Clone() const override { return std::make_unique<Term>(static_cast<const Term &>(*this)); }
};

using ForceTermCreator = Registry<ForceTerm>::Creator;
PetscErrorCode ForceTermRegister(const char name[], ForceTermCreator create);
/* A term by name (unconfigured); an unknown name is an error naming `option` and the known names. */
PetscErrorCode ForceTermCreate(MPI_Comm comm, const std::string &name, const char *option, std::unique_ptr<ForceTerm> *term);
std::string    ForceTermNames();

} // namespace turgor
