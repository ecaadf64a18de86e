#include <turgor/analysis/coarse_operators.h>
#include <cmath>

namespace turgor {

CoarseOperators::~CoarseOperators()
{
  for (Mat *A : {&J_, &K_, &C_, &M_}) PetscCallVoid(MatDestroy(A));
  for (IS *is : {&is_u_, &is_v_, &is_x_}) PetscCallVoid(ISDestroy(is));
}

PetscErrorCode CoarseOperators::SetUp()
{
  PetscInt lo, n;
  PetscFunctionBeginUser;
  PetscCall(model_.CreateFreeIS(&is_u_, &is_v_));
  PetscCall(ISGetSize(is_u_, &size_));
  PetscCheck(size_ > 0, PetscObjectComm((PetscObject)is_u_), PETSC_ERR_ARG_WRONG,
             "Options -coarse_dirichlet_*: every vertex of the mesh is clamped; there is no free displacement to analyse");
  PetscCall(MatDuplicate(model_.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &J_)); /* the model's pattern */
  PetscCall(MatCreateSubMatrix(model_.MassMatrix(), is_v_, is_v_, MAT_INITIAL_MATRIX, &M_));
  PetscCall(MatSetOption(M_, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(M_, MAT_SPD, PETSC_TRUE));
  /* the ux dofs in K's layout: even local rows (the free dofs come in pairs ux, uy per vertex) */
  PetscCall(MatGetOwnershipRange(M_, &lo, NULL));
  PetscCall(ISGetLocalSize(is_u_, &n));
  PetscCall(ISCreateStride(PetscObjectComm((PetscObject)M_), n / 2, lo, 2, &is_x_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::Assemble(Vec U, bool damping, PetscBool *ok, std::string *why)
{
  PetscFunctionBeginUser;
  PetscCheck(J_, PETSC_COMM_SELF, PETSC_ERR_ORDER, "CoarseOperators::SetUp() must be called first");
  PetscCall(model_.AssembleTangentAt(U, damping, J_, ok, why));
  if (!*ok) PetscFunctionReturn(PETSC_SUCCESS);
  const MatReuse reuse = K_ ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
  if (K_) PetscCall(MatSetOption(K_, MAT_SYMMETRIC, PETSC_FALSE)); /* until Symmetrize() */
  PetscCall(MatCreateSubMatrix(J_, is_v_, is_u_, reuse, &K_));
  asymmetry_ = 0;
  if (damping) {
    PetscCall(MatCreateSubMatrix(J_, is_v_, is_v_, have_C_ ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &C_));
    have_C_ = true;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::Symmetrize()
{
  Mat       Kt;
  PetscReal nk, nd;
  PetscFunctionBeginUser;
  PetscCall(MatTranspose(K_, MAT_INITIAL_MATRIX, &Kt));
  PetscCall(MatNorm(K_, NORM_FROBENIUS, &nk));
  PetscCall(MatAXPY(Kt, -1.0, K_, UNKNOWN_NONZERO_PATTERN)); /* K^T - K */
  PetscCall(MatNorm(Kt, NORM_FROBENIUS, &nd));
  asymmetry_ = nk > 0 ? nd / nk : 0;
  PetscCall(MatAXPY(K_, 0.5, Kt, UNKNOWN_NONZERO_PATTERN)); /* K + (K^T - K)/2 */
  PetscCall(MatDestroy(&Kt));
  PetscCall(MatSetOption(K_, MAT_SYMMETRIC, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::ToState(Vec x, Vec U) const
{
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(U));
  PetscCall(VecISCopy(U, is_u_, SCATTER_FORWARD, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::FromState(Vec U, Vec x) const
{
  PetscFunctionBeginUser;
  PetscCall(VecISCopy(U, is_u_, SCATTER_REVERSE, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::NormalizeShape(Vec x) const
{
  PetscInt           n;
  PetscReal          big = 0, hi, lo;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArrayRead(x, &a));
  for (PetscInt i = 0; i + 1 < n; i += 2) big = PetscMax(big, std::hypot(PetscRealPart(a[i]), PetscRealPart(a[i + 1])));
  PetscCall(VecRestoreArrayRead(x, &a));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &big, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)x)));
  PetscCall(VecMax(x, NULL, &hi));
  PetscCall(VecMin(x, NULL, &lo));
  if (big > 0) PetscCall(VecScale(x, (hi >= -lo ? 1.0 : -1.0) / big));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CoarseOperators::XFraction(Vec x, PetscReal *fraction) const
{
  Vec         Mx, a, b;
  PetscScalar all, xs;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &Mx));
  PetscCall(MatMult(M_, x, Mx));
  PetscCall(VecDot(x, Mx, &all));
  PetscCall(VecGetSubVector(x, is_x_, &a));
  PetscCall(VecGetSubVector(Mx, is_x_, &b));
  PetscCall(VecDot(a, b, &xs));
  PetscCall(VecRestoreSubVector(Mx, is_x_, &b));
  PetscCall(VecRestoreSubVector(x, is_x_, &a));
  PetscCall(VecDestroy(&Mx));
  *fraction = PetscRealPart(all) > 0 ? PetscRealPart(xs) / PetscRealPart(all) : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
