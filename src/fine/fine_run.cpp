#include <turgor/core/options.h>
#include <turgor/core/errors.h>
#include <turgor/core/memory.h>
#include <turgor/fine/fine_run.h>
#include <turgor/particles/local_numbering.h>
#include <turgor/ts/velocity_verlet.h>
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cmath>

namespace turgor {

PetscErrorCode FineRunSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char     *sides[8];
  PetscInt  nsides = 8;
  PetscBool set, pset, hset;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "fine_", "Full fine-scale run (-mode fine)", "turgor");
  PetscCall(TurgorOptionsReal(params, "-dt_safety", "Fixed-step integrators: dt = safety x the smallest stability limit (unless -ts_dt is given)",
                              "FineRunSpec", dt_safety, &dt_safety, NULL));
  {
    PetscBool e = energy ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscOptionsBool("-energy", "Write the energy balance energy.csv (kinetic, stored, work of controls and loads, dissipated, residual)",
                               "FineRunSpec", e, &e, NULL));
    energy = e;
  }
  PetscCall(PetscOptionsInt("-partition_report",
                            "Partition the tissue's cells into N parts with METIS (cell graph weighted by particles per cell and shared wall length) and "
                            "report the edge cut and imbalance in summary.json and the particles' part in the snapshots (a report only: a run on several "
                            "ranks partitions its cells by itself, -fine_distribute; 0: no report)",
                            "FineRunSpec", partition, &partition, &pset));
  {
    PetscBool d = distribute ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscOptionsBool("-distribute",
                               "On several ranks, partition the cells with METIS and keep every particle on the rank of its cell, with a halo of the "
                               "neighbouring ranks' particles (false: all particles on rank 0, the other ranks idle)",
                               "FineRunSpec", d, &d, NULL));
    distribute = d;
  }
  PetscCall(PetscOptionsReal("-halo_margin",
                             "Distributed runs: width [µm] of the halo beyond the interactions' reach (cutoffs + neighbour skin); cells may move this "
                             "far relative to each other before the run stops (default: the reach)",
                             "FineRunSpec", halo_margin, &halo_margin, &hset));
  /* last, and its strings taken at once: an error in another option must not leave them allocated */
  PetscCall(PetscOptionsStringArray("-clamp", "Tissue sides whose wall particles are fixed: left,right,bottom,top or none (default: left)", "FineRunSpec",
                                    sides, &nsides, &set));
  PetscOptionsEnd();
  std::vector<std::string> listed;
  for (PetscInt k = 0; set && k < nsides; k++) {
    listed.push_back(sides[k]);
    PetscCall(PetscFree(sides[k]));
  }
  PetscCheck(!hset || (halo_margin >= 0 && std::isfinite(halo_margin)), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_halo_margin = %g: must be >= 0",
             (double)halo_margin);
  PetscCheck(!pset || partition >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_partition_report = %" PetscInt_FMT ": the number of parts must be >= 1",
             partition);
  PetscCheck(!set || nsides < 8, comm, PETSC_ERR_ARG_SIZ, "Option -fine_clamp: more than 7 sides listed");
  PetscCall(CheckNotEmpty(comm, "-fine_clamp", "sides: left, right, bottom, top, or none"));
  if (set) clamp = listed;
  PetscCheck(dt_safety > 0 && dt_safety <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -fine_dt_safety = %g: must be in (0, 1]", (double)dt_safety);
  if (params) {
    std::string all;
    for (const std::string &c : clamp) all += (all.empty() ? "" : ",") + c;
    params->Set("-fine_clamp", all.empty() ? "none" : all);
  }
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
  const ParticleSet &P = tissue_.particles;
  PetscInt          *kind, *cell;
  PetscInt64        *pid;

  PetscFunctionBeginUser;
  PetscCall(DMCreate(comm_, &swarm_));
  PetscCall(PetscObjectSetName((PetscObject)swarm_, "tissue"));
  PetscCall(DMSetType(swarm_, DMSWARM));
  PetscCall(DMSetDimension(swarm_, 2));
  PetscCall(DMSwarmSetType(swarm_, DMSWARM_BASIC));
  PetscCall(DMSwarmRegisterPetscDatatypeField(swarm_, "kind", 1, PETSC_INT));
  PetscCall(DMSwarmRegisterPetscDatatypeField(swarm_, "cell", 1, PETSC_INT));
  PetscCall(DMSwarmFinalizeFieldRegister(swarm_));
  PetscCall(DMSwarmSetLocalSizes(swarm_, n_local_, 0));
  PetscCall(DMSwarmGetField(swarm_, "kind", NULL, NULL, (void **)&kind));
  PetscCall(DMSwarmGetField(swarm_, "cell", NULL, NULL, (void **)&cell));
  PetscCall(DMSwarmGetField(swarm_, DMSwarmField_pid, NULL, NULL, (void **)&pid));
  for (PetscInt i = 0; i < n_local_; i++) { /* the owned particles come first */
    kind[i] = P.kind[i];
    cell[i] = P.cell[i];
    pid[i]  = P.gid[i];
  }
  PetscCall(DMSwarmRestoreField(swarm_, DMSwarmField_pid, NULL, NULL, (void **)&pid));
  PetscCall(DMSwarmRestoreField(swarm_, "cell", NULL, NULL, (void **)&cell));
  PetscCall(DMSwarmRestoreField(swarm_, "kind", NULL, NULL, (void **)&kind));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::LocalState(PetscReal t, const PetscScalar *x, const PetscScalar *v, const PetscReal **xc, const PetscReal **vc)
{
  PetscFunctionBeginUser;
  if (!controls_.Active() && !distributed_) {
    *xc = x, *vc = v;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  const PetscInt n2 = 2 * n_local_;
  xw_.resize(2 * n_all_);
  std::copy(x, x + n2, xw_.begin());
  PetscReal *vl;                                                                                                    /* v with its halo */
  if (!controls_.Active() && v == v_stale_.data() && v_stale_.size() == (size_t)(2 * n_all_)) vl = v_stale_.data(); /* room for the halo: in place */
  else {
    vw_.resize(2 * n_all_);
    std::copy(v, v + n2, vw_.begin());
    vl = vw_.data();
  }
  if (distributed_) PetscCall(dist_.Gather(xw_.data(), vl));
  controls_.Impose(t, xw_.data(), vl);
  if (distributed_) PetscCall(dist_.Check(xw_.data()));
  *xc = xw_.data(), *vc = vl;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::TotalForces(const PetscReal *x, const PetscReal *v, PetscReal *f)
{
  PetscFunctionBeginUser;
  PetscCall(model_.ComputeForces(x, v, f, NULL));
  if (distributed_) PetscCall(dist_.Return(f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::Accelerations(const PetscReal *x, const PetscReal *v, PetscScalar *a, bool a_has_halo_room)
{
  PetscFunctionBeginUser;
  if (!distributed_) { /* the state's array holds every particle: no copy */
    PetscCall(model_.ComputeAcceleration(x, v, a));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (a_has_halo_room) { /* the halo's forces in a's spare tail, returned from there */
    PetscCall(TotalForces(x, v, a));
    model_.DivideByMass(a, a, n_local_);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  fw_.resize(2 * n_all_);
  PetscCall(TotalForces(x, v, fw_.data()));
  model_.DivideByMass(fw_.data(), a, n_local_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The METIS partition of the whole tissue on rank 0 (every rank holds the tissue here; the other
   ranks drop it after SetUp), its statistics broadcast to every rank. */
PetscErrorCode FineRun::PartitionCellsReport()
{
  const char *option = "-fine_partition_report";
  PetscMPIInt rank;
  PetscInt    ncells = tissue_.particles.polygons.empty() ? tissue_.NumCells() : (PetscInt)tissue_.particles.OwnedPolygons();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCallMPI(MPI_Bcast(&ncells, 1, MPIU_INT, 0, comm_));
  PetscCheck(spec_.partition <= ncells, comm_, PETSC_ERR_ARG_OUTOFRANGE, "Option %s = %" PetscInt_FMT ": more parts than the tissue's %" PetscInt_FMT " cells",
             option, spec_.partition, ncells);
  PetscErrorCode failed = PETSC_SUCCESS; /* a failure on rank 0 ends every rank */
  PetscReal     *stats  = partition_stats_;
  if (rank == 0) {
    CellGraph graph;
    failed = BuildCellGraph(PETSC_COMM_SELF, tissue_, &graph);
    if (!failed) failed = PartitionCells(PETSC_COMM_SELF, graph, spec_.partition, MetisOptions(), option, &partition_);
    if (!failed) {
      std::vector<PetscInt> part;
      ParticleParts(tissue_, partition_, &part);
      particle_part_.assign(part.begin(), part.end());
      stats[0] = (PetscReal)partition_.edge_cut;
      stats[1] = partition_.edge_cut_length;
      stats[2] = partition_.imbalance;
      stats[3] = partition_.metis_seconds;
      stats[4] = (PetscReal)*std::min_element(partition_.part_particles.begin(), partition_.part_particles.end());
      stats[5] = (PetscReal)*std::max_element(partition_.part_particles.begin(), partition_.part_particles.end());
    }
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm_));
  PetscCheck(!failed, comm_, PETSC_ERR_LIB, "Option %s = %" PetscInt_FMT ": the cell partition failed on rank 0", option, spec_.partition);
  PetscCallMPI(MPI_Bcast(stats, 6, MPIU_REAL, 0, comm_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every rank holds the whole tissue here: the cells are partitioned on rank 0 (METIS, weighted
   as in cell_partition.h), and each rank keeps its cells' particles and its halo
   (tissue_distribution.h). */
PetscErrorCode FineRun::Distribute()
{
  const char *option = "-fine_distribute";
  PetscMPIInt size, rank;
  PetscInt    ncells = tissue_.NumCells();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCheck(ncells >= size, comm_, PETSC_ERR_ARG_OUTOFRANGE,
             "A distributed fine run needs at least one cell per rank: %d ranks for %" PetscInt_FMT " cells (use fewer ranks, or %s 0)", size, ncells, option);
  std::vector<PetscInt> cell_rank(ncells, 0);
  PetscErrorCode        failed = PETSC_SUCCESS;
  if (rank == 0) {
    CellGraph     graph;
    CellPartition part;
    failed = BuildCellGraph(PETSC_COMM_SELF, tissue_, &graph);
    if (!failed) failed = PartitionCells(PETSC_COMM_SELF, graph, size, MetisOptions(), option, &part);
    if (!failed) cell_rank = part.part;
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm_));
  PetscCheck(!failed, comm_, PETSC_ERR_LIB, "Option %s: the cell partition failed on rank 0", option);
  PetscCallMPI(MPI_Bcast(cell_rank.data(), (PetscMPIInt)ncells, MPIU_INT, 0, comm_));
  /* the halo: the farthest reach of any term into another cell, with the neighbour lists' skin */
  halo_reach_ = 0;
  for (const auto &t : physics_.Terms()) halo_reach_ = std::max(halo_reach_, t->Reach(tissue_.particles));
  halo_reach_ += physics_.neighbour_skin;
  halo_margin_ = spec_.halo_margin >= 0 ? spec_.halo_margin : halo_reach_;
  Tissue                local;
  std::vector<PetscInt> local_of;
  PetscCall(dist_.SetUp(comm_, tissue_, cell_rank, halo_reach_, halo_margin_, &local, &local_of));
  controls_.Localize(local_of, local.particles);
  tip_ = tip_ >= 0 ? local_of[tip_] : -1;
  if (tip_ >= dist_.NumOwned()) tip_ = -1; /* observed by its owner */
  if (spec_.partition > 0) {               /* the report's part of every owned particle (rank 0 computed them) */
    std::vector<PetscReal> all(tissue_.particles.n);
    if (rank == 0) all = particle_part_;
    PetscCallMPI(MPI_Bcast(all.data(), (PetscMPIInt)all.size(), MPIU_REAL, 0, comm_));
    particle_part_.resize(dist_.NumOwned());
    for (PetscInt l = 0; l < dist_.NumOwned(); l++) particle_part_[l] = all[local.particles.gid[l]];
  }
  tissue_ = std::move(local);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::SetUpModel()
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (!have_tissue_) {
    PetscReal particles, springs;
    PetscCall(tissues_.Generator()->Estimate(&particles, &springs));
    const std::string what = "the fine tissue (" + tissues_.Generator()->SizeOptions() + ": " + std::to_string((long long)particles) + " particles)";
    PetscCall(CheckCount(comm_, 4 * particles, what + ", its state vector"));
    PetscCall(CheckMemory(comm_, rank == 0 ? kProcessBytes + kBytesPerParticle * particles : kProcessBytes, what));
    PetscCall(tissues_.Generate(comm_, &tissue_));
  }
  PetscCall(tissue_.Clamp(comm_, spec_.clamp, "-fine_clamp"));
  {
    /* the checkpoints' fingerprint of the reference positions and masses (FNV-1a), of the whole
       tissue, which every rank holds here (rank 0's, broadcast: the same bits everywhere) */
    std::uint64_t hash = 1469598103934665603ull;
    auto          add  = [&hash](const void *p, size_t bytes) {
      const unsigned char *b = (const unsigned char *)p;
      for (size_t k = 0; k < bytes; k++) hash = (hash ^ b[k]) * 1099511628211ull;
    };
    add(tissue_.X.data(), tissue_.X.size() * sizeof(PetscReal));
    add(tissue_.particles.mass.data(), tissue_.particles.mass.size() * sizeof(PetscReal));
    PetscCallMPI(MPI_Bcast(&hash, 1, MPI_UINT64_T, 0, comm_));
    char hex[24];
    PetscCall(PetscSNPrintf(hex, sizeof hex, "%016llx", (unsigned long long)hash));
    reference_hash_ = hex;
  }
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    distributed_ = size > 1 && spec_.distribute;
  }
  PetscCall(controls_.SetUp(comm_, tissue_, rank == 0 || distributed_));
  if (spec_.partition > 0) PetscCall(PartitionCellsReport());
  /* the observed point: the wall particle in the middle of the right side (seed's Fig. 3) */
  tip_    = tissue_.ClosestWallParticle(tissue_.hi[0], 0.5 * (tissue_.lo[1] + tissue_.hi[1]));
  tip_y0_ = tip_ >= 0 ? tissue_.X[2 * tip_ + 1] : 0;
  if (distributed_) PetscCall(Distribute());
  else if (rank != 0) {
    /* -fine_distribute 0: rank 0 holds the whole tissue, the other ranks none */
    tissue_ = Tissue();
    tip_    = -1;
  }
  n_all_   = tissue_.particles.n;
  n_local_ = tissue_.particles.NumOwned();
  PetscCall(CreateSwarm());
  PetscCall(model_.SetUp(physics_, tissue_.particles));

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
  if (spec_.energy) {
    const PetscScalar *u0;
    const PetscReal   *x0, *v0;
    PetscCall(energy_.SetUp(model_, controls_, tissue_.particles));
    PetscCall(VecGetArrayRead(U_, &u0));
    PetscCall(LocalState(0, u0, u0 + 2 * n_local_, &x0, &v0));
    PetscCall(energy_.Start(comm_, 0, x0, v0));
    PetscCall(VecRestoreArrayRead(U_, &u0));
  }

  PetscCall(TSSetRHSFunction(ts_, NULL, RHSFunction, this));
  PetscCall(TSRHSSplitSetIS(ts_, "position", is_x_));
  PetscCall(TSRHSSplitSetIS(ts_, "momentum", is_v_));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "position", NULL, RHSPosition, this));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "momentum", NULL, RHSMomentum, this));
  PetscCall(TSSetFunctionDomainError(ts_, CheckDomain));
  PetscCall(ChooseTimeStep());
  dt_initial_ = spec_.dt > 0 ? spec_.dt : spec_.dt_safety * dt_stable_;
  PetscCall(TSSetTimeStep(ts_, dt_initial_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Explicit integrators only: an implicit one would difference a Jacobian of every particle
   interaction (dense, 4n unknowns), which never finishes on a tissue. */
PetscErrorCode FineRun::CheckIntegrator()
{
  PetscBool explicit_type;
  TSType    type;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts_, &explicit_type, TSRK, TSEULER, TSSSP, TSBASICSYMPLECTIC, TSVERLET, "am", ""));
  PetscCall(TSGetType(ts_, &type));
  PetscCheck(explicit_type, comm_, PETSC_ERR_SUP,
             "Option -ts_type = %s: -mode fine integrates with explicit methods (rk, euler, ssp, verlet, basicsymplectic, am); an implicit one would need the "
             "Jacobian "
             "of every particle interaction",
             type);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::AfterTSSetFromOptions()
{
  PetscBool symplectic, kdk;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSBASICSYMPLECTIC, &symplectic));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts_, TSVERLET, &kdk));
  if (!symplectic && !kdk) PetscFunctionReturn(PETSC_SUCCESS);
  /* the split integrators' velocities of the last position update; a distributed run without
     controls gathers the halo's into their tail (LocalState: no copy of the velocities) */
  v_stale_.assign(2 * (distributed_ && !controls_.Active() ? n_all_ : n_local_), 0);
  split_ = true;
  if (kdk) {
    drift_fraction_ = 1.0; /* one drift of h per step */
    if (distributed_) {    /* its accelerations carry room for the halo's forces (Accelerations) */
      PetscCall(TSVerletSetAccelerationRoom(ts_, 2 * (n_all_ - n_local_)));
      acceleration_room_ = true;
      if (v_stale_.size() == (size_t)(2 * n_all_)) std::vector<PetscReal>().swap(vw_); /* the set-up's copy: the force evaluations gather into v_stale_ */
    }
  } else {
    /* PETSc's basicsymplectic defaults to first-order symplectic Euler; velocity Verlet unless asked */
    const char *prefix;
    PetscBool   chosen;
    PetscCall(TSGetOptionsPrefix(ts_, &prefix));
    PetscCall(PetscOptionsHasName(NULL, prefix, "-ts_basicsymplectic_type", &chosen));
    if (!chosen) PetscCall(TSBasicSymplecticSetType(ts_, TSBASICSYMPLECTICVELVERLET));
    /* PETSc 3.18's schemes: velocity Verlet drifts twice by h/2, symplectic Euler once by h; for the
       others a controlled velocity is taken at the start of each drift (first order in time) */
    TSBasicSymplecticType scheme;
    PetscBool             verlet, euler;
    PetscCall(TSBasicSymplecticGetType(ts_, &scheme));
    PetscCall(PetscStrcmp(scheme, TSBASICSYMPLECTICVELVERLET, &verlet));
    PetscCall(PetscStrcmp(scheme, TSBASICSYMPLECTICSIEULER, &euler));
    drift_fraction_ = verlet ? 0.5 : euler ? 1.0 : 0.0;
  }
  PetscCall(FitFixedSteps(0, 0)); /* a fixed step is not clipped at the final time */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::Report()
{
  PetscViewer out = PETSC_VIEWER_STDOUT_(comm_);
  PetscInt    nw, nf, nl[2] = {tissue_.particles.Count(KIND_WALL), tissue_.particles.Count(KIND_FLUID)};
  TSType      type;
  PetscReal   dt;
  PetscBool   fixed;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&nl[0], &nw, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(&nl[1], &nf, 1, MPIU_INT, MPI_SUM, comm_));
  PetscInt ncells = tissue_.NumCells(), nsprings = (PetscInt)tissue_.particles.OwnedSprings();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nsprings, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCall(PetscPrintf(comm_,
                        "turgor fine: %" PetscInt_FMT " cells, %" PetscInt_FMT " wall + %" PetscInt_FMT " fluid particles, %" PetscInt_FMT " springs, clamp:",
                        ncells, nw, nf, nsprings));
  for (const std::string &c : spec_.clamp) PetscCall(PetscPrintf(comm_, " %s", c.c_str()));
  PetscCall(PetscPrintf(comm_, "\n"));
  PetscCall(model_.View(out));
  PetscCall(PetscPrintf(comm_, "Explicit stability limits at t = 0 (smallest first):\n"));
  for (const TimeStepLimit &l : limits_) PetscCall(PetscPrintf(comm_, "  dt <= %-11.4g %s\n", (double)l.dt, l.why.c_str()));
  PetscCall(controls_.View(comm_));
  if (distributed_) {
    PetscReal   r[3] = {(PetscReal)n_local_, -(PetscReal)n_local_, (PetscReal)dist_.NumHalo()};
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, r, 3, MPIU_REAL, MPIU_MAX, comm_));
    PetscCall(PetscPrintf(comm_,
                          "Distributed over %d ranks (METIS cells, -fine_distribute): %.0f..%.0f particles per rank, halo up to %.0f particles "
                          "(cells within %.4g µm reach + %.4g µm -fine_halo_margin); the terms' lines above count rank 0's particles\n",
                          size, -(double)r[1], (double)r[0], (double)r[2], (double)halo_reach_, (double)halo_margin_));
  }
  if (spec_.partition > 0)
    PetscCall(PetscPrintf(comm_,
                          "Cell partition (METIS, -fine_partition_report; a report): %" PetscInt_FMT
                          " parts, edge cut %.0f walls (%.4g µm), particles per part %.0f..%.0f, imbalance %.4f, METIS %.3g s\n",
                          spec_.partition, (double)partition_stats_[0], (double)partition_stats_[1], (double)partition_stats_[4], (double)partition_stats_[5],
                          (double)partition_stats_[2], (double)partition_stats_[3]));
  PetscCall(TSGetType(ts_, &type));
  PetscCall(TSGetTimeStep(ts_, &dt));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts_, &fixed, TSBASICSYMPLECTIC, TSVERLET, ""));
  PetscCall(PetscPrintf(comm_, "Time integration: %s to t = %g µs, %s dt = %.4g µs\n", type, (double)t_final_, fixed ? "fixed" : "initial", (double)dt));
  if (fixed && dt > dt_stable_)
    PetscCall(PetscPrintf(comm_, "WARNING: the fixed step %.4g µs exceeds the smallest stability limit %.4g µs; the run will likely diverge\n", (double)dt,
                          (double)dt_stable_));
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

/* The particles (from the swarm), the force on every particle and the terms' cell and bar fields,
   all at the sampled state. */
PetscErrorCode FineRun::WriteSnapshot(PetscReal t, Vec U)
{
  const PetscScalar             *u;
  const PetscReal               *x, *v;
  ParticleSnapshotWriter::Fields fields;
  std::vector<TermField>         terms;
  ParticleSnapshotWriter::Field  force{"force", "µN", std::vector<PetscReal>(2 * n_all_), 2};
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(LocalState(t, u, u + 2 * n_local_, &x, &v));
  model_.SetTime(t);
  PetscCall(TotalForces(x, v, force.values.data()));
  force.values.resize(2 * n_local_); /* the owned particles' */
  PetscCall(model_.OutputFields(x, v, terms));
  {
    std::vector<TermSegments> segs;
    PetscCall(model_.OutputSegments(x, v, segs));
    for (TermSegments &g : segs) {
      ParticleSnapshotWriter::Segments w{g.name, std::move(g.xy), {}};
      for (TermField &f : g.fields) w.fields.push_back({f.name, f.unit, std::move(f.values), 1});
      fields.segments.push_back(std::move(w));
    }
  }
  fields.nodes.push_back(std::move(force));
  if (spec_.partition > 0) fields.nodes.push_back({"part", "1", particle_part_, 1}); /* -fine_partition_report: the part of the particle's cell */
  if (distributed_) {
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    fields.nodes.push_back({"rank", "1", std::vector<PetscReal>(n_local_, (PetscReal)rank), 1}); /* the rank that owns the particle */
  }
  /* this rank's bars and closed cells (they come first: particles.h) */
  const ParticleSet &P      = tissue_.particles;
  size_t             closed = 0;
  for (size_t c = 0; c < P.OwnedPolygons(); c++) closed += !P.polygons[c].open && P.polygons[c].nodes.size() >= 3;
  for (TermField &f : terms) {
    if (f.where == TermField::CELL && P.polygons.empty()) continue; /* the square grid has no polygon grid */
    f.values.resize(f.where == TermField::CELL ? closed : P.OwnedSprings());
    (f.where == TermField::CELL ? fields.cells : fields.bars).push_back({f.name, f.unit, std::move(f.values), 1});
  }
  PetscCall(snapshots_writer_.Write(swarm_, t, x, v, fields));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

using TextRows = std::vector<std::vector<std::string>>;

/* Every rank's rows of text cells, in rank order: on rank 0 only (to_all false; the others get
   none) or on every rank. A row travels as its cells separated by unit separators, ended by a
   record separator. */
static PetscErrorCode GatherRows(MPI_Comm comm, bool to_all, const TextRows &mine, TextRows *all)
{
  const char  US = '\x1f', RS = '\x1e';
  std::string text;
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (const auto &row : mine) {
    for (size_t c = 0; c < row.size(); c++) text += (c ? std::string(1, US) : std::string()) + row[c];
    text += RS;
  }
  PetscMPIInt              len = (PetscMPIInt)text.size();
  std::vector<PetscMPIInt> lens(size), displs(size + 1, 0);
  if (to_all) PetscCallMPI(MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, comm));
  else PetscCallMPI(MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, comm));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + lens[r];
  std::string joined(to_all || rank == 0 ? (size_t)displs[size] : 0, '\0');
  if (to_all) PetscCallMPI(MPI_Allgatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, comm));
  else PetscCallMPI(MPI_Gatherv(text.data(), len, MPI_CHAR, joined.data(), lens.data(), displs.data(), MPI_CHAR, 0, comm));
  all->clear();
  for (size_t at = 0; at < joined.size();) {
    const size_t             end = joined.find(RS, at);
    std::vector<std::string> row;
    for (size_t p = at;;) {
      const size_t q = std::min(joined.find(US, p), end);
      row.push_back(joined.substr(p, q - p));
      if (q == end) break;
      p = q + 1;
    }
    all->push_back(std::move(row));
    at = end + 1;
  }
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

