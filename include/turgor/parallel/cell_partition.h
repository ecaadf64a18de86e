#pragma once
/* The cells of a tissue partitioned into parts with METIS (metis_partition.h): the preparation of
   distributed fine runs, in which every particle will live on the rank that owns its cell. Today
   the partition is only computed and reported (-fine_partition_report N); the particles still live
   on rank 0.

   The cell graph: one vertex per cell, weighted by the particles the cell owns; an edge between
   neighbouring cells, weighted by the length of wall they share.
   - Square grid (cells share wall particles): two cells are neighbours when their wall rings share
     a wall segment (two consecutive ring points); the shared length is the sum of those segments.
     These are the grid's 4 neighbours (cells meeting at a corner share no wall).
   - Polygonal tissues (ParticleSet::polygons; each cell has its own nodes, neighbours 2 r apart):
     two cells are neighbours when a bar of one lies within 3 r (r = the bar radius: contact at 2 r,
     and half a radius of slack) of a bar of the other; the shared length is the length of bar within
     that distance (each bar sampled at 4 points), averaged over the two sides.
   A particle is owned by its cell: a fluid particle by ParticleSet::cell, a polygon node by
   ParticleSet::node_polygon, a square-grid wall particle (shared by up to four cells) by the lowest
   numbered cell whose ring holds it; particles in no cell are counted as unowned. */
#include <turgor/parallel/metis_partition.h>
#include <turgor/tissue/tissue.h>

namespace turgor {

struct CellGraph {
  CSRGraph               graph;           /* vwgt: particles owned (at least 1, METIS's balance), adjwgt: wall length / length_unit (at least 1) */
  std::vector<PetscReal> wall_length;     /* [adjncy] shared wall length of each edge, µm */
  std::vector<PetscInt>  particles;       /* [cells] particles owned by each cell */
  PetscInt               unowned     = 0; /* particles in no cell */
  PetscReal              length_unit = 1; /* µm per unit of adjwgt: the mean shared length / 100 */

  PetscInt NumCells() const { return graph.NumVertices(); }
};

/* The cell graph of the tissue (cells as in Tissue::cell_walls, or ParticleSet::polygons for a
   polygonal tissue). Not collective. */
PetscErrorCode BuildCellGraph(MPI_Comm comm, const Tissue &tissue, CellGraph *graph);

struct CellPartition {
  PetscInt              nparts = 0;
  std::vector<PetscInt> part;                /* [cells] part of each cell */
  PetscInt              edge_cut        = 0; /* neighbouring cell pairs in different parts */
  PetscReal             edge_cut_length = 0; /* their shared wall length, µm */
  PetscInt              metis_objval    = 0; /* METIS's weighted cut (units of CellGraph::length_unit) */
  std::vector<PetscInt> part_particles;      /* [nparts] particles owned by the cells of each part */
  PetscReal             imbalance     = 1;   /* max / mean of part_particles */
  PetscReal             metis_seconds = 0;   /* time in METIS_PartGraphKway */
};

/* Partition the cells into nparts parts (METIS k-way with `options`: by default contiguous parts
   where the graph is connected, seed 0, one cut) and fill in the statistics. nparts == 1: one part, no METIS
   call. nparts < 1 or more parts than cells: an error naming `option` and the value. Not
   collective. */
PetscErrorCode PartitionCells(MPI_Comm comm, const CellGraph &graph, PetscInt nparts, const MetisOptions &options, const char *option,
                              CellPartition *partition);

/* The statistics of partition->part (nparts, part set): edge cut, cut length, particles per part,
   imbalance. */
void PartitionStatistics(const CellGraph &graph, CellPartition *partition);

/* The cell that owns every particle (the rule above; a part of a tissue: its own cells' indices; -1: a
   particle in no cell). */
void OwnerCells(const Tissue &tissue, std::vector<PetscInt> *owner);

/* The part of every particle (the part of the cell that owns it; -1 for an unowned particle), for
   output. */
void ParticleParts(const Tissue &tissue, const CellPartition &partition, std::vector<PetscInt> *part);

} // namespace turgor
