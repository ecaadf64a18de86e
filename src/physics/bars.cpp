#include <turgor/physics/bars.h>
#include <turgor/physics/wall_springs.h>
#include <cmath>

namespace turgor {

PetscErrorCode Bars::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "bar_", "Bars of polygonal cells (axial springs with a dashpot)", "turgor");
  PetscCall(TurgorOptionsReal(ctx.params, "-stiffness", "Axial stiffness k_b [µN/µm = N/m]", "Bars", stiffness, &stiffness, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-damping", "Axial dashpot coefficient [ng/µs]; 0 = none", "Bars", damping, &damping, NULL));
  PetscOptionsEnd();
  PetscCheck(stiffness >= 0 && std::isfinite(stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -bar_stiffness = %g: a stiffness must be finite and >= 0",
             (double)stiffness);
  PetscCheck(damping >= 0 && std::isfinite(damping), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -bar_damping = %g: must be finite and >= 0", (double)damping);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  for (size_t s = 0; s < P.springs.size(); s++)
    PetscCheck(P.springs[s].rest_length > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Bar %zu (%" PetscInt_FMT ", %" PetscInt_FMT ") has rest length %g: must be > 0", s, P.springs[s].i, P.springs[s].j,
               (double)P.springs[s].rest_length);
  gamma_.assign(P.springs.size(), damping);
  order_.Build(P);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  SpringForces(in, stiffness, gamma_, damping > 0, f, virial, &order_, &scratch_);
  PetscCall(PetscLogFlops(30.0 * in.P->springs.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  *E   = SpringEnergy(in, stiffness);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  PetscCall(SpringTimeStepLimit(*in.P, stiffness, gamma_, "bars", limits));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::OutputFields(const ForceInput &in, std::vector<TermField> &fields)
{
  PetscFunctionBeginUser;
  fields.push_back({TermField::BAR, "axial_force", "µN (tension > 0)", SpringAxialForces(in, stiffness, gamma_, damping > 0)});
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Bars::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "bars: k_b = %g µN/µm, dashpot %g ng/µs\n", (double)stiffness, (double)damping));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
