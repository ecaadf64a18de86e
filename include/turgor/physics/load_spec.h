#pragma once
/* External loads of a scene, read once (prefix body_): the fine body-force term and the coarse
   model both take them from here. */
#include <turgor/core/parameters.h>
#include <turgor/core/registry.h>

namespace turgor {

struct LoadSpec {
  PetscReal body_acceleration[2] = {0.0, -0.2}; /* g [µm/µs^2], the seed's 0.2 downward */

  /* -body_force gx,gy */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
};

} // namespace turgor
