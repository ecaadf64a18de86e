#include <turgor/physics/dashpots.h>
#include <turgor/physics/wall_springs.h>
#include <cmath>

namespace turgor {

PetscErrorCode Dashpots::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "dashpot_", "Dashpots along the bars (wall springs): damping of their stretching rate", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-coefficient", "c [ng/µs]: force per relative velocity along a bar", "Dashpots", coefficient, &coefficient, NULL));
  PetscOptionsEnd();
  PetscCheck(coefficient >= 0 && std::isfinite(coefficient), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -dashpot_coefficient = %g: must be finite and >= 0",
             (double)coefficient);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Dashpots::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  gamma_.assign(P.springs.size(), coefficient);
  order_.Build(P);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The spring kernel with no spring: only its dashpot part. */
PetscErrorCode Dashpots::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  SpringForces(in, 0, gamma_, coefficient > 0, f, virial, &order_, &scratch_);
  PetscCall(PetscLogFlops(25.0 * in.P->springs.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Dashpots::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscCall(SpringTimeStepLimit(*in.P, 0, gamma_, "dashpots", limits));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Dashpots::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "dashpots: c = %g ng/µs along every bar\n", (double)coefficient));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
