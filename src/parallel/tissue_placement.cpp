#include <turgor/parallel/rank_reductions.h>
#include <turgor/parallel/tissue_placement.h>
#include <algorithm>
#include <cstdint>

namespace turgor {

/* The METIS partition of the whole tissue on rank 0 (every rank holds the tissue here), its
   statistics broadcast to every rank. */
PetscErrorCode TissuePlacement::PartitionReport(MPI_Comm comm, const Tissue &tissue)
{
  const char *option = "-fine_partition_report";
  PetscMPIInt rank;
  PetscInt    ncells = tissue.particles.polygons.empty() ? tissue.NumCells() : (PetscInt)tissue.particles.OwnedPolygons();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&ncells, 1, MPIU_INT, 0, comm));
  PetscCheck(options_.report_parts <= ncells, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option %s = %" PetscInt_FMT ": more parts than the tissue's %" PetscInt_FMT " cells", option, options_.report_parts, ncells);
  PetscErrorCode failed = PETSC_SUCCESS; /* a failure on rank 0 ends every rank */
  PetscReal     *stats  = partition_stats_;
  if (rank == 0) {
    CellGraph graph;
    failed = BuildCellGraph(PETSC_COMM_SELF, tissue, &graph);
    if (!failed) failed = PartitionCells(PETSC_COMM_SELF, graph, options_.report_parts, MetisOptions(), option, &partition_);
    if (!failed) {
      std::vector<PetscInt> part;
      ParticleParts(tissue, partition_, &part);
      particle_part_.assign(part.begin(), part.end());
      stats[0] = (PetscReal)partition_.edge_cut;
      stats[1] = partition_.edge_cut_length;
      stats[2] = partition_.imbalance;
      stats[3] = partition_.metis_seconds;
      stats[4] = (PetscReal)*std::min_element(partition_.part_particles.begin(), partition_.part_particles.end());
      stats[5] = (PetscReal)*std::max_element(partition_.part_particles.begin(), partition_.part_particles.end());
    }
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm));
  PetscCheck(!failed, comm, PETSC_ERR_LIB, "Option %s = %" PetscInt_FMT ": the cell partition failed on rank 0", option, options_.report_parts);
  PetscCallMPI(MPI_Bcast(stats, 6, MPIU_REAL, 0, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The cells partitioned on rank 0 (METIS, weighted as in cell_partition.h) or by ranges; each rank
   keeps its cells' particles and its halo (tissue_distribution.h). */
PetscErrorCode TissuePlacement::Distribute(MPI_Comm comm, Tissue *tissue, std::vector<PetscInt> *local_of)
{
  const char *option = "-fine_distribute";
  PetscMPIInt size, rank;
  PetscInt    ncells = tissue->NumCells();
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<PetscInt> cell_rank(ncells, 0);
  PetscErrorCode        failed = PETSC_SUCCESS;
  if (options_.ranges)
    for (PetscInt c = 0; c < ncells; c++) cell_rank[c] = RangeRank(order_ ? order_->CellPlace(c) : c, ncells, size);
  else if (rank == 0 && ncells < size) /* fewer cells than ranks: one cell a rank, the last ranks hold none (an empty rank is a valid rank) */
    for (PetscInt c = 0; c < ncells; c++) cell_rank[c] = c;
  else if (rank == 0) {
    CellGraph     graph;
    CellPartition part;
    failed = BuildCellGraph(PETSC_COMM_SELF, *tissue, &graph);
    if (!failed) failed = PartitionCells(PETSC_COMM_SELF, graph, size, MetisOptions(), option, &part);
    if (!failed) cell_rank = part.part;
  }
  PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, comm));
  PetscCheck(!failed, comm, PETSC_ERR_LIB, "Option %s: the cell partition failed on rank 0", option);
  PetscCallMPI(MPI_Bcast(cell_rank.data(), (PetscMPIInt)ncells, MPIU_INT, 0, comm));
  Tissue local;
  PetscCall(dist_.SetUp(comm, *tissue, cell_rank, reach_, margin_, &local, local_of));
  if (options_.report_parts > 0) { /* the report's part of every owned particle (rank 0 computed them) */
    std::vector<PetscReal> all(tissue->particles.n);
    if (rank == 0) all = particle_part_;
    PetscCallMPI(MPI_Bcast(all.data(), (PetscMPIInt)all.size(), MPIU_REAL, 0, comm));
    particle_part_.resize(dist_.NumOwned());
    for (PetscInt l = 0; l < dist_.NumOwned(); l++) particle_part_[l] = all[local.particles.gid[l]];
  }
  *tissue = std::move(local);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissuePlacement::Place(MPI_Comm comm, const Options &options, PetscReal reach, Tissue *tissue, std::vector<PetscInt> *local_of,
                                      const TissueGenerator *order)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  options_     = options;
  order_       = order;
  distributed_ = size > 1 && options.distribute;
  reach_       = distributed_ ? reach : 0;
  margin_      = !distributed_ ? 0 : options.halo_margin >= 0 ? options.halo_margin : reach;
  local_of->clear();
  if (options.report_parts > 0) PetscCall(PartitionReport(comm, *tissue));
  if (distributed_) PetscCall(Distribute(comm, tissue, local_of));
  else if (rank != 0) *tissue = Tissue(); /* -fine_distribute 0: rank 0 holds the whole tissue, the other ranks none */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissuePlacement::OwnedRange(MPI_Comm comm, PetscInt C, PetscInt *c0, PetscInt *c1)
{
  PetscMPIInt size, rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *c0 = (PetscInt)((long long)rank * C / size);
  *c1 = (PetscInt)((long long)(rank + 1) * C / size);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissuePlacement::PlaceParts(MPI_Comm comm, const Options &options, PetscReal reach, const TissueGenerator &generator, Tissue *tissue)
{
  PetscMPIInt    size;
  const PetscInt C = generator.NumCellsOfParts();
  PetscInt       c0, c1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCheck(options.ranges && options.distribute && options.report_parts == 0 && size > 1 && C >= 0, comm, PETSC_ERR_PLIB,
             "a tissue is built in parts only by cell ranges, on several ranks, without a partition report, by a generator that can");
  options_     = options;
  distributed_ = true;
  parts_       = true;
  reach_       = reach;
  margin_      = options.halo_margin >= 0 ? options.halo_margin : reach;
  PetscCall(OwnedRange(comm, C, &c0, &c1));
  Tissue part;
  PetscCall(AgreeOnError(comm, generator.GeneratePart(comm, c0, c1, reach_ + margin_, &part), "generating a part of the tissue"));
  std::vector<PetscInt> cell_rank(part.NumCells()), local_of;
  for (PetscInt c = 0; c < part.NumCells(); c++) cell_rank[c] = RangeRank(generator.CellPlace(part.CellGid(c)), C, size);
  PetscCall(dist_.SetUp(comm, part, cell_rank, reach_, margin_, tissue, &local_of));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissuePlacement::View(MPI_Comm comm, PetscInt n_owned) const
{
  PetscFunctionBeginUser;
  if (distributed_) {
    PetscReal   r[3] = {(PetscReal)n_owned, -(PetscReal)n_owned, (PetscReal)dist_.NumHalo()};
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCall(MaxOverRanks(comm, r, 3));
    PetscCall(PetscPrintf(comm,
                          "Distributed over %d ranks (%s, -fine_distribute): %.0f..%.0f particles per rank, halo up to %.0f particles "
                          "(cells within %.4g µm reach + %.4g µm -fine_halo_margin); the terms' lines above count rank 0's particles\n",
                          size,
                          !options_.ranges ? "METIS cells"
                          : parts_         ? "cell ranges, each rank built its own part of the tissue"
                                           : "cell ranges",
                          -(double)r[1], (double)r[0], (double)r[2], (double)reach_, (double)margin_));
  }
  if (options_.report_parts > 0)
    PetscCall(PetscPrintf(comm,
                          "Cell partition (METIS, -fine_partition_report; a report): %" PetscInt_FMT
                          " parts, edge cut %.0f walls (%.4g µm), particles per part %.0f..%.0f, imbalance %.4f, METIS %.3g s\n",
                          options_.report_parts, (double)partition_stats_[0], (double)partition_stats_[1], (double)partition_stats_[4],
                          (double)partition_stats_[5], (double)partition_stats_[2], (double)partition_stats_[3]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The distribution: particles per rank, the halo and what it moves (every Gather and Return,
   outputs included), the full halo checks and what they received; the partition report's figures. */
PetscErrorCode TissuePlacement::AddSummary(MPI_Comm comm, JsonObject &js, PetscInt n_owned, PetscInt steps) const
{
  PetscReal mx = (PetscReal)n_owned, sum = (PetscReal)n_owned,
            halo[4] = {(PetscReal)dist_.NumHalo(), dist_.Bytes(), (PetscReal)dist_.FullChecks(), dist_.CheckBytes()};
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MaxOverRanks(comm, &mx));
  PetscCall(SumOverRanks(comm, &sum));
  PetscCall(MaxOverRanks(comm, halo, 4));
  js.Set("distributed", distributed_);
  js.Set("partitioner", options_.ranges ? "ranges" : "metis");
  js.Set("setup_in_parts", parts_); /* no rank held the whole tissue */
  js.Set("particles_per_rank_max", (PetscInt)mx);
  js.Set("particles_per_rank_mean", sum / size);
  js.Set("load_imbalance", sum > 0 ? mx * size / sum : 1.0);
  js.Set("halo_particles_max", (PetscInt)halo[0]);
  js.Set("halo_bytes_per_step", steps > 0 ? halo[1] / steps : 0.0);
  js.Set("halo_reach", reach_);
  js.Set("halo_margin", margin_);
  js.Set("halo_full_checks", (PetscInt)halo[2]);
  js.Set("halo_check_bytes", halo[3]); /* received by one rank's full checks, the most of any rank */
  if (options_.report_parts > 0) {     /* the same numbers on every rank */
    js.Set("partition_parts", options_.report_parts);
    js.Set("partition_edge_cut", (PetscInt)partition_stats_[0]);
    js.Set("partition_edge_cut_length", partition_stats_[1]);
    js.Set("partition_imbalance", partition_stats_[2]);
    js.Set("partition_metis_seconds", partition_stats_[3]);
    js.Set("partition_particles_min", (PetscInt)partition_stats_[4]);
    js.Set("partition_particles_max", (PetscInt)partition_stats_[5]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TissueReferenceHash(MPI_Comm comm, const Tissue &tissue, std::string *hex)
{
  const ParticleSet &P   = tissue.particles;
  std::uint64_t      sum = 0;
  char               buf[24];
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < P.NumOwned(); i++) {
    std::uint64_t hash = 1469598103934665603ull;
    auto          add  = [&hash](const void *p, size_t bytes) {
      const unsigned char *b = (const unsigned char *)p;
      for (size_t k = 0; k < bytes; k++) hash = (hash ^ b[k]) * 1099511628211ull;
    };
    const long long gid = P.gid.empty() ? i : P.gid[i]; /* the same width on every build */
    add(&gid, sizeof gid);
    add(&tissue.X[2 * i], 2 * sizeof(PetscReal));
    add(&P.mass[i], sizeof(PetscReal));
    sum += hash;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_UINT64_T, MPI_SUM, comm));
  PetscCall(PetscSNPrintf(buf, sizeof buf, "%016llx", (unsigned long long)sum));
  *hex = buf;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ClosestOwnedWallParticle(MPI_Comm comm, const Tissue &tissue, PetscReal px, PetscReal py, PetscInt *local)
{
  const ParticleSet &P    = tissue.particles;
  PetscReal          best = PETSC_MAX_REAL;
  PetscInt           gid  = PETSC_MAX_INT;
  PetscFunctionBeginUser;
  *local = -1;
  for (PetscInt i = 0; i < P.NumOwned(); i++) {
    if (P.kind[i] != KIND_WALL) continue;
    const PetscReal dx = tissue.X[2 * i] - px, dy = tissue.X[2 * i + 1] - py, r2 = dx * dx + dy * dy;
    if (r2 < best) best = r2, *local = i;
  }
  PetscReal mine = best;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &best, 1, MPIU_REAL, MPIU_MIN, comm));
  if (*local >= 0 && mine == best) gid = P.gid.empty() ? *local : P.gid[*local]; /* the first owned one at that distance: global order */
  PetscInt min_gid = gid;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &min_gid, 1, MPIU_INT, MPI_MIN, comm));
  if (gid != min_gid) *local = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
