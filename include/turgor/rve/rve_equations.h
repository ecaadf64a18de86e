#pragma once
/* The equations of a deformed RVE: G(w) = -f_free(x(w)) / force_scale, the scaled forces on its
   free particles (TW 562 eq 27), the virial of all internal forces (eq 30), and the interaction
   graph that gives the sparsity of G'. Rank 0 of the RVE's communicator holds the unknowns and
   computes; the other ranks of the group own none (they join the linear algebra).

   The last evaluation is kept: it is identified by the input vector's id and PETSc object state and
   by the version of the deformation, so TSPSEUDO, the stopping tests and the stress asking again
   for an unchanged W cost nothing. */
#include <turgor/physics/force_model.h>
#include <turgor/rve/periodic_cell.h>
#include <petscvec.h>

namespace turgor {

class RVEEquations {
public:
  PetscErrorCode SetUp(MPI_Comm comm, const PeriodicCell &cell, const PhysicsSpec &physics, PetscReal fluid_density);
  /* x = F X, v = Fdot X, the lattice a_i = F A_i; invalidates the kept evaluation. */
  void SetDeformation(const Tensor2 &F, const Tensor2 &Fdot);
  /* R = G(W) (R may be NULL). */
  PetscErrorCode Residual(Vec W, Vec R);
  /* ||G(W)||_2 with G(W) left in R (collective). */
  PetscErrorCode ResidualNorm(Vec W, Vec R, PetscReal *norm);
  /* The virial [4] of all internal forces at W (rank 0; zero elsewhere). */
  PetscErrorCode Virial(Vec W, PetscReal virial[4]);
  /* Columns (unknown pairs) coupled to each unknown pair: particles interacting directly (springs,
     particle-spring pairs with both spring ends, fluid pairs), closed over two hops because the
     SPH force on i depends on its neighbours' densities and correction matrices. */
  PetscErrorCode PatternColumns(std::vector<std::vector<PetscInt>> &cols) const;
  PetscInt       NeighbourRebuilds() const { return model_.Neighbours().Rebuilds(); }
  /* The particle positions of the last evaluation (all particles), and whether that state can be
     the tissue's (PeriodicCell::Admissible; *why says why not). */
  const std::vector<PetscReal> &Positions() const { return x_; }
  bool                          Admissible(std::string *why) const;
  /* History: the terms' internal state (plastic hinges, contact springs, glue bonds) updated at the
     relaxed state W of the current deformation (an accepted coarse step: rank 0 of the group), and
     that state declared apart, so that an RVE can keep its committed copy and go back to it. */
  bool                       HasHistory() const { return model_.HasInternalState(); }
  PetscErrorCode             AcceptStep(Vec W);
  void                       DeclareTermState(StateDeclaration &d);
  PetscErrorCode             AfterTermStateRead();
  const PeriodicCell        &Cell() const { return *cell_; }
  PetscInt                   ForceEvaluations() const { return force_evals_; }
  std::vector<TermStatistic> TermStatistics() const { return model_.Statistics(); }
  PetscMPIInt                Rank() const { return rank_; }
  /* Declared state: the neighbour lists (the positions and the lattice they were last built at, so
     that a restored RVE rebuilds them when the uninterrupted one does and visits its pairs in the
     same order) and the force count. AfterStateRead leaves the deformation at the identity. */
  void           DeclareState(StateDeclaration &d);
  PetscErrorCode AfterStateRead();

private:
  PetscErrorCode Compute(Vec W); /* forces and virial at W unless kept */

  const PeriodicCell      *cell_ = nullptr;
  PetscMPIInt              rank_ = 0;
  ForceModel               model_;
  Tensor2                  F_, Fdot_;
  Tensor2                  build_F_ = Tensor2::Identity(), build_Fdot_ = Tensor2::Zero(); /* the deformation of the lists' last build */
  std::vector<PetscReal>   x_, v_, f_;
  std::vector<PetscScalar> r_; /* G of the kept evaluation */
  PetscReal                virial_[4]   = {0, 0, 0, 0};
  PetscReal                force_scale_ = 1;
  /* what the kept evaluation was computed from */
  PetscObjectId    kept_id_    = 0;
  PetscObjectState kept_state_ = -1;
  PetscInt         version_ = 0, kept_version_ = -1;
  PetscInt         force_evals_ = 0;
};

} // namespace turgor