/* The smallest stability limit at the initial state; printed at start. Adaptive RK uses it only as
   its first step; basicsymplectic uses dt_safety times it unless -ts_dt is given. */
PetscErrorCode FineRun::ChooseTimeStep()
{
  const PetscScalar *u;
  const PetscReal   *x, *v;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U_, &u));
  PetscCall(LocalState(0, u, u + 2 * n_local_, &x, &v));
  PetscCall(model_.TimeStepLimits(x, v, limits_));
  PetscCall(VecRestoreArrayRead(U_, &u));
  if (distributed_) PetscCall(SmallestLimits(comm_, limits_));
  std::sort(limits_.begin(), limits_.end(), [](const TimeStepLimit &a, const TimeStepLimit &b) { return a.dt < b.dt; });
  PetscReal dt = limits_.empty() ? PETSC_MAX_REAL : limits_[0].dt;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPIU_REAL, MPIU_MIN, comm_));
  if (dt == PETSC_MAX_REAL) dt = 1e-3; /* no forces at all */
  dt_stable_ = dt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::RHSFunction(TS ts, PetscReal t, Vec U, Vec F, void *ctx)
{
  return TURGOR_GUARDED({
    FineRun           *run = (FineRun *)ctx;
    const PetscInt     n2  = 2 * run->n_local_;
    const PetscScalar *u;
    PetscScalar       *f;
    PetscBool          answered;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    PetscCall(run->ObserveRHS(t, U, F, &answered)); /* a restart's first derivative, the FSAL stage */
    if (answered) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(VecGetArrayRead(U, &u));
    PetscCall(VecGetArray(F, &f));
    const std::vector<char> &fixed = run->tissue_.particles.fixed;
    run->model_.SetTime(t);
    /* with controls, the controlled components: x and v imposed, dx/dt = v_c(t), v not integrated */
    const PetscReal *x, *v;
    PetscCall(run->LocalState(t, u, u + n2, &x, &v));
    for (PetscInt k = 0; k < n2; k++) f[k] = fixed[k / 2] ? 0 : v[k];
    PetscCall(run->Accelerations(x, v, f + n2));
    if (run->controls_.Active()) run->controls_.AdjustAccelerations(t, f + n2);
    PetscCall(VecRestoreArray(F, &f));
    PetscCall(VecRestoreArrayRead(U, &u));
    run->rhs_evals_++;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* Velocity Verlet (TSVERLET, TSBASICSYMPLECTIC) evaluates dx/dt = v and dv/dt = a(x) separately. The
   dashpot and viscous forces also need v: they use the velocity of the preceding position update. */
PetscErrorCode FineRun::RHSPosition(TS ts, PetscReal t, Vec V, Vec Xdot, void *ctx)
{
  return TURGOR_GUARDED({
    FineRun           *run = (FineRun *)ctx;
    const PetscScalar *v;
    PetscScalar       *xd;
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(V, &v));
    PetscCall(VecGetArray(Xdot, &xd));
    const std::vector<char> &fixed = run->tissue_.particles.fixed;
    for (PetscInt k = 0; k < 2 * run->n_local_; k++) {
      xd[k]            = fixed[k / 2] ? 0 : v[k];
      run->v_stale_[k] = v[k];
    }
    if (run->controls_.Active()) {
      PetscReal h;
      PetscCall(TSGetTimeStep(run->ts_, &h));
      run->controls_.PositionRates(t, run->drift_fraction_ * h, xd);
    }
    PetscCall(VecRestoreArray(Xdot, &xd));
    PetscCall(VecRestoreArrayRead(V, &v));
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FineRun::RHSMomentum(TS ts, PetscReal t, Vec X, Vec Vdot, void *ctx)
{
  return TURGOR_GUARDED({
    FineRun           *run = (FineRun *)ctx;
    const PetscScalar *x;
    PetscScalar       *a;
    PetscFunctionBeginUser;
    PetscCall(CheckStopNow());
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArray(Vdot, &a));
    run->model_.SetTime(t);
    const PetscReal *xc, *vc;
    PetscCall(run->LocalState(t, x, run->v_stale_.data(), &xc, &vc));
    PetscCall(run->Accelerations(xc, vc, a, run->acceleration_room_));
    if (run->controls_.Active()) run->controls_.AdjustAccelerations(t, a);
    for (PetscInt k = 0; k < 2 * run->n_local_; k++)
      PetscCheck(std::isfinite(a[k]), PETSC_COMM_SELF, PETSC_ERR_FP,
                 "Non-finite acceleration of particle %" PetscInt_FMT
                 " at t = %g µs: the fixed step is above the stability limit (lower -ts_dt or -fine_dt_safety)",
                 k / 2, (double)t);
    PetscCall(VecRestoreArray(Vdot, &a));
    PetscCall(VecRestoreArrayRead(X, &x));
    run->rhs_evals_++;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

/* A distributed run: every rank's log rows (file, cells) to rank 0, which writes the files. */
static PetscErrorCode GatherRecords(MPI_Comm comm, std::vector<std::pair<std::string, std::vector<std::string>>> &rows)
{
  TextRows mine, all;
  PetscFunctionBeginUser;
  for (auto &r : rows) {
    mine.push_back({r.first});
    mine.back().insert(mine.back().end(), r.second.begin(), r.second.end());
  }
  PetscCall(GatherRows(comm, false, mine, &all));
  rows.clear();
  for (auto &row : all) rows.push_back({row.front(), std::vector<std::string>(row.begin() + 1, row.end())});
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After every accepted step: the terms' internal state (plastic angles, contact history, bonds) at
   the accepted state, their log rows (breaks.csv), and the energy balance. */
PetscErrorCode FineRun::AfterStep(PetscReal t, Vec U)
{
  const PetscScalar *u;
  const PetscReal   *x, *v;
  PetscFunctionBeginUser;
  if (!model_.HasInternalState() && !spec_.energy) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(LocalState(t, u, u + 2 * n_local_, &x, &v));
  if (model_.HasInternalState()) PetscCall(model_.AcceptStep(x, v, t));
  if (!record_csv_.empty()) {
    std::vector<std::pair<std::string, std::vector<std::string>>> rows;
    model_.TakeRecords(rows);
    if (distributed_) PetscCall(GatherRecords(comm_, rows));
    for (auto &r : rows)
      for (size_t k = 0; k < record_names_.size(); k++)
        if (record_names_[k] == r.first && record_csv_[k]->IsOpen()) PetscCall(record_csv_[k]->RowText(r.second));
  }
  if (spec_.energy) {
    PetscCall(energy_.Step(t, x, v));
    if (t >= energy_next_ * (1 - 1e-12) || t >= t_final_ * (1 - 1e-12)) {
      PetscCall(EnergyRow(t, x, v));
      while (energy_next_ <= t * (1 + 1e-12)) energy_next_ += energy_every_;
    }
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::EnergyRow(PetscReal t, const PetscReal *x, const PetscReal *v)
{
  std::vector<PetscReal> row;
  PetscReal              rel;
  PetscFunctionBeginUser;
  PetscCall(energy_.Row(comm_, x, v, row, &rel));
  row.insert(row.begin(), t);
  if (energy_csv_.IsOpen()) PetscCall(energy_csv_.Row(row));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* energy.csv (with its first row, the initial state) and the terms' log files. */
PetscErrorCode FineRun::OpenOutputs()
{
  PetscFunctionBeginUser;
  std::vector<std::pair<std::string, std::vector<std::string>>> files;
  model_.RecordFiles(files);
  record_names_.clear();
  record_csv_.clear();
  for (auto &f : files) {
    record_names_.push_back(f.first);
    record_csv_.push_back(std::make_unique<CsvWriter>());
    PetscCall(OpenSeries(*record_csv_.back(), f.first, f.second));
  }
  if (spec_.energy) {
    std::vector<std::string> columns = {"time"};
    for (const std::string &c : energy_.Columns()) columns.push_back(c);
    energy_every_ = t_final_ / std::max<PetscInt>(out_.samples, 1);
    PetscCall(OpenSeries(energy_csv_, "energy.csv", columns));
    if (!RestartFile().empty()) PetscFunctionReturn(PETSC_SUCCESS); /* continued: energy_next_ and the sums come from the checkpoint */
    energy_next_ = energy_every_;
    const PetscScalar *u;
    const PetscReal   *x, *v;
    PetscCall(VecGetArrayRead(U_, &u));
    PetscCall(LocalState(0, u, u + 2 * n_local_, &x, &v));
    PetscCall(EnergyRow(0, x, v));
    PetscCall(VecRestoreArrayRead(U_, &u));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A stage with non-finite values is rejected, so an adaptive integrator retries with a smaller step. */
PetscErrorCode FineRun::CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept)
{
  return TURGOR_GUARDED({
    PetscReal nrm;
    PetscFunctionBeginUser;
    PetscCall(VecNorm(U, NORM_INFINITY, &nrm));
    *accept = std::isfinite(nrm) ? PETSC_TRUE : PETSC_FALSE;
    PetscFunctionReturn(PETSC_SUCCESS);
  });
}

PetscErrorCode FineRun::Observe(PetscReal t, Vec U, std::vector<PetscReal> &row)
{
  const PetscScalar *u;
  PetscReal          vals[2] = {0, 0}, ke = 0;
  PetscFunctionBeginUser;
  const PetscReal *x, *v;
  PetscCall(VecGetArrayRead(U, &u));
  const PetscInt n2 = 2 * n_local_;
  x = u, v = u + n2; /* the owned particles': the state's own, unless controls impose components */
  if (controls_.Active()) PetscCall(LocalState(t, u, u + n2, &x, &v));
  for (PetscInt i = 0; i < n_local_; i++) ke += 0.5 * tissue_.particles.mass[i] * (v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]);
  if (tip_ >= 0) vals[0] = x[2 * tip_ + 1] - tip_y0_;
  PetscCall(VecRestoreArrayRead(U, &u));
  vals[1] = ke;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, vals, 2, MPIU_REAL, MPIU_SUM, comm_));
  row = {vals[0], vals[1]};
  PetscFunctionReturn(PETSC_SUCCESS);
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
  PetscCall(LocalState(t, u, u + 2 * n_local_, &x, &v));
  model_.SetTime(t);
  PetscCall(TotalForces(x, v, f.data()));
  PetscCall(controls_.Observe(comm_, t, x, f.data(), rows[0]));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::AddSummary(JsonObject &js)
{
  PetscInt nw, nf, nl[2] = {tissue_.particles.Count(KIND_WALL), tissue_.particles.Count(KIND_FLUID)};
  PetscInt nsprings = (PetscInt)tissue_.particles.OwnedSprings(), rebuilds = model_.Neighbours().Rebuilds();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&nl[0], &nw, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(&nl[1], &nf, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nsprings, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &rebuilds, 1, MPIU_INT, MPI_MAX, comm_));
  js.Set("n_wall_particles", nw);
  js.Set("n_fluid_particles", nf);
  js.Set("n_springs", nsprings);
  js.Set("physics", model_.ActiveTerms());
  js.Set("clamp", spec_.clamp);
  js.Set("dt_stable", dt_stable_);
  js.Set("dt_initial", dt_initial_);
  js.Set("neighbour_rebuilds", rebuilds);
  {
    /* a polygonal tissue's sizes: nodes are the wall particles, bars the springs */
    PetscInt  ncells = tissue_.particles.polygons.empty() ? tissue_.NumCells() : (PetscInt)tissue_.particles.OwnedPolygons(), steps;
    PetscReal wall   = WallTime();
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm_));
    PetscCall(TSGetStepNumber(ts_, &steps));
    js.Set("n_nodes", nw);
    js.Set("n_cells", ncells);
    PetscInt nclosed = 0;
    for (size_t c = 0; c < tissue_.particles.OwnedPolygons(); c++) nclosed += !tissue_.particles.polygons[c].open;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nclosed, 1, MPIU_INT, MPI_SUM, comm_));
    if (!tissue_.particles.polygons.empty()) js.Set("n_closed_cells", nclosed);
    js.Set("n_bars", nsprings);
    js.Set("node_steps_per_s", wall > 0 ? (PetscReal)(nw + nf) * steps / wall : 0.0);
    std::vector<PetscReal>   dts;
    std::vector<std::string> why;
    for (const TimeStepLimit &l : limits_) dts.push_back(l.dt), why.push_back(l.why);
    js.Set("stability_limits_dt", dts);
    js.Set("stability_limits", why);
    js.Set("controls", controls_.Names());
  }
  {
    /* the distribution: particles per rank, the halo and what it moves (every Gather and Return,
       outputs included), the full halo checks */
    PetscReal own = (PetscReal)n_local_, mx, sum, halo[3] = {(PetscReal)dist_.NumHalo(), dist_.Bytes(), (PetscReal)dist_.FullChecks()};
    PetscInt  steps;
    PetscCall(TSGetStepNumber(ts_, &steps));
    PetscCallMPI(MPI_Allreduce(&own, &mx, 1, MPIU_REAL, MPIU_MAX, comm_));
    PetscCallMPI(MPI_Allreduce(&own, &sum, 1, MPIU_REAL, MPIU_SUM, comm_));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, halo, 3, MPIU_REAL, MPIU_MAX, comm_));
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    js.Set("distributed", distributed_);
    js.Set("particles_per_rank_max", (PetscInt)mx);
    js.Set("particles_per_rank_mean", sum / size);
    js.Set("load_imbalance", sum > 0 ? mx * size / sum : 1.0);
    js.Set("halo_particles_max", (PetscInt)halo[0]);
    js.Set("halo_bytes_per_step", steps > 0 ? halo[1] / steps : 0.0);
    js.Set("halo_reach", halo_reach_);
    js.Set("halo_margin", halo_margin_);
    js.Set("halo_full_checks", (PetscInt)halo[2]);
  }
  if (spec_.partition > 0) { /* -fine_partition_report (the same numbers on every rank) */
    js.Set("partition_parts", spec_.partition);
    js.Set("partition_edge_cut", (PetscInt)partition_stats_[0]);
    js.Set("partition_edge_cut_length", partition_stats_[1]);
    js.Set("partition_imbalance", partition_stats_[2]);
    js.Set("partition_metis_seconds", partition_stats_[3]);
    js.Set("partition_particles_min", (PetscInt)partition_stats_[4]);
    js.Set("partition_particles_max", (PetscInt)partition_stats_[5]);
  }
  if (spec_.energy) {
    PetscReal worst = energy_.LargestRelativeResidual(), wext = energy_.ExternalWork();
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &wext, 1, MPIU_REAL, MPIU_SUM, comm_));
    js.Set("energy_residual_max", worst);
    js.Set("energy_external_work", wext);
  }
  for (const TermStatistic &s : model_.Statistics()) { /* the terms' counters (contacts, plastic dissipation) */
    PetscReal v = s.value;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPIU_REAL, s.reduction == TermStatistic::MAX ? MPIU_MAX : MPIU_SUM, comm_));
    js.Set(s.name, v);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FineRun::DoneDetails(std::string *details)
{
  PetscFunctionBeginUser;
  *details = std::to_string(rhs_evals_) + " RHS evaluations";
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---- checkpoints ---- */

PetscErrorCode FineRun::CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp)
{
  PetscInt n = n_local_, ncells = tissue_.particles.polygons.empty() ? tissue_.NumCells() : (PetscInt)tissue_.particles.OwnedPolygons();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ncells, 1, MPIU_INT, MPI_SUM, comm_));
  /* what the options do not show (a node file's contents, the generators' arithmetic); the physics
     parameters are compared one by one besides */
  fp.push_back({"particles", std::to_string((long long)n)});
  fp.push_back({"cells", std::to_string((long long)ncells)});
  fp.push_back({"energy", spec_.energy ? "on" : "off"});
  fp.push_back({"reference_positions_hash", reference_hash_});
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Declared state: the velocities of the split integrators' last drift, the energy balance's next
   row, the model's (neighbour lists, terms) and the energy balance's. */
