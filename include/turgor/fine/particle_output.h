#pragma once
/* What the fine modes (-mode fine, -mode fine_static) write of their particles besides positions:
   the DMSwarm record the snapshots name them by, and the force terms' own snapshot fields. */
#include <turgor/io/particle_snapshots.h>
#include <turgor/physics/force_model.h>
#include <petscdm.h>

namespace turgor {

/* The DMSwarm of this rank's first n_local particles of P: their ids (DMSwarm_pid), kinds and cells.
   Not their positions and velocities: those live once, in the solver's state. */
PetscErrorCode CreateParticleSwarm(MPI_Comm comm, const ParticleSet &P, PetscInt n_local, DM *swarm);
/* The terms' fields at (x, v) for a snapshot: per bar and per closed cell (the cell fields left out
   where the writer draws no cells grid), and their segments (the glue bonds), appended to *fields. */
PetscErrorCode AddTermSnapshotFields(ForceModel &model, const ParticleSet &P, const ParticleSnapshotWriter &writer, const PetscReal *x, const PetscReal *v,
                                     ParticleSnapshotWriter::Fields *fields);

} // namespace turgor
