#include <turgor/physics/viscosity.h>
#include <turgor/core/vector_clones.h>
#include <cmath>

namespace turgor {

PetscErrorCode Viscosity::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "viscosity_", "Global viscosity f = -nu v on every node", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-coefficient", "nu [ng/µs]: force per velocity on every node", "Viscosity", coefficient, &coefficient, NULL));
  PetscOptionsEnd();
  PetscCheck(coefficient >= 0 && std::isfinite(coefficient), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -viscosity_coefficient = %g: must be finite and >= 0",
             (double)coefficient);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* No virial: the force is not an interaction (it acts against the lab frame). */
namespace {
/* f -= nu v, in a loop the compiler vectorises (f and v apart) */
TURGOR_VECTOR_CLONES void DragLoop(PetscInt n, PetscReal nu, const PetscReal *__restrict v, PetscReal *__restrict f)
{
  for (PetscInt k = 0; k < n; k++) f[k] -= nu * v[k];
}
} // namespace

/* The work it removes is the energy balance's (the term's force on the velocities), not summed here. */
PetscErrorCode Viscosity::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  const PetscInt    n     = 2 * in.P->NumOwned();
  const PetscReal   nu    = coefficient;
  const ForceGrain &grain = in.Grain();
  if (grain.On())
    for (PetscInt k = 0; k < n; k++) f[k] -= grain(nu * in.v[k]);
  else DragLoop(n, nu, in.v, f);
  PetscCall(PetscLogFlops(2.0 * n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* x'' = -(nu/m) x': an explicit step is stable for dt < 2 m / nu. */
PetscErrorCode Viscosity::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscReal mmin = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < in.P->n; i++) mmin = std::min(mmin, in.P->mass[i]);
  if (coefficient > 0 && in.P->n > 0) {
    char why[128];
    PetscCall(PetscSNPrintf(why, sizeof why, "viscosity: rate nu/m <= %.4g /µs", (double)(coefficient / mmin)));
    limits.push_back({2.0 * mmin / coefficient, why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Viscosity::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "viscosity: f = -nu v, nu = %g ng/µs\n", (double)coefficient));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