PetscErrorCode FineRun::DeclareState(std::deque<StateDeclaration> &decls)
{
  PetscFunctionBeginUser;
  numbering_ = std::make_unique<LocalNumbering>(tissue_.particles);
  decls.emplace_back("fine");
  StateDeclaration &d = decls.back();
  if (spec_.energy) d.Scalar("next_energy_row", &energy_next_, Combine::Owner);
  if (split_) d.Table("particles", StateEntity::Particle).Rows([this] { return (size_t)n_local_; }).Column("drift_velocity", v_stale_, 2);
  model_.DeclareState(decls);
  if (spec_.energy) {
    decls.emplace_back("energy");
    energy_.DeclareState(decls.back());
  }
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
  if (!numbering_) return -1;
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
  PetscCall(LocalState(t, u, u + 2 * n_local_, &x, &v));
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
  PetscInt              n = n_local_, N;
  std::vector<PetscInt> idx(4 * n);
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(&n, &N, 1, MPIU_INT, MPI_SUM, comm_));
  for (PetscInt l = 0; l < n; l++) /* [x | v], each in the tissue's particle order */
    for (PetscInt d = 0; d < 2; d++) {
      idx[2 * l + d]         = 2 * tissue_.particles.gid[l] + d;
      idx[2 * n + 2 * l + d] = 2 * N + 2 * tissue_.particles.gid[l] + d;
    }
  PetscCall(ISCreateGeneral(comm_, 4 * n, idx.data(), PETSC_COPY_VALUES, order));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
