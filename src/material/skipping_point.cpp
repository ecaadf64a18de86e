#include <turgor/io/declared_state.h>
#include <turgor/material/skipping_point.h>
#include <cmath>

namespace turgor {

/* [L11, L22, L12 + L21]: the Voigt strain the tangents' columns answer (tangents.cpp) */
static void Voigt(const Tensor2 &L, PetscReal v[3])
{
  v[0] = L(0, 0);
  v[1] = L(1, 1);
  v[2] = L(0, 1) + L(1, 0);
}

/* D v as a symmetric stress */
static Tensor2 Apply(const PetscReal D[3][3], const PetscReal v[3])
{
  PetscReal s[3];
  for (int r = 0; r < 3; r++) s[r] = D[r][0] * v[0] + D[r][1] * v[1] + D[r][2] * v[2];
  return {
    {{s[0], s[2]}, {s[2], s[1]}}
  };
}

/* The Truesdell rate's inverse: the stress change along L and Ld about sigma */
static Tensor2 Change(const Tangents &D, const Tensor2 &sigma, const Tensor2 &L, const Tensor2 &Ld)
{
  PetscReal v[3], vd[3];
  Voigt(L, v);
  Voigt(Ld, vd);
  return Apply(D.De, v) + L * sigma + sigma * L.T() + (-L.Trace()) * sigma + Apply(D.Dv, vd);
}

bool SkippingPoint::Expand(const Tensor2 &F, const Tensor2 &Fdot, Tensor2 *sigma, PetscReal *d2) const
{
  if (!base_.have) return false;
  const Tensor2 Finv = base_.F.Inverse(), L = (F - base_.F) * Finv, Ld = (Fdot - base_.Fdot) * Finv;
  *sigma = base_.sigma + Change(base_.D, base_.sigma, L, Ld);
  *d2    = L.Norm() * L.Norm() + (Ld.Norm() / fdot_typ_) * (Ld.Norm() / fdot_typ_);
  return true;
}

PetscErrorCode SkippingPoint::Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out)
{
  Tensor2   s;
  PetscReal d2 = 0;
  PetscFunctionBeginUser;
  const bool expanded = Expand(F, Fdot, &s, &d2);
  /* a trial within the last measured step whose error, scaled down linearly, is within the
     tolerance; or a tangent's perturbation of a trial that was skipped */
  const PetscReal d    = std::sqrt(d2);
  const bool      near = kind == EvaluationKind::Trial && err_ >= 0 && d <= reach_ && (d == 0 || err_ * d <= tol_ * reach_);
  const bool      skip = expanded && F.Det() > 0 && (near || (kind == EvaluationKind::Perturbed && last_skipped_ != 0));
  if (skip) {
    *out       = MaterialResponse();
    out->sigma = s;
    out->rho   = base_.rho * base_.F.Det() / F.Det();
    if (kind == EvaluationKind::Trial) {
      skipped_++;
      last_skipped_ = 1;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(inner_->Evaluate(F, Fdot, kind, out));
  if (kind == EvaluationKind::Trial) {
    last_skipped_ = 0;
    /* the expansion's error at this solve and the step it was measured at */
    if (out->ok && expanded) {
      err_   = (out->sigma - s).Norm();
      reach_ = std::sqrt(d2);
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SkippingPoint::StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                                Tensor2 *dsigma, MaterialResponse *status)
{
  PetscFunctionBeginUser;
  if (!last_skipped_) {
    PetscCall(inner_->StressDerivatives(F, Fdot, n, dF, dFdot, kind, dsigma, status));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* the expansion's derivatives: sigma0 + Change(L) is linear in L = (F - F0) F0^-1 and Ld, so its
     derivative along (dF, dFdot) is Change(dF F0^-1, dFdot F0^-1) */
  *status            = MaterialResponse();
  const Tensor2 Finv = base_.F.Inverse();
  for (PetscInt k = 0; k < n; k++) dsigma[k] = Change(base_.D, base_.sigma, dF[k] * Finv, dFdot[k] * Finv);
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SkippingPoint::KeepTangents(const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &r, const Tangents &D)
{
  if (last_skipped_ || !r.ok) return; /* a base is a solved state */
  base_.have  = 1;
  base_.F     = F;
  base_.Fdot  = Fdot;
  base_.sigma = r.sigma;
  base_.rho   = r.rho;
  base_.D     = D;
}

PetscErrorCode SkippingPoint::Commit()
{
  PetscFunctionBeginUser;
  PetscCall(inner_->Commit());
  committed_base_  = base_;
  committed_err_   = err_;
  committed_reach_ = reach_;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SkippingPoint::Revert()
{
  PetscFunctionBeginUser;
  PetscCall(inner_->Revert());
  base_         = committed_base_;
  err_          = committed_err_;
  reach_        = committed_reach_;
  last_skipped_ = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void SkippingPoint::AddCounters(MaterialCounters &c) const
{
  inner_->AddCounters(c);
  c.skipped_solves += skipped_;
}

/* [the inner point's state; for the current and the committed base: have, rho, F, Fdot, sigma, De, Dv;
   the measured error and step, their committed values, last skipped, skipped] */
void SkippingPoint::DeclareState(StateDeclaration &d)
{
  StateDeclaration inner("inner");
  inner_->DeclareState(inner);
  d.Include(std::move(inner));
  for (Base *b : {&base_, &committed_base_}) {
    const std::string p = b == &base_ ? "base_" : "committed_base_";
    d.Scalar(p + "have", &b->have, Combine::Owner);
    d.Scalar(p + "rho", &b->rho, Combine::Owner);
    d.Array(p + "F", &b->F.a[0][0], 4, Combine::Owner);
    d.Array(p + "Fdot", &b->Fdot.a[0][0], 4, Combine::Owner);
    d.Array(p + "sigma", &b->sigma.a[0][0], 4, Combine::Owner);
    d.Array(p + "De", &b->D.De[0][0], 9, Combine::Owner);
    d.Array(p + "Dv", &b->D.Dv[0][0], 9, Combine::Owner);
  }
  d.Scalar("measured_error", &err_, Combine::Owner);
  d.Scalar("measured_step", &reach_, Combine::Owner);
  d.Scalar("committed_measured_error", &committed_err_, Combine::Owner);
  d.Scalar("committed_measured_step", &committed_reach_, Combine::Owner);
  d.Scalar("last_skipped", &last_skipped_, Combine::Owner);
  d.Scalar("skipped", &skipped_, Combine::Owner);
}

} // namespace turgor
