#include "q2_element.h"

namespace turgor {
namespace q2 {

/* PetscDT's n x n Gauss-Legendre rule on [-1, 1]^2. */
static PetscErrorCode GaussRule(PetscInt n, std::vector<PetscReal> &xi, std::vector<PetscReal> &w)
{
  PetscQuadrature  q;
  PetscInt         np;
  const PetscReal *p, *wt;
  PetscFunctionBeginUser;
  PetscCall(PetscDTGaussTensorQuadrature(2, 1, n, -1.0, 1.0, &q));
  PetscCall(PetscQuadratureGetData(q, NULL, NULL, &np, &p, &wt));
  xi.assign(p, p + 2 * np);
  w.assign(wt, wt + np);
  PetscCall(PetscQuadratureDestroy(&q));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Tabulate(CoarseQuadrature rule, ReferenceElement *ref)
{
  const bool             sri = rule == CoarseQuadrature::SRI;
  std::vector<PetscReal> x3, w3, x2, w2;
  PetscFE                fe;
  PetscInt               Nb;
  PetscTabulation        T;
  PetscFunctionBeginUser;
  PetscCall(GaussRule(3, x3, w3));
  PetscCall(GaussRule(2, x2, w2));
  ref->element     = "q2";
  ref->rule        = sri ? "sri" : "full";
  ref->description = sri ? "Q2, selective reduced integration (deviator at the 3 x 3 Gauss points, pressure at the 2 x 2)" : "Q2, full 3 x 3 integration";
  ref->degree      = 2;
  ref->nodes       = 9;
  ref->xi          = x3;
  ref->w           = w3;
  ref->part.assign(w3.size(), sri ? PointPart::Deviatoric : PointPart::Whole);
  ref->where.clear();
  for (size_t q = 0; q < w3.size(); q++) ref->where.push_back((sri ? "deviatoric point " : "Gauss point ") + std::to_string(q + 1) + " of 3 x 3");
  if (sri) {
    ref->xi.insert(ref->xi.end(), x2.begin(), x2.end());
    ref->w.insert(ref->w.end(), w2.begin(), w2.end());
    ref->part.insert(ref->part.end(), w2.size(), PointPart::Pressure);
    for (size_t q = 0; q < w2.size(); q++) ref->where.push_back("pressure point " + std::to_string(q + 1) + " of 2 x 2");
  }
  ref->points = (PetscInt)ref->w.size();

  /* the scalar Q2 space: its basis is one node per closure point, in closure order */
  PetscCall(PetscFECreateLagrange(PETSC_COMM_SELF, 2, 1, PETSC_FALSE, 2, PETSC_DETERMINE, &fe));
  PetscCall(PetscFEGetDimension(fe, &Nb));
  PetscCheck(Nb == 9, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Q2 PetscFE with %" PetscInt_FMT " basis functions, expected 9", Nb);
  PetscCall(PetscFECreateTabulation(fe, 1, ref->points, ref->xi.data(), 1, &T));
  ref->dN.assign(T->T[1], T->T[1] + ref->points * Nb * 2); /* [point][basis][component 0][d] */
  PetscCall(PetscTabulationDestroy(&T));
  /* the consistent mass: 3 x 3 Gauss is exact for N_a N_b det J (degree 5 per direction) */
  ref->mass_xi     = x3;
  ref->mass_w      = w3;
  ref->mass_points = (PetscInt)w3.size();
  PetscCall(PetscFECreateTabulation(fe, 1, ref->mass_points, ref->mass_xi.data(), 0, &T));
  ref->mass_N.assign(T->T[0], T->T[0] + ref->mass_points * Nb);
  PetscCall(PetscTabulationDestroy(&T));
  PetscCall(PetscFEDestroy(&fe));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace q2
} // namespace turgor
