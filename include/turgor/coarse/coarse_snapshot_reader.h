#pragma once
/* A state of the coarse model read back from a snapshot file written by CoarseFieldsWriter
   (coarse.h5 of -mode fe2 or fe2_static): the displacement of the snapshot at a given time. Its
   vertices are matched to the model's by their reference coordinates (to 1e-9 of the mesh size),
   so a file written on another number of ranks (another vertex numbering) is read the same; the
   velocity is not read (U gets v = 0). A file that is missing, not such a file, of another mesh,
   without a snapshot at the time, or with non-finite displacements is refused, naming the option
   and the value. */
#include <turgor/coarse/coarse_model.h>
#include <string>

namespace turgor {

struct CoarseSnapshotRequest {
  std::string path; /* the .h5 file */
  bool        has_time    = false;
  PetscReal   time        = 0; /* the snapshot's time attribute (to 1e-6 of the largest time); the last one without has_time */
  const char *file_option = "-snapshot_file", *time_option = "-snapshot_time"; /* for messages */
};

/* U: a global vector of the model; *time_found the snapshot's time. Collective. */
PetscErrorCode ReadCoarseSnapshot(CoarseModel &model, const CoarseSnapshotRequest &req, Vec U, PetscReal *time_found);

} // namespace turgor
