#include <turgor/material/neo_hookean.h>
#include <cmath>

namespace turgor {

/* The moduli a neo-Hookean point accepts [N/m]: magnitudes in [kModulusMin, kModulusMax], and
   mu >= kShearRatioMin (lambda + mu) (a smaller shear modulus is below the round-off of the tangent:
   at 1e-15 of the bulk modulus the lowest eigenvalue is 8% off, at 1e-17 the stiffness is singular). */
static const PetscReal kModulusMin = 1e-100, kModulusMax = 1e100, kShearRatioMin = 1e-12;

PetscErrorCode NeoHookeanSpec::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "nh_", "Closed-form neo-Hookean material point (verification)", "turgor");
  PetscCall(TurgorOptionsReal(params, "-mu", "Shear modulus mu [N/m]", "NeoHookeanSpec", mu, &mu, NULL));
  PetscCall(TurgorOptionsReal(params, "-lambda", "Lame constant lambda [N/m]", "NeoHookeanSpec", lambda, &lambda, NULL));
  PetscCall(TurgorOptionsReal(params, "-viscosity", "Viscosity eta in eta (l + l^T) [ng/µs]", "NeoHookeanSpec", viscosity, &viscosity, NULL));
  PetscCall(TurgorOptionsReal(params, "-density", "Reference density rho0 [ng/µm^2]", "NeoHookeanSpec", density, &density, NULL));
  PetscOptionsEnd();
  PetscCheck(mu > 0 && std::isfinite(mu), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -nh_mu = %g: must be finite and > 0", (double)mu);
  PetscCheck(lambda > -mu && std::isfinite(lambda), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -nh_lambda = %g: must be finite and > -mu", (double)lambda);
  /* the tangents, and the eigen solvers' products of them, square the moduli: beyond this range
     they leave double precision (the shift-and-invert solves break down) */
  for (auto [name, value] : {
         std::pair<const char *, PetscReal>{"-nh_mu",     mu    },
            {"-nh_lambda", lambda}
  })
    PetscCheck(value == 0 || (std::fabs(value) >= kModulusMin && std::fabs(value) <= kModulusMax), comm, PETSC_ERR_ARG_OUTOFRANGE,
               "Option %s = %g N/m: outside [%g, %g] N/m (in magnitude), where the stiffness and its products stay within double precision", name,
               (double)value, (double)kModulusMin, (double)kModulusMax);
  /* a shear modulus below the round-off of the bulk one is lost from the tangent: the stiffness is
     singular (the eigen mode's factorisation fails, a static solve diverges) */
  PetscCheck(mu >= kShearRatioMin * (lambda + mu), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "Option -nh_mu = %g N/m: below %g of the bulk modulus lambda + mu = %g N/m (-nh_lambda %g): the shear stiffness is lost to round-off and the "
             "tangent stiffness is singular; the material must resist shear",
             (double)mu, (double)kShearRatioMin, (double)(lambda + mu), (double)lambda);
  PetscCheck(viscosity >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -nh_viscosity = %g: must be >= 0", (double)viscosity);
  PetscCheck(density > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -nh_density = %g: a density must be > 0", (double)density);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A fresh response; a failed one (and true) when det F <= 0. */
static bool Inverted(PetscReal J, MaterialResponse *r)
{
  *r = MaterialResponse();
  if (J > 0) return false;
  r->ok     = false;
  r->reason = "inverted element (det F = " + std::to_string(J) + ")";
  return true;
}

PetscErrorCode NeoHookean::Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out)
{
  PetscFunctionBeginUser;
  const PetscReal J = F.Det();
  if (Inverted(J, out)) PetscFunctionReturn(PETSC_SUCCESS);
  const Tensor2 b = F * F.T(), l = Fdot * F.Inverse();
  out->sigma = (p.mu / J) * (b - Tensor2::Identity()) + (p.lambda * std::log(J) / J) * Tensor2::Identity() + p.viscosity * (l + l.T());
  out->rho   = p.density / J;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* d sigma = -mu dJ/J^2 (b - I) + (mu/J) db + lambda (1 - ln J) dJ/J^2 I + eta (dl + dl^T), with
   dJ = J tr(dF F^-1), db = dF F^T + F dF^T, dl = dFdot F^-1 - l dF F^-1. */
PetscErrorCode NeoHookean::StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind,
                                             Tensor2 *dsigma, MaterialResponse *status)
{
  PetscFunctionBeginUser;
  const PetscReal J = F.Det();
  if (Inverted(J, status)) PetscFunctionReturn(PETSC_SUCCESS);
  const Tensor2 Fi = F.Inverse(), l = Fdot * Fi, I = Tensor2::Identity(), bI = F * F.T() - I;
  for (PetscInt k = 0; k < n; k++) {
    const PetscReal dJ = J * (dF[k] * Fi).Trace();
    const Tensor2   db = dF[k] * F.T() + F * dF[k].T();
    const Tensor2   dl = dFdot[k] * Fi - l * dF[k] * Fi;
    dsigma[k]          = (-p.mu * dJ / (J * J)) * bI + (p.mu / J) * db + (p.lambda * (1 - std::log(J)) * dJ / (J * J)) * I + p.viscosity * (dl + dl.T());
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* c_ijkl = (lambda/J) d_ij d_kl + ((mu - lambda ln J)/J)(d_ik d_jl + d_il d_jk): D^e(11,11) = lambda/J
   + 2(mu - lambda ln J)/J, D^e(11,22) = lambda/J, D^e(12,12) = (mu - lambda ln J)/J; viscosity
   eta (l + l^T) gives D^v = diag(2 eta, 2 eta, eta). */
void NeoHookean::AnalyticTangents(const Tensor2 &F, Tangents *D) const
{
  const PetscReal J = F.Det(), m = (p.mu - p.lambda * std::log(J)) / J;
  *D          = Tangents();
  D->De[0][0] = D->De[1][1] = p.lambda / J + 2 * m;
  D->De[0][1] = D->De[1][0] = p.lambda / J;
  D->De[2][2]               = m;
  D->Dv[0][0] = D->Dv[1][1] = 2 * p.viscosity;
  D->Dv[2][2]               = p.viscosity;
}

PetscErrorCode NeoHookeanMaterial::CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const
{
  PetscFunctionBeginUser;
  *point = std::make_unique<NeoHookean>(spec);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode NeoHookeanMaterial::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "material neo_hookean: mu = %g, lambda = %g N/m, eta = %g ng/µs, rho0 = %g ng/µm^2\n", (double)spec.mu,
                                   (double)spec.lambda, (double)spec.viscosity, (double)spec.density));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
