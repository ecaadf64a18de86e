#include <turgor/analysis/pencil_eigensolver.h>
#include <algorithm>
#include <cmath>
#include <numeric>

namespace turgor {

PetscErrorCode SetDirectST(ST st, STType type, PCType factor)
{
  KSP ksp;
  PC  pc;
  PetscFunctionBeginUser;
  PetscCall(STSetType(st, type));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, factor));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DescribeSolver(const char *method, ST st, std::string *text)
{
  STType        st_type;
  KSPType       ksp_type;
  PCType        pc_type;
  MatSolverType solver = NULL;
  KSP           ksp;
  PC            pc;
  PetscBool     factor;
  PetscFunctionBeginUser;
  PetscCall(STGetType(st, &st_type));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(KSPGetType(ksp, &ksp_type));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &pc_type));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factor, PCLU, PCCHOLESKY, PCILU, PCICC, ""));
  if (factor) PetscCall(PCFactorGetMatSolverType(pc, &solver));
  *text = std::string(method) + ", " + (st_type ? st_type : "") + ", " + (ksp_type ? ksp_type : "") + " + " + (pc_type ? pc_type : "") +
          (solver ? std::string(" (") + solver + ")" : std::string());
  PetscFunctionReturn(PETSC_SUCCESS);
}

PencilEigensolver::~PencilEigensolver()
{
  PetscCallVoid(EPSDestroy(&eps_));
}

PetscErrorCode PencilEigensolver::SetFromOptions(const std::string &prefix, PencilEnd end, PetscInt nev, PetscReal tol)
{
  ST st;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("TgEigenSolve", PETSC_OBJECT_CLASSID, &ev_solve_));
  PetscCall(EPSDestroy(&eps_));
  PetscCall(EPSCreate(comm_, &eps_));
  PetscCall(EPSSetOptionsPrefix(eps_, prefix.c_str()));
  PetscCall(EPSSetProblemType(eps_, EPS_GHEP));
  PetscCall(EPSSetType(eps_, EPSKRYLOVSCHUR));
  PetscCall(EPSSetDimensions(eps_, nev, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps_, tol, PETSC_DEFAULT));
  PetscCall(EPSGetST(eps_, &st));
  /* one direct factorisation (of K - sigma M, or of M), symmetric: MUMPS's LDL^T takes a K that is
     indefinite past a loss of stability */
  if (end == PencilEnd::Lowest) {
    /* shift-and-invert about the target: the lowest modes converge in a few iterations */
    PetscCall(SetDirectST(st, STSINVERT, PCCHOLESKY));
    PetscCall(EPSSetTarget(eps_, 0.0));
    PetscCall(EPSSetWhichEigenpairs(eps_, EPS_TARGET_MAGNITUDE));
  } else {
    PetscCall(SetDirectST(st, STSHIFT, PCCHOLESKY));
    PetscCall(EPSSetWhichEigenpairs(eps_, EPS_LARGEST_REAL));
  }
  PetscCall(EPSSetFromOptions(eps_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscInt PencilEigensolver::Requested() const
{
  PetscInt nev = 0;
  if (eps_) PetscCallAbort(comm_, EPSGetDimensions(eps_, &nev, NULL, NULL));
  return nev;
}

PetscErrorCode PencilEigensolver::Solve(const CoarseOperators &ops)
{
  PetscInt       nconv;
  Vec            x;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCheck(eps_, comm_, PETSC_ERR_ORDER, "PencilEigensolver::SetFromOptions() must be called before Solve()");
  PetscCall(PetscLogEventBegin(ev_solve_, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  PetscCall(EPSSetOperators(eps_, ops.K(), ops.M()));
  PetscCall(EPSSolve(eps_));
  PetscCall(PetscTime(&t1));
  solve_time_ = t1 - t0;
  PetscCall(EPSGetIterationNumber(eps_, &its_));
  PetscCall(EPSGetConverged(eps_, &nconv));
  PetscCall(ops.CreateVector(&x));
  std::vector<Eigenpair> pairs(nconv);
  for (PetscInt i = 0; i < nconv; i++) {
    PetscScalar kr;
    PetscCall(EPSGetEigenpair(eps_, i, &kr, NULL, x, NULL));
    pairs[i].lambda = PetscRealPart(kr);
    PetscCall(EPSComputeError(eps_, i, EPS_ERROR_BACKWARD, &pairs[i].residual));
    PetscCall(ops.XFraction(x, &pairs[i].x_fraction));
  }
  PetscCall(VecDestroy(&x));
  /* the requested number, in the EPS's order (nearest the target, or largest, first: it may converge
     a few more, not all of the next ones), then sorted by lambda */
  order_.resize(PetscMin(nconv, Requested()));
  std::iota(order_.begin(), order_.end(), 0);
  std::stable_sort(order_.begin(), order_.end(), [&](PetscInt a, PetscInt b) { return pairs[a].lambda < pairs[b].lambda; });
  pairs_.clear();
  for (PetscInt i : order_) pairs_.push_back(pairs[i]);
  {
    EPSType type;
    ST      st;
    PetscCall(EPSGetType(eps_, &type));
    PetscCall(EPSGetST(eps_, &st));
    PetscCall(DescribeSolver(type, st, &description_));
  }
  PetscCall(PetscLogEventEnd(ev_solve_, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PencilEigensolver::GetVector(PetscInt i, Vec x) const
{
  PetscScalar kr;
  PetscFunctionBeginUser;
  PetscCheck(i >= 0 && i < (PetscInt)order_.size(), comm_, PETSC_ERR_ARG_OUTOFRANGE, "Eigenpair %" PetscInt_FMT " of %zu", i, order_.size());
  PetscCall(EPSGetEigenpair(eps_, order_[i], &kr, NULL, x, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
