#pragma once
/* A material point that answers from its last solve's tangents while the deformation has moved
   little since (-material_skip_tolerance): "simulate only what the scene calls for" at the material
   point. The answer is the first-order expansion about the base (F0, Fdot0, sigma0, D^e, D^v) of the
   last trial solve whose tangents the pool computed, in the Truesdell form the tangents are stored in
   (tangents.cpp):

     sigma ~ sigma0 + D^e v(L) + L sigma0 + sigma0 L^T - tr(L) sigma0 + D^v v(Ld),
     L = (F - F0) F0^-1,  Ld = (Fdot - Fdot0) F0^-1,  v(L) = [L11, L22, L12 + L21],

   and rho = rho0 det F0 / det F. Its error is measured at every trial solve that follows a base: the
   solved stress against the expansion's, e at the step |d|, |d|^2 = |L|^2 + |Ld / Fdot_typ|^2
   (-material_tangent_fdot_typ). A later trial is answered by the expansion when its step is within
   the measured one and the error scaled down linearly, e |d| / |d_measured|, is within the tolerance
   [N/m]; otherwise (and before any measurement) it solves, and measures again. Only interpolation:
   an error measured at a small step says nothing of a larger one, and a linear scaling (not the
   smooth expansion's quadratic one) holds across the kinks of contact, glue or a viscosity that acts
   on approaching pairs only (with a quadratic model extrapolated from one measurement, the default
   FE² scene's tip went wrong by 30 % at 1e-3 N/m). Perturbed evaluations and exact derivatives after
   a skipped trial come from the same expansion, so that the coarse Jacobian is the expansion's;
   output evaluations always solve.

   The inner point keeps the state of its last solve: Commit after a skipped trial commits that one
   (history -- plastic hinges, bonds -- moves on at the last solved state, within the tolerance's
   reach); Revert returns the base and the measured error and step to their committed values. These
   and the count of skipped evaluations are declared state beside the inner point's (they restart
   and move with it). */
#include <turgor/material/material_point.h>
#include <memory>

namespace turgor {

class SkippingPoint : public MaterialPoint {
public:
  SkippingPoint(std::unique_ptr<MaterialPoint> inner, PetscReal tolerance, PetscReal fdot_typ) : inner_(std::move(inner)), tol_(tolerance), fdot_typ_(fdot_typ)
  {
  }
  PetscErrorCode Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out) override;
  PetscErrorCode Commit() override;
  PetscErrorCode Revert() override;
  PetscReal      StressUncertainty() const override { return inner_->StressUncertainty(); }
  PetscErrorCode StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                   Tensor2 *dsigma, MaterialResponse *status) override;
  void           KeepTangents(const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &r, const Tangents &D) override;
  void           AddCounters(MaterialCounters &c) const override;
  void           DeclareState(StateDeclaration &d) override;
  PetscErrorCode AfterStateRead() override { return inner_->AfterStateRead(); }

  /* The expansion's stress at (F, Fdot) and its step size |d|^2; false without a base. */
  bool Expand(const Tensor2 &F, const Tensor2 &Fdot, Tensor2 *sigma, PetscReal *d2) const;

private:
  struct Base {
    PetscReal have = 0, rho = 0;
    Tensor2   F, Fdot, sigma;
    Tangents  D;
  };
  std::unique_ptr<MaterialPoint> inner_;
  PetscReal                      tol_, fdot_typ_;
  Base                           base_, committed_base_;
  PetscReal                      err_ = -1, reach_ = 0; /* the last measured error (< 0: none yet) and its step |d| */
  PetscReal                      committed_err_ = -1, committed_reach_ = 0;
  PetscReal                      last_skipped_ = 0; /* the last trial was answered by the expansion */
  PetscInt                       skipped_      = 0;
};

} // namespace turgor
