#include <turgor/core/options.h>
#include <turgor/core/geometry.h>
#include <turgor/core/errors.h>
#include <turgor/core/memory.h>
#include <turgor/fine/fine_run.h>
#include <turgor/io/checkpoint_file.h>
#include <turgor/fine/particle_output.h>
#include <turgor/parallel/exact_sum.h>
#include <turgor/parallel/rank_reductions.h>
#include <turgor/ts/velocity_verlet.h>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace turgor {

PetscErrorCode FineRunSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscBool pset, hset;
  PetscFunctionBeginUser;
  char partitioner_name[16]; /* -fine_partitioner, read as a string and checked after PetscOptionsEnd */
  PetscCall(PetscStrncpy(partitioner_name, partitioner == 1 ? "ranges" : "metis", sizeof partitioner_name));
  PetscOptionsBegin(comm, "fine_", "Full fine-scale run (-mode fine)", "turgor");
  PetscCall(TurgorOptionsReal(params, "-dt_safety", "Fixed-step integrators: dt = safety x the smallest stability limit (unless -ts_dt is given)",
                              "FineRunSpec", dt_safety, &dt_safety, NULL));
  PetscCall(PetscOptionsBool("-energy", "Write the energy balance energy.csv (kinetic, stored, work of controls and loads, dissipated, residual)",
                             "FineRunSpec", energy, &energy, NULL));
  PetscCall(TurgorOptionsBool(params, "-predict_velocity",
                              "TS verlet: the dashpots and the viscosity at the step's end see the velocity predicted there, v_n + h a_n (second order "
                              "with velocity-dependent forces; the stability limits are halved) instead of the drift's v_n + h/2 a_n (first order)",
                              "FineRunSpec", predict_velocity, &predict_velocity, NULL));
  PetscCall(PetscOptionsReal("-energy_tolerance",
                             "With -fine_energy: a relative energy residual above this fails the run (energy created or lost that no term accounts for); 0: "
                             "no check",
                             "FineRunSpec", energy_tolerance, &energy_tolerance, NULL));
  PetscCall(PetscOptionsInt("-partition_report",
                            "Partition the tissue's cells into N parts with METIS (cell graph weighted by particles per cell and shared wall length) and "
                            "report the edge cut and imbalance in summary.json and the particles' part in the snapshots (a report only: a run on several "
                            "ranks partitions its cells by itself, -fine_distribute; 0: no report)",
                            "FineRunSpec", partition, &partition, &pset));
  PetscCall(PetscOptionsBool("-distribute",
                             "On several ranks, deal the cells to the ranks (-fine_partitioner) and keep every particle on the rank of its cell, with a "
                             "halo of the neighbouring ranks' particles (false: all particles on rank 0, the other ranks idle)",
                             "FineRunSpec", distribute, &distribute, NULL));
  PetscCall(PetscOptionsString("-partitioner",
                               "Distributed runs: how the cells are dealt to the ranks: metis (a partition of the cell graph on the first rank; every "
                               "rank generates the whole tissue at set-up) or ranges (equal ranges of the cells in space order: a square grid's rows, "
                               "the Hilbert curve through a Voronoi tissue's seeds or a node file's cells; the tissue is then generated (or read) in "
                               "parts, no rank holding all of it)",
                               "FineRunSpec", partitioner_name, partitioner_name, sizeof partitioner_name, NULL));
  PetscCall(PetscOptionsBool("-setup_in_parts",
                             "With -fine_partitioner ranges: each rank generates only its cells and their halo where the generator can (square_grid, voronoi, "
                             "node_file); "
                             "false: every rank generates the whole tissue first (the same run, more memory at set-up)",
                             "FineRunSpec", setup_in_parts, &setup_in_parts, NULL));
  PetscCall(TurgorOptionsBool(params, "-reproducible_sums",
                              "Round every force share to a grain chosen from the state (2.3e-13 of the largest share) so that the forces' sums are "
                              "exact: a run, and a restart, give the same bits on any number of ranks (fixed-step integrators, or adaptive ones with "
                              "-ts_adapt_wnormtype infinity)",
                              "FineRunSpec", reproducible_sums, &reproducible_sums, NULL));
  PetscCall(PetscOptionsReal("-halo_margin",
                             "Distributed runs: width [µm] of the halo beyond the interactions' reach (cutoffs + neighbour skin); cells may move this "
                             "far relative to each other before the run stops (default: the reach)",
                             "FineRunSpec", halo_margin, &halo_margin, &hset));
  PetscOptionsEnd();
  PetscCall(ClampFromOptions(comm, &clamp, params));
  /* checked here: an unknown value refused inside PetscOptionsBegin/End would leave its items allocated */
  PetscCall(CheckNotEmpty(comm, "-fine_partitioner", "metis or ranges"));
  PetscCheck(!std::strcmp(partitioner_name, "metis") || !std::strcmp(partitioner_name, "ranges"), comm, PETSC_ERR_ARG_UNKNOWN_TYPE,
             "Option -fine_partitioner = %s: unknown partitioner (known: metis, ranges)", partitioner_name);
  partitioner = std::strcmp(partitioner_name, "ranges") ? 0 : 1;
  PetscCheck(!hset || (halo_margin >= 0 && std::isfinite(halo_margin)), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_halo_margin = %g: must be >= 0",
             (double)halo_margin);
  PetscCheck(!pset || partition >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_partition_report = %" PetscInt_FMT ": the number of parts must be >= 1",
             partition);
  PetscCheck(dt_safety > 0 && dt_safety <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_dt_safety = %g: must be in (0, 1]", (double)dt_safety);
  PetscCheck(energy_tolerance >= 0 && std::isfinite(energy_tolerance), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -fine_energy_tolerance = %g: must be finite and >= 0 (0: no check)", (double)energy_tolerance);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Measured (max RSS of 16^2 .. 128^2-cell runs with DOPRI, docs/benchmarks.md): a process
   with PETSc and MPI, and every particle's share (state and TS stages, neighbour lists, SPH work
   arrays, swarm). */
static const PetscReal kProcessBytes = 45e6, kBytesPerParticle = 1000;

FineRun::~FineRun()
{
  PetscCallVoid(ISDestroy(&is_x_));
  PetscCallVoid(ISDestroy(&is_v_));
  PetscCallVoid(DMDestroy(&swarm_));
}

PetscErrorCode FineRun::SetTSDefaults()
{
  PetscFunctionBeginUser;
  PetscCall(TSSetType(ts_, TSRK));
  PetscCall(TSRKSetType(ts_, TSRK5DP));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::ModeSetFromOptions()
{
  PetscFunctionBeginUser;
  ParameterList &params = PhysicsParameters();
  PetscCall(tissues_.SetFromOptions(comm_, &params));
  PetscCall(load_.SetFromOptions(comm_, &params));
  PetscCall(physics_.SetFromOptions(comm_, TermContext{&load_, &params}));
  PetscCall(spec_.SetFromOptions(comm_, &params));
  PetscCall(controls_.SetFromOptions(comm_, &params));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::CreateSwarm()
{
  return CreateParticleSwarm(comm_, tissue_.particles, n_local_, &swarm_);
}

PetscErrorCode FineRun::SetUpModel()
{
  PetscMPIInt rank, size;
  PetscFunctionBeginUser;
  PetscCall(RankAndSize(comm_, &rank, &size));
  const bool                     distributed = size > 1 && spec_.distribute;
  const TissuePlacement::Options placing     = {spec_.distribute == PETSC_TRUE, spec_.partition, spec_.halo_margin, spec_.partitioner == 1};
  /* dealt by cell ranges, a generator that can builds the tissue in parts, no rank holding all of
     it (not for controls, which select their particles in the whole tissue, nor for the partition
     report, which partitions it) */
  const bool in_parts = distributed && !have_tissue_ && placing.ranges && spec_.setup_in_parts && placing.report_parts == 0 && !controls_.Active() &&
                        tissues_.Generator()->NumCellsOfParts() >= 0;
  /* ranges of a numbering in no spatial order (a Voronoi tissue's seeds) would be scattered parts,
     every rank's halo most of the tissue */
  PetscCheck(!placing.ranges || (!have_tissue_ && tissues_.Generator()->NumCellsOfParts() >= 0), comm_, PETSC_ERR_ARG_INCOMP,
             "Option -fine_partitioner ranges: %s; use -fine_partitioner metis",
             have_tissue_ ? "a tissue given through the API numbers its cells in no known spatial order"
                          : ("-tissue_type " + std::string(tissues_.Generator()->Name()) + " " + tissues_.Generator()->PartsRefused()).c_str());
  if (distributed && placing.ranges) PetscCall(tissues_.Generator()->PrepareParts(comm_)); /* the space order (a Voronoi tissue's seeds) */
  if (!have_tissue_) {
    PetscReal particles, springs;
    PetscCall(tissues_.Generator()->Estimate(&particles, &springs));
    const std::string what = "the fine tissue (" + tissues_.Generator()->SizeOptions() + ": " + std::to_string((long long)particles) + " particles)";
    PetscCall(CheckCount(comm_, 4 * particles, what + ", its state vector"));
    PetscCall(CheckMemory(comm_, kProcessBytes + (in_parts ? kBytesPerParticle * particles / size : rank == 0 ? kBytesPerParticle * particles : 0), what));
    if (!in_parts) PetscCall(tissues_.Generate(comm_, &tissue_));
  }
  /* the halo's width: the farthest reach of any term into another cell, with the neighbour lists' skin */
  auto reach_of = [this](PetscReal *reach) {
    PetscFunctionBeginUser;
    *reach = 0;
    for (const auto &t : physics_.Terms()) *reach = std::max(*reach, t->Reach(tissue_.particles));
    PetscCall(MaxOverRanks(comm_, reach));
    *reach += physics_.neighbour_skin;
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  if (in_parts) {
    PetscInt  c0, c1;
    PetscReal reach;
    PetscCall(TissuePlacement::OwnedRange(comm_, tissues_.Generator()->NumCellsOfParts(), &c0, &c1));
    /* the terms' reach (it reads the tissue's constants) from this rank's range without its halo.
       A part of one cell would do and saves 1.2 s of the 10^7 bar's 12.6 s set-up, but the set-up's
       peak then rose by 26 MB a rank (1.531 -> 1.557 GB, glibc's heap laid out otherwise: the first
       part's freed blocks are reused by the second), and the peak is what the set-up in parts is for */
    /* (a node file is read here: any rank may fail) */
    PetscCall(AgreeOnError(comm_, tissues_.Generator()->GeneratePart(comm_, c0, c1, 0, &tissue_), "generating a part of the tissue"));
    PetscCall(reach_of(&reach));
    tissue_ = Tissue();
    PetscCall(placement_.PlaceParts(comm_, placing, reach, *tissues_.Generator(), &tissue_));
  }
  PetscCall(tissue_.Clamp(comm_, spec_.clamp, "-fine_clamp")); /* a part knows the whole tissue's bounds */
  { /* the skin is a length in µm: in a scene of much smaller lengths every neighbour list would hold most of the tissue */
    const PetscReal extent = std::max(tissue_.hi[0] - tissue_.lo[0], tissue_.hi[1] - tissue_.lo[1]), r = tissue_.particles.bar_radius;
    if (extent > 0 && physics_.neighbour_skin > 0.25 * extent)
      PetscCall(PetscPrintf(comm_,
                            "WARNING: -neighbour_skin %g µm is more than a quarter of the tissue's size (%g µm): every neighbour list holds most of the "
                            "tissue; a skin of about %g µm (%s) suits this scene\n",
                            (double)physics_.neighbour_skin, (double)extent, (double)(r > 0 ? r : 0.02 * extent),
                            r > 0 ? "the bar radius" : "2% of the tissue's size"));
  }
  PetscCall(controls_.SetUp(comm_, tissue_, in_parts || rank == 0 || distributed)); /* in parts: no control groups */
  if (!in_parts) {
    PetscReal             reach = 0;
    std::vector<PetscInt> local_of;
    if (distributed) PetscCall(reach_of(&reach));
    PetscCall(placement_.Place(comm_, placing, reach, &tissue_, &local_of, have_tissue_ ? nullptr : tissues_.Generator()));
    if (placement_.Distributed()) controls_.Localize(local_of, tissue_.particles);
  }
  PetscCall(TissueReferenceHash(comm_, tissue_, &reference_hash_));
  /* the observed point: the wall particle in the middle of the right side (seed's Fig. 3), on its owner */
  PetscCall(ClosestOwnedWallParticle(comm_, tissue_, tissue_.hi[0], 0.5 * (tissue_.lo[1] + tissue_.hi[1]), &tip_));
  tip_y0_  = tip_ >= 0 ? tissue_.X[2 * tip_ + 1] : 0;
  n_all_   = tissue_.particles.n;
  n_local_ = tissue_.particles.NumOwned();
  { /* the closed cells this rank owns, as their reference orientation (a cell's nodes are its owner's) */
    const ParticleSet &P = tissue_.particles;
    cell_area0_.assign(P.OwnedPolygons(), 0);
    for (size_t c = 0; c < P.OwnedPolygons(); c++)
      if (!P.polygons[c].open && P.polygons[c].nodes.size() >= 3) cell_area0_[c] = PolygonArea(P.polygons[c].nodes, tissue_.X.data());
  }
  PetscCall(CreateSwarm());
  PetscCall(model_.SetUp(physics_, tissue_.particles));
  equations_.SetUp(model_, controls_, placement_.Halo(), tissue_.particles, fields_);
  equations_.SetReproducibleSums(spec_.reproducible_sums == PETSC_TRUE);
  /* the snapshots' further particle fields */
  fields_.Declare("force", "µN", 2, kSnapshot, [this] { return force_.data(); });
  if (spec_.partition > 0) /* -fine_partition_report: the part of the particle's cell */
    fields_.Declare("part", "1", 1, kSnapshot, [this] { return const_cast<PetscReal *>(placement_.ReportParts().data()); });
  if (placement_.Distributed()) {
    /* the rank that owns the particle, made when first written: a run without snapshots holds none */
    auto ranks = [this, rank] {
      if (rank_of_.size() != (size_t)n_local_) rank_of_.assign(n_local_, (PetscReal)rank);
      return rank_of_.data();
    };
    fields_.Declare("rank", "1", 1, kSnapshot, ranks);
  }

  /* state [x | v] and the position/momentum splits used by basicsymplectic */
  PetscInt     start;
  PetscScalar *u;
  PetscCall(VecCreateMPI(comm_, 4 * n_local_, PETSC_DETERMINE, &U_));
  PetscCall(PetscObjectSetName((PetscObject)U_, "state"));
  PetscCall(VecGetOwnershipRange(U_, &start, NULL));
  PetscCall(ISCreateStride(comm_, 2 * n_local_, start, 1, &is_x_));
  PetscCall(ISCreateStride(comm_, 2 * n_local_, start + 2 * n_local_, 1, &is_v_));
  PetscCall(VecGetArray(U_, &u));
  for (PetscInt k = 0; k < 2 * n_local_; k++) {
    u[k]                = tissue_.X[k];
    u[2 * n_local_ + k] = tissue_.V.empty() || tissue_.particles.fixed[k / 2] ? 0 : tissue_.V[k];
  }
  controls_.Impose(0, u, u + 2 * n_local_, n_local_);
  PetscCall(VecRestoreArray(U_, &u));
  if (RestartFile().empty()) ReleaseReferences(); /* a restart primes its references from them first (AfterSetUp) */
  {
    const PetscScalar *u0;
    const PetscReal   *x0 = nullptr, *v0 = nullptr;
    PetscCall(VecGetArrayRead(U_, &u0));
    if (spec_.energy) PetscCall(equations_.LocalState(0, u0, &x0, &v0));
    PetscCall(
      records_.SetUp(comm_, spec_.energy == PETSC_TRUE, spec_.energy_tolerance, placement_.Distributed(), model_, controls_, tissue_.particles, x0, v0));
    PetscCall(VecRestoreArrayRead(U_, &u0));
  }
  PetscCall(equations_.SetTS(ts_, is_x_, is_v_, [this](PetscReal t, Vec U, Vec F, PetscBool *answered) { return ObserveRHS(t, U, F, answered); }));
  PetscCall(equations_.StabilityLimits(U_, limits_, &dt_stable_));
  dt_initial_ = spec_.dt > 0 ? spec_.dt : spec_.dt_safety * dt_stable_;
  PetscCall(TSSetTimeStep(ts_, dt_initial_));
  if (spec_.energy) { /* the round-off's energy: every particle moved by 10 ulps of the largest coordinate, at the stiffest frequency 2 / dt_stable */
    const PetscScalar *u;
    PetscReal          mx[2] = {0, 0}; /* [mass, largest |x|] */
    PetscCall(VecGetArrayRead(U_, &u));
    for (PetscInt i = 0; i < n_local_; i++) {
      mx[0] += tissue_.particles.mass[i];
      mx[1] = std::max({mx[1], std::fabs(PetscRealPart(u[2 * i])), std::fabs(PetscRealPart(u[2 * i + 1]))});
    }
    PetscCall(VecRestoreArrayRead(U_, &u));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx[0], 1, MPIU_REAL, MPIU_SUM, comm_));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mx[1], 1, MPIU_REAL, MPIU_MAX, comm_));
    const PetscReal omega = dt_stable_ > 0 && std::isfinite(dt_stable_) ? 2 / dt_stable_ : 0, dx = 10 * PETSC_MACHINE_EPSILON * mx[1];
    records_.SetRoundOffEnergy(0.5 * mx[0] * omega * omega * dx * dx);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Explicit integrators only: an implicit one would difference a Jacobian of every particle
   interaction (dense, 4n unknowns), which never finishes on a tissue. */
PetscErrorCode FineRun::CheckIntegrator()
{
  PetscBool explicit_type;
  TSType    type;
  PetscFunctionBeginUser;
  PetscCall(TSIsExplicit(ts_, &explicit_type));
  PetscCall(TSGetType(ts_, &type));
  PetscCheck(explicit_type, comm_, PETSC_ERR_SUP,
             "Option -ts_type = %s: -mode fine integrates with explicit methods (rk, lsrk, euler, ssp, verlet, basicsymplectic, am); an implicit one "
             "would need the Jacobian of every particle interaction",
             type);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::AfterTSSetFromOptions()
{
  PetscFunctionBeginUser;
  PetscCall(equations_.ConfigureIntegrator(ts_, fields_, spec_.predict_velocity == PETSC_TRUE));
  if (spec_.predict_velocity) {
    /* a damping-dominated step's limit is half the drift's: 2/(c + sqrt(c^2 + w^2)) against
       2/(c/2 + sqrt(c^2/4 + w^2)) (the same where nothing damps): every limit halved */
    for (TimeStepLimit &l : limits_) l.dt *= 0.5, l.why += " (x 0.5: -fine_predict_velocity)";
    dt_stable_ *= 0.5;
    const char *prefix;
    PetscBool   given;
    PetscCall(TSGetOptionsPrefix(ts_, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_dt", &given));
    if (!given && !(spec_.dt > 0)) {
      dt_initial_ = spec_.dt_safety * dt_stable_;
      PetscCall(TSSetTimeStep(ts_, dt_initial_));
    }
  }
  if (equations_.Split()) PetscCall(FitFixedSteps(0, 0)); /* a fixed step is not clipped at the final time */
  PetscCall(LimitControlSteps());
  if (spec_.reproducible_sums) { /* an adaptive step's 2-norm of the error sums over the ranks in their order: its step sizes, and so the
                                    run, would differ in their last bits; the largest error does not */
    TSAdaptType type;
    NormType    norm;
    PetscBool   none;
    PetscCall(TSAdaptGetTypeAndNorm(ts_, &type, &norm));
    PetscCall(PetscStrcmp(type, TSADAPTNONE, &none));
    PetscCheck(none || norm == NORM_INFINITY, comm_, PETSC_ERR_ARG_INCOMP,
               "Option -fine_reproducible_sums: the adaptive step (-ts_adapt_type %s) measures its error in the 2-norm, a sum over the ranks in their "
               "order, so its steps would differ in their last bits between rank counts; add -ts_adapt_wnormtype infinity",
               type);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A velocity control moves its nodes |v| dt in a step whatever the forces: a move of more than a
   quarter of the contact reach (2 r) between two evaluations lets a node pass through a wall unseen.
   A fixed step that does is refused, naming the control; an adaptive one is capped there. */
PetscErrorCode FineRun::LimitControlSteps()
{
  PetscReal   r = tissue_.particles.bar_radius, vmax = 0, dt;
  std::string name;
  PetscBool   fixed;
  PetscFunctionBeginUser;
  PetscCall(MaxOverRanks(comm_, &r)); /* a rank without particles has no bar radius */
  for (const ControlGroup &g : controls_.Groups()) {
    if (!g.velocity) continue;
    const PetscReal s = std::hypot(g.free[0] ? 0 : g.value[0], g.free[1] ? 0 : g.value[1]);
    if (s > vmax) vmax = s, name = g.name;
  }
  if (!(r > 0) || !(vmax > 0)) PetscFunctionReturn(PETSC_SUCCESS);
  const PetscReal hmax = 0.5 * r / vmax;
  PetscCall(TSGetTimeStep(ts_, &dt));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts_, &fixed, TSBASICSYMPLECTIC, TSVERLET, ""));
  if (fixed) {
    PetscCheck(dt <= hmax, comm_, PETSC_ERR_ARG_OUTOFRANGE,
               "Option -control_%s_velocity: %g µm/µs moves its nodes %g µm in a step of %g µs, more than a quarter of the contact reach 2 r = %g µm: "
               "nodes would pass through walls between two evaluations; lower the velocity, or the step to %g µs (-fine_dt_safety)",
               name.c_str(), (double)vmax, (double)(vmax * dt), (double)dt, (double)(2 * r), (double)hmax);
  } else {
    TSAdapt   adapt;
    PetscReal hmin, hmax_now;
    PetscCall(TSGetAdapt(ts_, &adapt));
    PetscCall(TSAdaptGetStepLimits(adapt, &hmin, &hmax_now));
    if (hmax_now > hmax) PetscCall(TSAdaptSetStepLimits(adapt, PetscMin(hmin, hmax), hmax));
    if (dt > hmax) PetscCall(TSSetTimeStep(ts_, hmax));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::Report()
{
  PetscViewer out  = PETSC_VIEWER_STDOUT_(comm_);
  PetscInt    n[4] = {tissue_.particles.Count(KIND_WALL), tissue_.particles.Count(KIND_FLUID), tissue_.NumCells(), (PetscInt)tissue_.particles.OwnedSprings()};
  TSType      type;
  PetscReal   dt;
  PetscBool   fixed;
  PetscFunctionBeginUser;
  PetscCall(SumOverRanks(comm_, n, 4));
  PetscCall(PetscPrintf(comm_,
                        "turgor fine: %" PetscInt_FMT " cells, %" PetscInt_FMT " wall + %" PetscInt_FMT " fluid particles, %" PetscInt_FMT " springs, clamp:",
                        n[2], n[0], n[1], n[3]));
  for (const std::string &c : spec_.clamp) PetscCall(PetscPrintf(comm_, " %s", c.c_str()));
  PetscCall(PetscPrintf(comm_, "\n"));
  PetscCall(model_.View(out));
  PetscCall(PetscPrintf(comm_, "Explicit stability limits at t = 0 (smallest first):\n"));
  for (const TimeStepLimit &l : limits_) PetscCall(PetscPrintf(comm_, "  dt <= %-11.4g %s\n", (double)l.dt, l.why.c_str()));
  PetscCall(controls_.View(comm_));
  PetscCall(placement_.View(comm_, n_local_));
  PetscCall(TSGetType(ts_, &type));
  PetscCall(TSGetTimeStep(ts_, &dt));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts_, &fixed, TSBASICSYMPLECTIC, TSVERLET, ""));
  PetscCall(PetscPrintf(comm_, "Time integration: %s to t = %g µs, %s dt = %.4g µs\n", type, (double)t_final_, fixed ? "fixed" : "initial", (double)dt));
  /* above the limit an elastic mode grows; a plastic or damaging term may absorb the energy it
     gains, so the run completes with that energy counted as dissipation */
  if (fixed && dt > dt_stable_)
    PetscCall(PetscPrintf(comm_,
                          "WARNING: the fixed step %.4g µs exceeds the smallest stability limit %.4g µs (%s) %.3g times; the run will likely diverge, or, "
                          "where plastic hinges or damage absorb the energy the unstable mode gains, complete with that energy counted as dissipation "
                          "and a drifting energy balance\n",
                          (double)dt, (double)dt_stable_, limits_.empty() ? "no force term" : limits_[0].why.c_str(), (double)(dt / dt_stable_)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::OpenSnapshots()
{
  PetscFunctionBeginUser;
  /* this rank's particles, bars and cells (a distributed run's halo is drawn by its owners); the
     cells' reference areas at the tissue's positions (a restart holds them until its checkpoint's
     state is in, AfterSetUp), else at the initial state */
  const PetscScalar *u;
  std::string        base = "particles";
  if (!RestartFile().empty()) { /* a restart's snapshots go beside the interrupted run's, which stay whole */
    char name[64];
    PetscCall(PetscSNPrintf(name, sizeof name, "particles_restart_%08" PetscInt_FMT, RestartStep()));
    base = name;
  }
  PetscCall(VecGetArrayRead(U_, &u));
  PetscCall(snapshots_writer_.Open(swarm_, tissue_.particles, tissue_.X.empty() ? u : tissue_.X.data(), out_.dir, base));
  PetscCall(VecRestoreArrayRead(U_, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The particle fields declared for the snapshots and the terms' cell and bar fields, all at the
   sampled state. */
PetscErrorCode FineRun::WriteSnapshot(PetscReal t, Vec U)
{
  const PetscScalar             *u;
  const PetscReal               *x, *v;
  ParticleSnapshotWriter::Fields fields;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(equations_.LocalState(t, u, &x, &v));
  model_.SetTime(t);
  force_.resize(2 * n_all_);
  PetscCall(equations_.TotalForces(x, v, force_.data()));
  for (const ParticleField *f : fields_.With(kSnapshot)) { /* the owned particles' values (position and velocity: the geometry and its motion) */
    if (f->name == "position" || f->name == "velocity") continue;
    fields.nodes.push_back({f->name, f->unit, {}, f->components, f->values(), (size_t)(f->components * n_local_)}); /* read in place */
  }
  PetscCall(AddTermSnapshotFields(model_, tissue_.particles, snapshots_writer_, x, v, &fields));
  PetscCall(snapshots_writer_.Write(swarm_, t, x, v, fields));
  std::vector<PetscReal>().swap(force_); /* made again for the next snapshot: 16 B a particle not held between them */
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After every accepted step: the terms' internal state (plastic angles, contact history, bonds) at
   the accepted state, their log rows (breaks.csv), and the energy balance. */
PetscErrorCode FineRun::AfterStep(PetscReal t, Vec U)
{
  const PetscScalar *u;
  const PetscReal   *x, *v;
  PetscFunctionBeginUser;
  if (!model_.HasInternalState() && !records_.Active() && !spec_.energy) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(equations_.IntegratorState(t, u, &x, &v));
  if (model_.HasInternalState()) PetscCall(equations_.AcceptStep(t, x, v));
  PetscCall(records_.AfterStep(t, x, v, t_final_));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* energy.csv (with its first row, the initial state) and the terms' log files. */
PetscErrorCode FineRun::OpenOutputs()
{
  const PetscScalar *u;
  const PetscReal   *x = nullptr, *v = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U_, &u));
  if (spec_.energy && RestartFile().empty()) PetscCall(equations_.LocalState(0, u, &x, &v));
  PetscCall(records_.Open([this](CsvWriter &csv, const std::string &file, const std::vector<std::string> &columns) { return OpenSeries(csv, file, columns); },
                          t_final_, out_.samples, !RestartFile().empty(), x, v));
  PetscCall(VecRestoreArrayRead(U_, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::Observe(PetscReal t, Vec U, std::vector<PetscReal> &row)
{
  const PetscScalar *u;
  PetscReal          vals[3] = {0, 0, 0}, ke = 0;
  PetscFunctionBeginUser;
  const PetscReal *x, *v;
  PetscCall(VecGetArrayRead(U, &u));
  const PetscInt n2 = 2 * n_local_;
  x = u, v = u + n2; /* the owned particles': the state's own, unless controls impose components */
  if (controls_.Active()) PetscCall(equations_.LocalState(t, u, &x, &v));
  const PetscReal *m       = tissue_.particles.mass.data();
  const auto       kinetic = [m, v](PetscInt i) { return 0.5 * m[i] * (v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]); };
  if (spec_.reproducible_sums) PetscCall(ExactSumOverRanks(comm_, n_local_, kinetic, &ke)); /* the same bits on any number of ranks */
  else
    for (PetscInt i = 0; i < n_local_; i++) ke += kinetic(i);
  if (tip_ >= 0) vals[0] = x[2 * tip_ + 1] - tip_y0_;
  vals[1] = spec_.reproducible_sums ? 0 : ke;
  vals[2] = (PetscReal)CountCellsInverted(x);
  PetscCall(SumOverRanks(comm_, vals, 3));
  if (vals[2] > 0) PetscCall(CheckCellsInverted(t, x, (PetscInt)vals[2]));
  PetscCall(VecRestoreArrayRead(U, &u));
  row = {vals[0], spec_.reproducible_sums ? ke : vals[1]};
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A cell whose signed area changed sign (or vanished) has turned inside out: its walls crossed, the
   state is unphysical whatever the integrator reports. Checked at every sample (the tip's cadence,
   -fine_tip_samples), by the cell's owner. */
PetscInt FineRun::CountCellsInverted(const PetscReal *x) const
{
  PetscInt n = 0;
  for (size_t c = 0; c < cell_area0_.size(); c++)
    if (cell_area0_[c] != 0) n += !(PolygonArea(tissue_.particles.polygons[c].nodes, x) / cell_area0_[c] > 0);
  return n;
}

PetscErrorCode FineRun::CheckCellsInverted(PetscReal t, const PetscReal *x, PetscInt inverted)
{
  PetscReal first[3] = {PETSC_MAX_REAL, 0, 0}; /* the lowest inverted cell id, its area and its reference area */
  PetscFunctionBeginUser;
  for (size_t c = 0; c < cell_area0_.size(); c++) {
    if (cell_area0_[c] == 0) continue;
    const PetscReal a = PolygonArea(tissue_.particles.polygons[c].nodes, x), id = (PetscReal)tissue_.particles.PolygonGid(c);
    if (!(a / cell_area0_[c] > 0) && id < first[0]) first[0] = id, first[1] = a, first[2] = cell_area0_[c];
  }
  PetscReal lowest = first[0];
  PetscCall(MinOverRanks(comm_, &lowest));
  if (first[0] != lowest) first[1] = first[2] = 0;
  PetscCall(SumOverRanks(comm_, first + 1, 2)); /* only the owner of the lowest id contributes */
  SETERRQ(comm_, PETSC_ERR_NOT_CONVERGED,
          "Cell %.0f turned inside out at t = %g µs: its area is %g µm² (signed, in its orientation at rest) against %g µm² at rest (%" PetscInt_FMT
          " cell%s inverted); the walls crossed and the state is unphysical -- a smaller step (-fine_dt_safety), stiffer walls or contact, or a "
          "milder load",
          (double)lowest, (double)t, (double)(first[2] > 0 ? first[1] : -first[1]), (double)std::fabs(first[2]), inverted, inverted == 1 ? "" : "s");
}

std::vector<TimeRun::Series> FineRun::ObservedSeries() const
{
  if (!controls_.Active()) return {};
  return {
    {"groups.csv", controls_.Columns()}
  };
}

/* groups.csv: the forces at the sampled state (one evaluation per sample, with controls only) */
PetscErrorCode FineRun::ObserveSeries(PetscReal t, Vec U, std::vector<std::vector<PetscReal>> &rows)
{
  const PetscScalar     *u;
  const PetscReal       *x, *v;
  std::vector<PetscReal> f(2 * n_all_);
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(equations_.LocalState(t, u, &x, &v));
  model_.SetTime(t);
  PetscCall(equations_.TotalForces(x, v, f.data()));
  PetscCall(controls_.Observe(comm_, t, x, f.data(), rows[0]));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::AddSummary(JsonObject &js)
{
  const ParticleSet &P = tissue_.particles;
  /* a polygonal tissue's sizes: nodes are the wall particles, bars the springs */
  PetscInt n[5] = {P.Count(KIND_WALL), P.Count(KIND_FLUID), (PetscInt)P.OwnedSprings(), P.polygons.empty() ? tissue_.NumCells() : (PetscInt)P.OwnedPolygons(),
                   0};
  PetscInt rebuilds = model_.Neighbours().Rebuilds(), steps;
  PetscFunctionBeginUser;
  for (size_t c = 0; c < P.OwnedPolygons(); c++) n[4] += !P.polygons[c].open;
  PetscCall(SumOverRanks(comm_, n, 5));
  PetscCall(MaxOverRanks(comm_, &rebuilds));
  PetscCall(TSGetStepNumber(ts_, &steps));
  const PetscInt  nw = n[0], nf = n[1], nsprings = n[2];
  const PetscReal wall = WallTime();
  js.Set("n_wall_particles", nw);
  js.Set("n_fluid_particles", nf);
  js.Set("n_springs", nsprings);
  js.Set("physics", model_.ActiveTerms());
  js.Set("clamp", spec_.clamp);
  js.Set("dt_stable", dt_stable_);
  js.Set("dt_initial", dt_initial_);
  js.Set("neighbour_rebuilds", rebuilds);
  if (spec_.reproducible_sums) js.Set("force_regrains", equations_.Regrains()); /* the same on every rank */
  js.Set("n_nodes", nw);
  js.Set("n_cells", n[3]);
  if (!P.polygons.empty()) js.Set("n_closed_cells", n[4]);
  js.Set("n_bars", nsprings);
  js.Set("node_steps_per_s", wall > 0 ? (PetscReal)(nw + nf) * steps / wall : 0.0);
  {
    std::vector<PetscReal>   dts;
    std::vector<std::string> why;
    for (const TimeStepLimit &l : limits_) dts.push_back(l.dt), why.push_back(l.why);
    js.Set("stability_limits_dt", dts);
    js.Set("stability_limits", why);
  }
  js.Set("controls", controls_.Names());
  PetscCall(placement_.AddSummary(comm_, js, n_local_, steps));
  PetscCall(records_.AddSummary(js));
  for (const TermStatistic &s : model_.Statistics()) { /* the terms' counters (contacts, plastic dissipation) */
    PetscReal v = s.value;
    if (s.reduction == TermStatistic::MAX) PetscCall(MaxOverRanks(comm_, &v));
    else PetscCall(SumOverRanks(comm_, &v));
    js.Set(s.name, v);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::DoneDetails(std::string *details)
{
  PetscFunctionBeginUser;
  *details = std::to_string(equations_.RHSEvaluations()) + " RHS evaluations";
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- checkpoints ---- */

PetscErrorCode FineRun::CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp)
{
  PetscInt n[2] = {n_local_, tissue_.particles.polygons.empty() ? tissue_.NumCells() : (PetscInt)tissue_.particles.OwnedPolygons()};
  PetscFunctionBeginUser;
  PetscCall(SumOverRanks(comm_, n, 2));
  /* what the options do not show (a node file's contents, the generators' arithmetic); the physics
     parameters are compared one by one besides */
  fp.push_back({"particles", std::to_string((long long)n[0])});
  fp.push_back({"cells", std::to_string((long long)n[1])});
  fp.push_back({"energy", spec_.energy ? "on" : "off"});
  fp.push_back({"reference_positions_hash", reference_hash_});
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The integrator's history is a vector in the state's layout [x | v] (DOPRI's last derivative) or
   in one half's (Verlet's dv/dt): two values per particle and half, kept as columns of the particle
   table (a row per particle holds them under its one key, instead of a row per value). */
bool FineRun::KeepStateVector(std::vector<PetscReal> &values, PetscInt global_size)
{
  PetscInt N4 = 0;
  if (!U_ || VecGetSize(U_, &N4)) return false;
  const int parts = global_size == N4 ? 2 : 2 * global_size == N4 ? 1 : 0; /* the same on every rank */
  if (!parts) return false;
  kept_vectors_.push_back({&values, parts});
  return true;
}

/* Declared state: the particle fields declared for the checkpoints (the state U's position and
   velocity, as SolutionView holds them, and the split integrators' drift velocity), the
   integrator's history (KeepStateVector), the model's (neighbour lists, terms) and the records'. */
PetscErrorCode FineRun::DeclareState(std::deque<StateDeclaration> &decls)
{
  PetscFunctionBeginUser;
  const SolutionSpan u = SolutionView();
  PetscCheck(u.size == (size_t)(4 * n_local_), PETSC_COMM_SELF, PETSC_ERR_PLIB, "The state's view has %zu values for %" PetscInt_FMT " particles", u.size,
             n_local_);
  equations_.Present(u.data, u.data + 2 * n_local_);
  decls.emplace_back("fine");
  StateTable &t = decls.back().Table("particles", StateEntity::Particle).Rows([this] { return (size_t)n_local_; });
  for (const ParticleField *f : fields_.With(kCheckpoint)) {
    PetscReal *a = f->values();
    const int  c = f->components;
    t.Column(
      f->name, c, [a, c](size_t r, PetscReal *out) { std::copy(a + c * r, a + c * (r + 1), out); },
      [a, c](size_t r, const PetscReal *in) { std::copy(in, in + c, a + c * r); });
  }
  for (const auto &kept : kept_vectors_) {
    std::vector<PetscReal> &h = *kept.first;
    PetscCheck(h.size() == (size_t)(2 * kept.second * n_local_), PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "The integrator's history has %zu values for %" PetscInt_FMT " particles", h.size(), n_local_);
    for (int part = 0; part < kept.second; part++) {
      const size_t base = (size_t)(2 * part * n_local_);
      t.Column(
        kept.second == 1 ? "integrator_history"
        : part == 0      ? "integrator_history_x"
                         : "integrator_history_v",
        2, [&h, base](size_t r, PetscReal *out) { std::copy(h.begin() + base + 2 * r, h.begin() + base + 2 * r + 2, out); },
        [&h, base](size_t r, const PetscReal *in) { std::copy(in, in + 2, h.begin() + base + 2 * r); });
    }
  }
  kept_vectors_.clear();
  model_.DeclareState(decls);
  records_.DeclareState(decls);
  PetscFunctionReturn(PETSC_SUCCESS);
}

std::uint64_t FineRun::EntityId(StateEntity e, PetscInt l) const
{
  const ParticleSet &P = tissue_.particles;
  switch (e) {
  case StateEntity::Particle:
    return (std::uint64_t)P.gid[l];
  case StateEntity::Bar:
    return (std::uint64_t)P.SpringGid((size_t)l);
  case StateEntity::Cell:
    return (std::uint64_t)P.PolygonGid((size_t)l);
  default:
    return (std::uint64_t)l;
  }
}

PetscInt FineRun::EntityLocal(StateEntity e, std::uint64_t id) const
{
  /* made when a checkpoint's rows are first read by id (a write needs none: about 100 B a particle
     of hash maps, kept until AfterStateRead) */
  if (!numbering_) numbering_ = std::make_unique<LocalNumbering>(tissue_.particles);
  switch (e) {
  case StateEntity::Particle:
    return numbering_->Particle((PetscInt)id);
  case StateEntity::Bar:
    return numbering_->Spring((PetscInt)id);
  case StateEntity::Cell:
    return numbering_->Polygon((PetscInt)id);
  default:
    return -1;
  }
}

bool FineRun::EntityOwned(StateEntity e, PetscInt l) const
{
  const ParticleSet &P = tissue_.particles;
  switch (e) {
  case StateEntity::Particle:
    return l >= 0 && l < P.NumOwned();
  case StateEntity::Bar:
    return l >= 0 && (size_t)l < P.OwnedSprings();
  case StateEntity::Cell:
    return l >= 0 && (size_t)l < P.OwnedPolygons();
  default:
    return true;
  }
}

/* The particles this rank holds, in order (owned, then the halo): equal on a rank of another run
   that holds the same ones (-fine_distribute 0's rank 0 and a one-rank run). */
std::uint64_t FineRun::LayoutHash() const
{
  const ParticleSet &P   = tissue_.particles;
  std::uint64_t      h   = 1469598103934665603ull;
  auto               mix = [&h](std::uint64_t v) { h = (h ^ v) * 1099511628211ull; };
  mix((std::uint64_t)n_local_);
  mix((std::uint64_t)P.n);
  for (PetscInt l = 0; l < P.n; l++) mix((std::uint64_t)P.gid[l]);
  return h;
}

PetscErrorCode FineRun::AfterStateRead(PetscReal t, Vec U, bool own_layout)
{
  const PetscScalar *u;
  const PetscReal   *x, *v;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(equations_.LocalState(t, u, &x, &v));
  model_.SetTime(t);
  PetscCall(model_.AfterStateRead(x, v, t, own_layout));
  PetscCall(VecRestoreArrayRead(U, &u));
  numbering_.reset();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The lazily taken references (hinge angles, cell areas, bonds at -glue_start_time 0) from the
   initial state, where the uninterrupted run's first evaluation took them. */
PetscErrorCode FineRun::PrimeReferences()
{
  const PetscInt         n2 = 2 * n_all_; /* every local particle's (a distributed run's halo too) */
  std::vector<PetscReal> u0(2 * n2, 0.0), f(n2);
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n2; k++) {
    u0[k]      = tissue_.X[k];
    u0[n2 + k] = tissue_.V.empty() || tissue_.particles.fixed[k / 2] ? 0 : tissue_.V[k];
  }
  controls_.Impose(0, u0.data(), u0.data() + n2);
  model_.SetTime(0);
  PetscCall(model_.ComputeForces(u0.data(), u0.data() + n2, f.data(), NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::StateOrder(IS *order)
{
  PetscInt  n = 4 * n_local_, N = n_local_;
  PetscInt *idx; /* handed to the IS (no copy) */
  PetscFunctionBeginUser;
  PetscCall(SumOverRanks(comm_, &N));
  PetscCall(PetscMalloc1(n, &idx));
  for (PetscInt k = 0; k < n; k++) idx[k] = StateIndex(k, N);
  PetscCall(ISCreateGeneral(comm_, n, idx, PETSC_OWN_POINTER, order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* entry by entry: no IS of 16 B a particle at the end of the run, where the memory peaks */
PetscErrorCode FineRun::StateChecksum(Vec U, std::uint64_t *h)
{
  const PetscScalar *u;
  PetscInt           N = n_local_;
  PetscFunctionBeginUser;
  PetscCall(SumOverRanks(comm_, &N));
  PetscCall(VecGetArrayRead(U, &u));
  for (PetscInt k = 0; k < 4 * n_local_; k++) *h += ChecksumTerm((std::uint64_t)StateIndex(k, N), (PetscReal)PetscRealPart(u[k]));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
