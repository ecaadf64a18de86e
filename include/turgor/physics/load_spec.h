#pragma once
/* External loads of a scene, read once (prefix body_): the fine body-force term and the coarse
   model both take them from here. */
#include <turgor/core/parameters.h>
#include <turgor/core/registry.h>

namespace turgor {

struct LoadSpec {
  PetscReal body_acceleration[2] = {0.0, -0.2}; /* g [µm/µs^2], the seed's 0.2 downward */
  /* its schedule in a fine run: nothing before the delay, then linear over the ramp time (a load
     that arrives at once shakes a tissue: its first swing doubles the static strain) */
  PetscReal body_delay     = 0; /* [µs] */
  PetscReal body_ramp_time = 0; /* [µs]; 0: at once */

  /* -body_force gx,gy, -body_force_delay, -body_force_ramp_time */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
  /* the fraction of the body force acting at time t */
  PetscReal BodyScale(PetscReal t) const
  {
    if (t < body_delay) return 0;
    return body_ramp_time > 0 && t < body_delay + body_ramp_time ? (t - body_delay) / body_ramp_time : 1;
  }
  bool Scheduled() const { return body_delay > 0 || body_ramp_time > 0; }
  /* a mode that applies the body force at once refuses a schedule, naming itself */
  PetscErrorCode RequireUnscheduled(MPI_Comm comm, const char *mode) const;
};

} // namespace turgor
