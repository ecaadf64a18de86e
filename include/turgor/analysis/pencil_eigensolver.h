#pragma once
/* Eigenvalues of the symmetric-definite pencil (K, M) of the coarse operators (analysis/
   coarse_operators.h), K phi = lambda M phi with lambda = omega^2 [1/µs^2], by SLEPc's EPS as a GHEP
   (Krylov-Schur; phi M-orthogonal):
     Lowest   the eigenvalues nearest a target (0 by default) by shift-and-invert (ST sinvert, the
              shifted K factored by MUMPS's symmetric LDL^T, which takes an indefinite K: the sign of
              the lowest eigenvalues tells whether K is positive definite);
     Largest  the largest eigenvalue (ST shift: M factored, the same MUMPS Cholesky), omega_max^2.
   Defaults are set through the API before EPSSetFromOptions, so the user's options win under the
   solver's prefix: -<prefix>eps_* (nev, tol, type, target, ...), -<prefix>st_* (type, shift,
   -<prefix>st_pc_factor_mat_solver_type, ...). */
#include <turgor/analysis/coarse_operators.h>
#include <slepceps.h>
#include <string>
#include <vector>

namespace turgor {

/* A spectral transformation of `type` whose linear solves are one direct factorisation (KSPPREONLY,
   `factor` = PCCHOLESKY or PCLU, by MUMPS on any number of ranks); defaults, options win. */
PetscErrorCode SetDirectST(ST st, STType type, PCType factor);
/* "krylovschur, sinvert, preonly + cholesky (mumps)": a method, its spectral transformation and its
   linear solver, for reports */
PetscErrorCode DescribeSolver(const char *method, ST st, std::string *text);

enum class PencilEnd {
  Lowest,
  Largest
};

/* One converged eigenpair, with what tells it apart. */
struct Eigenpair {
  PetscReal lambda     = 0; /* omega^2 [1/µs^2] */
  PetscReal residual   = 0; /* backward error |K phi - lambda M phi|_2 / ((|K|_inf + |lambda| |M|_inf) |phi|_2) (SLEPc's) */
  PetscReal x_fraction = 0; /* share of phi^T M phi in the x displacements (1: axial, 0: transverse in x) */
};

class PencilEigensolver {
public:
  explicit PencilEigensolver(MPI_Comm comm) : comm_(comm) { }
  ~PencilEigensolver();
  PencilEigensolver(const PencilEigensolver &)            = delete;
  PencilEigensolver &operator=(const PencilEigensolver &) = delete;

  /* Creates the EPS with its defaults (nev eigenpairs, tolerance tol) and reads -<prefix>eps_*. */
  PetscErrorCode SetFromOptions(const std::string &prefix, PencilEnd end, PetscInt nev, PetscReal tol);
  /* Solve for ops's K (symmetrized) and M. The pairs are sorted by lambda, ascending; a failure to
     converge leaves fewer pairs than requested (Requested()), not an error. */
  PetscErrorCode                Solve(const CoarseOperators &ops);
  const std::vector<Eigenpair> &Pairs() const { return pairs_; }
  /* The eigenvector of Pairs()[i] (M-normalised: phi^T M phi = 1). */
  PetscErrorCode GetVector(PetscInt i, Vec x) const;
  PetscInt       Requested() const;
  PetscInt       Iterations() const { return its_; }
  PetscReal      SolveTime() const { return solve_time_; }
  /* "krylovschur, sinvert, preonly + cholesky (mumps)", for reports */
  std::string Description() const { return description_; }
  EPS         GetEPS() const { return eps_; }

private:
  MPI_Comm               comm_;
  EPS                    eps_ = nullptr;
  std::vector<Eigenpair> pairs_;
  std::vector<PetscInt>  order_; /* EPS index of each sorted pair */
  PetscInt               its_        = 0;
  PetscReal              solve_time_ = 0;
  std::string            description_;
  PetscLogEvent          ev_solve_ = 0;
};

} // namespace turgor
