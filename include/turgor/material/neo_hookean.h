#pragma once
/* Closed-form material: compressible neo-Hookean solid (plane strain) plus linear viscosity,
     sigma = (mu/J)(F F^T - I) + (lambda/J) ln J I + eta (l + l^T),   l = Fdot F^{-1},  rho = rho0/J,
   with its analytic tangents, to verify the finite-difference tangents and the coarse solver. */
#include <turgor/core/parameters.h>
#include <turgor/material/material_point.h>

namespace turgor {

struct NeoHookeanSpec {
  PetscReal mu = 500.0, lambda = 1000.0; /* [N/m] */
  PetscReal viscosity = 1.0;             /* eta [ng/µs] */
  PetscReal density   = 0.0126;          /* rho0 [ng/µm^2] */

  /* -nh_mu, -nh_lambda, -nh_viscosity, -nh_density */
  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr);
};

class NeoHookean : public MaterialPoint {
public:
  explicit NeoHookean(const NeoHookeanSpec &spec = NeoHookeanSpec()) : p(spec) { }
  PetscErrorCode Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out) override;
  PetscReal      StressUncertainty() const override { return 1e-16; }
  /* The closed form's derivatives along (dF, dFdot) (no inner unknowns). */
  PetscErrorCode StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                   Tensor2 *dsigma, MaterialResponse *status) override;
  /* Analytic D^e (Truesdell rate, Fdot = 0) and D^v in the order (11, 22, 12). */
  void AnalyticTangents(const Tensor2 &F, Tangents *D) const;

  NeoHookeanSpec p;
};

/* -material neo_hookean */
class NeoHookeanMaterial : public MaterialModel {
public:
  const char              *Name() const override { return "neo_hookean"; }
  PetscErrorCode           SetFromOptions(MPI_Comm comm, ParameterList *params) override { return spec.SetFromOptions(comm, params); }
  PetscErrorCode           CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const override;
  std::vector<std::string> Physics() const override { return {"neo_hookean"}; }
  bool                     HasStressDerivatives() const override { return true; }
  PetscErrorCode           View(PetscViewer viewer) const override;

  NeoHookeanSpec spec;
};

} // namespace turgor
