#include <turgor/physics/body_force.h>

namespace turgor {

PetscErrorCode BodyForce::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscCheck(ctx.load, comm, PETSC_ERR_ARG_WRONGSTATE, "Physics term body_force: this scene has no loads (-body_force)");
  load = *ctx.load;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const ParticleSet &P = *in.P;
  const PetscReal    s = load.BodyScale(in.t), gx = s * load.body_acceleration[0], gy = s * load.body_acceleration[1];
  PetscFunctionBeginUser;
  const ForceGrain &grain   = in.Grain();
  const bool        rounded = grain.On(); /* once: f's stores could alias the grain */
  for (PetscInt i = 0; i < P.NumOwned(); i++) {
    PetscReal fx = P.mass[i] * gx, fy = P.mass[i] * gy;
    if (rounded) grain(fx, fy);
    f[2 * i] += fx;
    f[2 * i + 1] += fy;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  const ParticleSet &P = *in.P;
  const PetscReal   *g = load.body_acceleration;
  PetscFunctionBeginUser;
  *E = 0;
  for (PetscInt i = 0; i < P.NumOwned(); i++) *E -= P.mass[i] * (g[0] * in.x[2 * i] + g[1] * in.x[2 * i + 1]);
  *E *= load.BodyScale(in.t);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  char when[96] = "";
  if (load.Scheduled())
    PetscCall(PetscSNPrintf(when, sizeof when, ", from t = %g µs, built up over %g µs", (double)load.body_delay, (double)load.body_ramp_time));
  PetscCall(PetscViewerASCIIPrintf(viewer, "body_force: g = (%g, %g) µm/µs^2%s\n", (double)load.body_acceleration[0], (double)load.body_acceleration[1], when));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
