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
  Mat            A[3] = {ops.K(), ops.C(), ops.M()}, even[3] = {NULL, NULL, NULL};
  PetscInt       rows, fewest;
  PetscFunctionBeginUser;
  PetscCheck(pep_ && ops.C(), comm_, PETSC_ERR_ORDER, "DampedModes: SetFromOptions() first, and operators assembled with damping");
  PetscCall(PetscLogEventBegin(ev_solve_, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  /* SLEPc 3.18's TOAR breaks down where a rank holds no row of the pencil (LAPACK's DLASCL on a zero
     norm, or ranks that leave PEPSolve apart): the mesh's free dofs may all lie on some of the ranks.
     Then the pencil is solved in an even row layout; only the eigenvalues are kept, so nothing maps
     back. */
  PetscCall(MatGetLocalSize(A[0], &rows, NULL));
  PetscCallMPI(MPI_Allreduce(&rows, &fewest, 1, MPIU_INT, MPI_MIN, comm_));
  if (fewest == 0) {
    PetscInt N, lo;
    IS       is;
    PetscCall(MatGetSize(A[0], &N, NULL));
    PetscMPIInt size, rank;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    lo = (N * rank) / size;
    PetscCall(ISCreateStride(comm_, (N * (rank + 1)) / size - lo, lo, 1, &is));
    for (int q = 0; q < 3; q++) {
      PetscCall(MatCreateSubMatrix(A[q], is, is, MAT_INITIAL_MATRIX, &even[q]));
      A[q] = even[q];
    }
    PetscCall(ISDestroy(&is));
  }
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
    PetscCall(PEPComputeError(pep_, i, PEP_ERROR_BACKWARD, &v.residual)); /* collective: on every rank, for every pair */
    if (v.im < 0) continue;                                               /* the conjugate of a pair already reported */
    values_.push_back(v);
  }
  for (Mat &E : even) PetscCall(MatDestroy(&E));
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
