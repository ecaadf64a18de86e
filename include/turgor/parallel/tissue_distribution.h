#pragma once
/* Distributed fine runs: the cells of a tissue dealt to the ranks (a METIS partition,
   cell_partition.h), every particle on the rank that owns its cell. A Lagrangian decomposition:
   particles move with their cell and never migrate.

   - Owned: the particles whose cell (OwnerCells) this rank owns; particles in no cell belong to
     rank 0. They come first in the local numbering, in global order, and are this rank's block of
     the distributed state.
   - Halo: the wall particles (walls, nodes; never fluid, which only meets its own cell) of every
     cell of another rank whose bounding box lies within reach + margin of one of this rank's cells,
     reach being the farthest a particle's interactions go into another cell (ForceTerm::Reach plus
     the neighbour skin). Whole cells, so that a halo polygon is complete, and the cells that share
     a wall particle with this rank's cells (distance 0).
   - Every interaction is computed once, by the rank owning its anchor (particles.h); the forces on
     halo particles are returned to their owners (Return) and summed there.

   The halo is fixed at set-up; Check() keeps it honest as cells move: once an edge of some cell's
   box (of its ring and fluid) has moved half the smallest slack (the distance, beyond the reach,
   from a rank's cells to the nearest cell outside its halo) over sqrt 2 since the last full check,
   the cells' current boxes are sent to the ranks near them (whose region, the box of their cells
   grown by reach + margin, they meet: 4 numbers a rank are gathered, the cells' boxes go to their
   neighbours only) and each rank's halo must still hold every cell within reach, else the run
   stops with an error naming -fine_halo_margin. Between full checks that costs one pass over the
   boxes and one reduction of a number per evaluation.

   The exchange pattern is one PetscSF over the halo particles' two components (roots: the owned
   particles' components on their owner; leaves: the halo slots), used for positions and velocities
   (broadcast) and for forces (reduction by sum). */
#include <turgor/tissue/tissue.h>
#include <petscsf.h>
#include <vector>

namespace turgor {

class TissueDistribution {
public:
  ~TissueDistribution();
  /* Collective. Every rank holds the whole tissue `global`, or a part of it (Tissue::cell_gid) that
     holds every cell within reach + margin of this rank's cells, with all the springs of their
     particles (TissueGenerator::GeneratePart); cell_rank[c] is the rank that owns cell c
     (Tissue::cell_walls order). Builds this rank's tissue `local` (owned particles, then the halo;
     ParticleSet's owned counts and halo indices) and the exchange pattern; local_of[g] is the local
     index of global particle g, -1 where this rank has no copy (for the set-up's own maps: it is
     not kept, a rank holding N entries would not scale). A periodic tissue is refused. */
  PetscErrorCode SetUp(MPI_Comm comm, const Tissue &global, const std::vector<PetscInt> &cell_rank, PetscReal reach, PetscReal margin, Tissue *local,
                       std::vector<PetscInt> *local_of);
  MPI_Comm       Comm() const { return comm_; }

  /* Each array a[2n] (n local particles: a field of two components per particle): fill the halo
     part a[2 n_owned ...] from the owners' owned parts (all in flight at once: one latency). */
  PetscErrorCode Gather(const std::vector<PetscReal *> &arrays) const;
  /* f[2n]: add the halo part to the owners' owned parts (on their ranks); the halo part is left. */
  PetscErrorCode Return(PetscReal *f) const;
  /* Collective: is the halo still enough at these local positions x[2n]? (see above) */
  PetscErrorCode Check(const PetscReal *x);

  PetscInt  NumOwned() const { return n_owned_; }
  PetscInt  NumHalo() const { return n_halo_; }
  PetscInt  Start() const { return start_; }                 /* this rank's first particle in the distributed state */
  PetscInt  NumLocalCells() const { return n_local_cells_; } /* owned + halo cells */
  PetscInt  NumOwnedCells() const { return (PetscInt)owned_cells_.size(); }
  PetscInt  FullChecks() const { return full_checks_; }
  PetscReal Bytes() const { return bytes_; }            /* received by Gather and sent by Return so far */
  PetscReal CheckBytes() const { return check_bytes_; } /* received by the full checks so far (this rank) */
  PetscReal Slack() const { return slack_; }

private:
  MPI_Comm               comm_    = MPI_COMM_NULL;
  PetscSF                sf_      = nullptr;
  PetscInt               n_owned_ = 0, n_halo_ = 0, start_ = 0, n_cells_ = 0, n_local_cells_ = 0, full_checks_ = 0;
  std::vector<PetscInt>  owned_cells_; /* global ids of this rank's cells */
  std::vector<PetscInt>  ring_start_;  /* [owned cells + 1] into ring_: */
  std::vector<PetscInt>  ring_;        /* their particles: rings and fluid (local indices) */
  std::vector<PetscInt>  local_cells_; /* global ids of the cells here (owned, halo), increasing */
  PetscReal              reach_ = 0, margin_ = 0, slack_ = 0;
  std::vector<PetscReal> box_check_;       /* this rank's cells' boxes at the last full check */
  bool                   checked_ = false; /* a full check was made (the same on every rank: a rank may own no cell) */
  std::vector<PetscReal> box_now_;         /* ... and now (Check's work array, kept: it runs every evaluation) */
  mutable PetscReal      bytes_       = 0;
  PetscReal              check_bytes_ = 0;
  MPI_Comm               comm_tag_    = MPI_COMM_NULL; /* PetscCommDuplicate's inner communicator of comm_, and the checks' tag */
  PetscMPIInt            tag_         = 0;
  PetscLogEvent          ev_exchange_ = 0, ev_check_ = 0; /* TgHaloExchange (Gather, Return), TgHaloCheck */
};

} // namespace turgor
