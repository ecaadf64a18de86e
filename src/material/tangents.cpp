#include <turgor/material/material_point.h>
#include <cmath>

namespace turgor {

/* The three perturbation directions (k, l) and the Voigt row of a stress component. */
static const int kPairs[3][2] = {
  {0, 0},
  {1, 1},
  {0, 1}
};

static void StoreColumn(const Tensor2 &c, int col, PetscReal D[3][3])
{
  D[0][col] = c(0, 0);
  D[1][col] = c(1, 1);
  D[2][col] = 0.5 * (c(0, 1) + c(1, 0));
}

PetscErrorCode MaterialPoint::StressDerivatives(const Tensor2 &, const Tensor2 &, PetscInt, const Tensor2 *, const Tensor2 *, EvaluationKind, Tensor2 *,
                                                MaterialResponse *status)
{
  PetscFunctionBeginUser;
  *status        = MaterialResponse();
  status->ok     = false;
  status->reason = "this material has no exact stress derivatives (-material_tangent forward or central)";
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The columns of eqs 48 and 51 from exact derivatives: along dF = (e_k (x) e_l) F (Fdot fixed) the
   Truesdell rate with L = dF F^-1 = e_k (x) e_l, and along dFdot = (e_k (x) e_l) F (F fixed) the
   derivative itself. */
static PetscErrorCode ExactTangents(MaterialPoint &mp, const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &base, const TangentOptions &opt,
                                    Tangents *D, MaterialResponse *status, EvaluationKind kind)
{
  const PetscInt n = opt.viscosity ? 6 : 3;
  Tensor2        dF[6], dFdot[6], ds[6];
  PetscFunctionBeginUser;
  for (int col = 0; col < 3; col++) {
    const Tensor2 EF = Tensor2::Unit(kPairs[col][0], kPairs[col][1]) * F;
    dF[col]          = EF;
    dFdot[col + 3]   = EF;
  }
  PetscCall(mp.StressDerivatives(F, Fdot, n, dF, dFdot, kind, ds, status));
  if (!status->ok) PetscFunctionReturn(PETSC_SUCCESS);
  const Tensor2 &sigma = base.sigma;
  for (int col = 0; col < 3; col++) {
    const Tensor2 L = Tensor2::Unit(kPairs[col][0], kPairs[col][1]);
    StoreColumn(ds[col] - L * sigma - sigma * L.T() + L.Trace() * sigma, col, D->De);
    if (opt.viscosity) StoreColumn(ds[col + 3], col, D->Dv);
    else
      for (int r = 0; r < 3; r++) D->Dv[r][col] = 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ComputeTangents(MaterialPoint &mp, const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &base, const TangentOptions &opt, Tangents *D,
                               MaterialResponse *status, EvaluationKind kind)
{
  const PetscReal  U       = opt.U > 0 ? opt.U : mp.StressUncertainty();
  const PetscReal  sq      = std::sqrt(U);
  const Tensor2   &sigma   = base.sigma;
  const bool       central = opt.method == TangentMethod::Central;
  MaterialResponse rp, rm;

  PetscFunctionBeginUser;
  *status = MaterialResponse();
  if (opt.method == TangentMethod::Implicit) {
    PetscCall(ExactTangents(mp, F, Fdot, base, opt, D, status, kind));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  for (int col = 0; col < 3; col++) {
    const int     k = kPairs[col][0], l = kPairs[col][1];
    const Tensor2 E = Tensor2::Unit(k, l);
    /* elasticity, eqs 47-48 and 52: dF = eps (e_k (x) e_l) F, so dF F^{-1} = eps e_k (x) e_l */
    {
      const PetscReal eps = sq;
      const Tensor2   dF  = eps * (E * F);
      Tensor2         dsigma;
      PetscCall(mp.Evaluate(F + dF, Fdot, kind, &rp));
      if (!rp.ok) {
        *status = rp;
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      if (central) {
        PetscCall(mp.Evaluate(F - dF, Fdot, kind, &rm));
        if (!rm.ok) {
          *status = rm;
          PetscFunctionReturn(PETSC_SUCCESS);
        }
        dsigma = 0.5 * (rp.sigma - rm.sigma);
      } else dsigma = rp.sigma - sigma;
      const Tensor2 L = eps * E; /* dF F^{-1} */
      /* Truesdell rate: d sigma - L sigma - sigma L^T + tr(L) sigma = c : sym(L) */
      const Tensor2 c = (1.0 / eps) * (dsigma - L * sigma - sigma * L.T() + L.Trace() * sigma);
      StoreColumn(c, col, D->De);
    }
    /* viscosity, eqs 50-51 and 53 */
    if (opt.viscosity) {
      const Tensor2   EF  = E * F;
      const PetscReal eps = sq * std::max(Fdot.Norm() / EF.Norm(), opt.Fdot_typ);
      const Tensor2   dFd = eps * EF;
      Tensor2         dsigma;
      PetscCall(mp.Evaluate(F, Fdot + dFd, kind, &rp));
      if (!rp.ok) {
        *status = rp;
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      if (central) {
        PetscCall(mp.Evaluate(F, Fdot - dFd, kind, &rm));
        if (!rm.ok) {
          *status = rm;
          PetscFunctionReturn(PETSC_SUCCESS);
        }
        dsigma = 0.5 * (rp.sigma - rm.sigma);
      } else dsigma = rp.sigma - sigma;
      StoreColumn((1.0 / eps) * dsigma, col, D->Dv);
    } else
      for (int r = 0; r < 3; r++) D->Dv[r][col] = 0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
