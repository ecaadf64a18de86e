#include <turgor/physics/body_force.h>
#include <cmath>

namespace turgor {

PetscErrorCode BodyForce::SetFromOptions(MPI_Comm comm)
{
  PetscInt  n = 2;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "body_", "Body force", "turgor");
  PetscCall(PetscOptionsRealArray("-force", "Acceleration gx,gy on every particle [µm/µs^2] (default 0,-0.2)", "BodyForce", g, &n, &set));
  PetscOptionsEnd();
  PetscCheck(!set || n == 2, comm, PETSC_ERR_ARG_SIZ, "Option -body_force needs two components gx,gy (got %" PetscInt_FMT ")", n);
  PetscCheck(std::isfinite(g[0]) && std::isfinite(g[1]), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -body_force = %g,%g: must be finite", (double)g[0], (double)g[1]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  const ParticleSet &P = *in.P;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < P.n; i++) {
    f[2 * i] += P.mass[i] * g[0];
    f[2 * i + 1] += P.mass[i] * g[1];
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  const ParticleSet &P = *in.P;
  PetscFunctionBeginUser;
  *E = 0;
  for (PetscInt i = 0; i < P.n; i++) *E -= P.mass[i] * (g[0] * in.x[2 * i] + g[1] * in.x[2 * i + 1]);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BodyForce::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "body_force: g = (%g, %g) µm/µs^2\n", (double)g[0], (double)g[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
