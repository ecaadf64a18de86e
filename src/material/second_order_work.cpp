#include <turgor/material/second_order_work.h>
#include <cmath>

namespace turgor {

StrainStress GreenLagrangeAndPiola(const Tensor2 &F, const Tensor2 &sigma)
{
  const Tensor2 Fi = F.Inverse();
  StrainStress  r;
  r.E = 0.5 * (F.T() * F - Tensor2::Identity());
  r.S = F.Det() * (Fi * sigma * Fi.T());
  return r;
}

static PetscReal Contract(const Tensor2 &A, const Tensor2 &B)
{
  PetscReal s = 0;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) s += A(i, j) * B(i, j);
  return s;
}

PetscReal SecondOrderWorkCosine(const StrainStress &a, const StrainStress &b, PetscReal strain_floor, PetscReal stress_floor)
{
  const Tensor2   dE = b.E - a.E, dS = b.S - a.S;
  const PetscReal nE = dE.Norm(), nS = dS.Norm();
  if (!(nE > strain_floor) || !(nS > stress_floor * PetscMax(a.S.Norm(), b.S.Norm()))) return 1;
  return PetscMax(-1.0, PetscMin(1.0, Contract(dS, dE) / (nS * nE)));
}

} // namespace turgor
