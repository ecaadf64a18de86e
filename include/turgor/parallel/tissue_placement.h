#pragma once
/* Where the particles of a fine run live. On one rank, or with -fine_distribute 0, the first rank
   holds the whole tissue (the others none: an empty rank takes part in every collective call); on
   several ranks with -fine_distribute (the default) the cells are partitioned with METIS on the
   first rank and every particle lives on the rank of its cell, with a halo of the neighbouring
   ranks' particles (tissue_distribution.h). -fine_partition_report N partitions the cells into N
   parts as a report only (summary.json, and each particle's part in the snapshots). */
#include <turgor/io/output.h>
#include <turgor/parallel/cell_partition.h>
#include <turgor/parallel/tissue_distribution.h>

namespace turgor {

class TissuePlacement {
public:
  struct Options {
    bool      distribute   = true; /* -fine_distribute */
    PetscInt  report_parts = 0;    /* -fine_partition_report: 0 none */
    PetscReal halo_margin  = -1;   /* -fine_halo_margin [µm]; < 0: the reach */
  };
  /* Collective; every rank holds the whole tissue. Keeps this rank's part of it (owned particles
     first, then the halo's), the halo's width `reach` (the interactions' reach with the neighbour
     skin, µm) plus the margin. local_of[g]: the local index of global particle g, -1 where this
     rank has none (empty where the tissue is not distributed). */
  PetscErrorCode Place(MPI_Comm comm, const Options &options, PetscReal reach, Tissue *tissue, std::vector<PetscInt> *local_of);

  bool                Distributed() const { return distributed_; }
  TissueDistribution *Halo() { return distributed_ ? &dist_ : nullptr; }
  /* -fine_partition_report: the part of each owned particle's cell (empty without the report). */
  const std::vector<PetscReal> &ReportParts() const { return particle_part_; }
  /* The start-up report's lines, and the summary's keys (collective). */
  PetscErrorCode View(MPI_Comm comm, PetscInt n_owned) const;
  PetscErrorCode AddSummary(MPI_Comm comm, JsonObject &js, PetscInt n_owned, PetscInt steps) const;

private:
  PetscErrorCode PartitionReport(MPI_Comm comm, const Tissue &tissue);
  PetscErrorCode Distribute(MPI_Comm comm, Tissue *tissue, std::vector<PetscInt> *local_of);

  Options                options_;
  bool                   distributed_ = false;
  TissueDistribution     dist_;
  PetscReal              reach_ = 0, margin_ = 0;
  CellPartition          partition_;
  std::vector<PetscReal> particle_part_;
  /* the report's edge cut (walls), its length (µm), the imbalance, METIS's time (s), the smallest
     and largest part (particles), on every rank */
  PetscReal partition_stats_[6] = {0, 0, 0, 0, 0, 0};
};

/* The reference positions and masses of the whole tissue, hashed (FNV-1a) on the first rank and
   broadcast (the same bits everywhere): a checkpoint's fingerprint of a scene's geometry. */
PetscErrorCode TissueReferenceHash(MPI_Comm comm, const Tissue &tissue, std::string *hex);

} // namespace turgor
