#pragma once
/* The coarse model's linearised operators on its free displacements, for eigen analysis: at a
   state U = [u; v] of the CoarseModel,
     K = d f_int / d u  (initial-stress and constitutive parts, from the material points' D^e),
     C = d f_int / d v  (from D^v; only when asked),
     M = the mass matrix (consistent or lumped, -coarse_lumped_mass),
   each the block of the free (unclamped) vertices' displacement dofs: the clamped vertices are
   constrained dofs of the model's section, absent from its global system, so the blocks carry the
   scene's essential conditions. They are extracted from the model's own assembly (the [[0, -I],
   [K, C]] of CoarseModel::AssembleTangentAt and diag(I, M)) by MatCreateSubMatrix on the free
   velocity rows (where f_int - f_ext lives) and the free displacement / velocity columns, vertex by
   vertex in the same order, so row i and column i are the same dof.

   K is symmetric for a hyperelastic material; the material points' tangents are finite differences
   (eqs 46-53), so the assembled K is symmetric only to their accuracy. Symmetrize() replaces K by
   (K + K^T)/2 (the eigenproblem is then a symmetric-definite GHEP) and keeps ||K - K^T||_F /
   ||K||_F for the report. */
#include <turgor/coarse/coarse_model.h>
#include <string>

namespace turgor {

class CoarseOperators {
public:
  explicit CoarseOperators(CoarseModel &model) : model_(model) { }
  ~CoarseOperators();
  CoarseOperators(const CoarseOperators &)            = delete;
  CoarseOperators &operator=(const CoarseOperators &) = delete;

  /* After the model's SetUp: the index sets, the mass block. */
  PetscErrorCode SetUp();
  /* K (and C when damping) at the model state U. *ok = false when a material point failed (*why
     says where): K, C are then not valid. The material points are evaluated for output: a run
     analysed in passing is not changed. */
  PetscErrorCode Assemble(Vec U, bool damping, PetscBool *ok, std::string *why);
  /* K <- (K + K^T)/2; Asymmetry() the relative size of what was removed. */
  PetscErrorCode Symmetrize();

  Mat       K() const { return K_; }
  Mat       C() const { return C_; }
  Mat       M() const { return M_; }
  PetscReal Asymmetry() const { return asymmetry_; }
  PetscInt  Size() const { return size_; } /* global number of free displacement dofs */
  /* vectors of K's layout */
  PetscErrorCode CreateVector(Vec *x) const { return MatCreateVecs(M_, x, NULL); }
  /* x (free displacements) into the displacement part of a model state U, v = 0; and back */
  PetscErrorCode ToState(Vec x, Vec U) const;
  PetscErrorCode FromState(Vec U, Vec x) const;
  /* x scaled to a mode shape for output: largest vertex displacement 1 (µm), its largest entry in
     modulus positive (the same shape on any number of ranks) */
  PetscErrorCode NormalizeShape(Vec x) const;
  /* the share of x^T M x in the x components (M couples no two directions) */
  PetscErrorCode XFraction(Vec x, PetscReal *fraction) const;

private:
  CoarseModel &model_;
  Mat          J_ = nullptr, K_ = nullptr, C_ = nullptr, M_ = nullptr;
  IS           is_u_ = nullptr, is_v_ = nullptr, is_x_ = nullptr; /* is_x_: the ux dofs of K's layout */
  PetscReal    asymmetry_ = 0;
  PetscInt     size_      = 0;
  bool         have_C_    = false;
};

} // namespace turgor
