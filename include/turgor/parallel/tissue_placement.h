#pragma once
/* Where the particles of a fine run live. On one rank, or with -fine_distribute 0, the first rank
   holds the whole tissue (the others none: an empty rank takes part in every collective call); on
   several ranks with -fine_distribute (the default) the cells are dealt to the ranks and every
   particle lives on the rank of its cell, with a halo of the neighbouring ranks' particles
   (tissue_distribution.h). -fine_partitioner picks how the cells are dealt:
   - metis (the default): a METIS partition of the cell graph, made on the first rank, which needs
     the whole tissue on every rank at set-up;
   - ranges: each rank the cells of one range of the generator's space order, as many as the next
     rank (the cell at place c on rank floor((c P + P - 1) / C); TissueGenerator::CellPlace: the
     square grid's row-major numbering, the Hilbert curve through a Voronoi tissue's seeds). A
     generator that can build a part of its tissue (TissueGenerator::GeneratePart: square grid,
     Voronoi) then builds on each rank only its cells and those within the halo's width
     (PlaceParts): no rank holds the whole tissue at any time. Ranges of a row-major grid are strips:
     their halo is wider than METIS's blocks' on many ranks.
   -fine_partition_report N partitions the cells into N parts as a report only (summary.json, and
   each particle's part in the snapshots). */
#include <turgor/io/output.h>
#include <turgor/parallel/cell_partition.h>
#include <turgor/parallel/tissue_distribution.h>
#include <turgor/tissue/tissue_generator.h>

namespace turgor {

class TissuePlacement {
public:
  struct Options {
    bool      distribute   = true;  /* -fine_distribute */
    PetscInt  report_parts = 0;     /* -fine_partition_report: 0 none */
    PetscReal halo_margin  = -1;    /* -fine_halo_margin [µm]; < 0: the reach */
    bool      ranges       = false; /* -fine_partitioner ranges (else metis) */
  };
  /* The cell ranges' rank of cell c of C on P ranks. */
  static PetscMPIInt RangeRank(PetscInt c, PetscInt C, PetscMPIInt P) { return (PetscMPIInt)(((long long)c * P + P - 1) / C); }
  /* Collective; every rank holds the whole tissue. Keeps this rank's part of it (owned particles
     first, then the halo's), the halo's width `reach` (the interactions' reach with the neighbour
     skin, µm) plus the margin. local_of[g]: the local index of global particle g, -1 where this
     rank has none (empty where the tissue is not distributed). `order`: the generator whose space
     order the ranges follow (TissueGenerator::CellPlace, after PrepareParts; null: the cells'
     numbers). */
  PetscErrorCode Place(MPI_Comm comm, const Options &options, PetscReal reach, Tissue *tissue, std::vector<PetscInt> *local_of,
                       const TissueGenerator *order = nullptr);
  /* Collective; a distributed run with -fine_partitioner ranges of a generator that builds parts
     (NumCellsOfParts() >= 0): each rank generates its cells and those within reach + margin and
     keeps its part as Place does. */
  PetscErrorCode PlaceParts(MPI_Comm comm, const Options &options, PetscReal reach, const TissueGenerator &generator, Tissue *tissue);
  /* The places [c0, c1) of the space order (TissueGenerator::CellPlace) whose cells this rank owns
     under the ranges (of the generator's C cells). */
  static PetscErrorCode OwnedRange(MPI_Comm comm, PetscInt C, PetscInt *c0, PetscInt *c1);
  bool                  Distributed() const { return distributed_; }
  TissueDistribution   *Halo() { return distributed_ ? &dist_ : nullptr; }
  /* -fine_partition_report: the part of each owned particle's cell (empty without the report). */
  const std::vector<PetscReal> &ReportParts() const { return particle_part_; }
  /* The start-up report's lines, and the summary's keys (collective). */
  PetscErrorCode View(MPI_Comm comm, PetscInt n_owned) const;
  PetscErrorCode AddSummary(MPI_Comm comm, JsonObject &js, PetscInt n_owned, PetscInt steps) const;

private:
  PetscErrorCode PartitionReport(MPI_Comm comm, const Tissue &tissue);
  PetscErrorCode Distribute(MPI_Comm comm, Tissue *tissue, std::vector<PetscInt> *local_of);

  Options                options_;
  bool                   distributed_ = false, parts_ = false;
  const TissueGenerator *order_ = nullptr; /* Place's: whose space order the ranges follow */
  TissueDistribution     dist_;
  PetscReal              reach_ = 0, margin_ = 0;
  CellPartition          partition_;
  std::vector<PetscReal> particle_part_;
  /* the report's edge cut (walls), its length (µm), the imbalance, METIS's time (s), the smallest
     and largest part (particles), on every rank */
  PetscReal partition_stats_[6] = {0, 0, 0, 0, 0, 0};
};

/* Collective; every rank holds its placed tissue (owned particles first). The reference positions
   and masses of the whole tissue hashed, whatever the ranks: each owned particle's global id,
   position and mass hashed (FNV-1a), the hashes summed over the particles and the ranks modulo
   2^64 (the same bits everywhere): a checkpoint's fingerprint of a scene's geometry. */
PetscErrorCode TissueReferenceHash(MPI_Comm comm, const Tissue &tissue, std::string *hex);
/* Collective: the owned wall particle closest to (px, py), the lowest global id among equals (the
   same particle on any number of ranks): its local index on its owner, -1 on the other ranks. */
PetscErrorCode ClosestOwnedWallParticle(MPI_Comm comm, const Tissue &tissue, PetscReal px, PetscReal py, PetscInt *local);

} // namespace turgor
