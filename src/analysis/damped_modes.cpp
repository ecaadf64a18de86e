#include <turgor/analysis/damped_modes.h>
#include <turgor/analysis/pencil_eigensolver.h>
#include <algorithm>
#include <cmath>

namespace turgor {

DampedModes::~DampedModes()
{
  PetscCallVoid(PEPDestroy(&pep_));
}

PetscErrorCode DampedModes::SetFromOptions(const std::string &prefix, PetscInt nev, PetscReal tol)
{
  ST st;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgEigenDamped", PETSC_OBJECT_CLASSID, &ev_solve_));
  PetscCall(PEPDestroy(&pep_));
  PetscCall(PEPCreate(comm_, &pep_));
  PetscCall(PEPSetOptionsPrefix(pep_, prefix.c_str()));
  PetscCall(PEPSetType(pep_, PEPTOAR));
  PetscCall(PEPSetProblemType(pep_, PEP_GENERAL));
  /* each pair s, conj(s) counts twice: 2 nev eigenvalues give nev modes */
  PetscCall(PEPSetDimensions(pep_, 2 * nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(PEPSetTolerances(pep_, tol, PETSC_DEFAULT));
  PetscCall(PEPSetTarget(pep_, 0.0));
  PetscCall(PEPSetWhichEigenpairs(pep_, PEP_TARGET_MAGNITUDE));
  PetscCall(PEPGetST(pep_, &st));
  PetscCall(SetDirectST(st, STSINVERT, PCLU)); /* P(target) = K + target C + target^2 M need not be symmetric */
  PetscCall(PEPSetFromOptions(pep_));
  {
    PetscInt n;
    PetscCall(PEPGetDimensions(pep_, &n, NULL, NULL));
    nev_ = (n + 1) / 2;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DampedModes::Solve(const CoarseOperators &ops)
{
  PetscInt       nconv;
  PetscLogDouble t0, t1;
  Mat            A[3] = {ops.K(), ops.C(), ops.M()};
  PetscFunctionBeginUser;
  PetscCheck(pep_ && ops.C(), comm_, PETSC_ERR_ORDER, "DampedModes: SetFromOptions() first, and operators assembled with damping");
  PetscCall(PetscLogEventBegin(ev_solve_, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(PEPSetOperators(pep_, 3, A));
  PetscCall(PEPSolve(pep_));
  PetscCall(PetscTime(&t1));
  solve_time_ = t1 - t0;
  PetscCall(PEPGetIterationNumber(pep_, &its_));
  PetscCall(PEPGetConverged(pep_, &nconv));
  values_.clear();
  for (PetscInt i = 0; i < nconv; i++) {
    PetscScalar      kr, ki;
    DampedEigenvalue v;
    PetscCall(PEPGetEigenpair(pep_, i, &kr, &ki, NULL, NULL));
    v.re = PetscRealPart(kr);
#if defined(PETSC_USE_COMPLEX)
    v.im = PetscImaginaryPart(kr);
#else
    v.im = PetscRealPart(ki);
#endif
    if (v.im < 0) continue; /* the conjugate of a pair already reported */
    PetscCall(PEPComputeError(pep_, i, PEP_ERROR_BACKWARD, &v.residual));
    values_.push_back(v);
  }
  std::stable_sort(values_.begin(), values_.end(),
                   [](const DampedEigenvalue &a, const DampedEigenvalue &b) { return std::hypot(a.re, a.im) < std::hypot(b.re, b.im); });
  if ((PetscInt)values_.size() > nev_) values_.resize(nev_); /* the modes asked for (PEP may converge a few more) */
  {
    PEPType type;
    ST      st;
    PetscCall(PEPGetType(pep_, &type));
    PetscCall(PEPGetST(pep_, &st));
    PetscCall(DescribeSolver(type, st, &description_));
  }
  PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
