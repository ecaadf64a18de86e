#pragma once
/* METIS 5's k-way graph partitioner (METIS_PartGraphKway, libmetis from Debian's libmetis-dev)
   behind PETSc's error handling, shared by the fine tissue's cell partition (cell_partition.h) and
   the FE^2 coarse mesh (-coarse_partitioner metis). Serial: it partitions a whole graph held by the
   calling rank (Debian's PETSc has no ParMETIS). */
#include <turgor/core/petsc_compat.h>
#include <vector>

namespace turgor {

/* A graph in CSR form, 0-based, symmetric, without self loops: the neighbours of vertex v are
   adjncy[xadj[v] .. xadj[v + 1]). Empty weight arrays mean weight 1 everywhere; weights must be
   >= 0 (vertices) and >= 1 (edges). */
struct CSRGraph {
  std::vector<PetscInt> xadj = {0}, adjncy, vwgt, adjwgt;

  PetscInt NumVertices() const { return (PetscInt)xadj.size() - 1; }
};

struct MetisOptions {
  PetscInt seed       = 0;    /* METIS_OPTION_SEED: the same graph and seed give the same parts */
  bool     contiguous = true; /* METIS_OPTION_CONTIG: each part one connected piece (when the graph is connected) */
  /* METIS_OPTION_NCUTS: partitionings tried, the smallest cut kept. 16, not METIS's 1: a 64 x 64 grid
     on 4 parts cut 1.05-1.23 times the 128 walls of a 2 x 2 split with one try over 20 seeds, and
     1.02-1.09 times with 16 (docs/scaling.md), for 16 times the METIS time (50 ms there) */
  PetscInt ncuts = 16;
};

/* part[v] in [0, nparts) for every vertex. nparts == 1: all 0 and METIS is not called. nparts < 1,
   nparts > the number of vertices or a METIS failure: an error naming `option` and the value.
   *objval (optional): METIS's weighted edge cut (0 for one part); *seconds (optional): the time
   spent in METIS. Not collective: `comm` is the communicator errors are raised on. */
PetscErrorCode MetisPartGraphKway(MPI_Comm comm, const CSRGraph &graph, PetscInt nparts, const MetisOptions &options, const char *option,
                                  std::vector<PetscInt> *part, PetscInt *objval = nullptr, PetscReal *seconds = nullptr);

} // namespace turgor
