#pragma once
/* The geometry of an RVE (TW 562 §3.2): one period of the tissue, k x k cells, deformed by the
   coarse F. Particles sit at x = F X + u1 and move with v = Fdot X (the seed's v1 = 0); the corner
   particle (the four RVE corners are one particle under periodicity) is held at F X; interactions
   see the deformed periodic lattice a_i = F A_i, moving with Fdot A_i. The unknowns are
   w = u1 / L of the free particles, L the cell size. */
#include <turgor/core/tensor2.h>
#include <turgor/tissue/square_grid.h>
#include <vector>

namespace turgor {

class PeriodicCell {
public:
  PetscErrorCode SetUp(MPI_Comm comm, const SquareGridSpec &cell, PetscInt cells);

  const Tissue                &GetTissue() const { return tissue_; }
  const std::vector<PetscInt> &Free() const { return free_; } /* particle of each unknown pair */
  PetscInt                     NumUnknowns() const { return 2 * (PetscInt)free_.size(); }
  PetscReal                    LengthScale() const { return length_; }
  PetscReal                    ReferenceArea() const { return tissue_.period[0] * tissue_.period[1]; }
  PetscReal                    Mass() const { return mass_; }

  /* The periodic images of the lattice under (F, Fdot). */
  PeriodicImages Lattice(const Tensor2 &F, const Tensor2 &Fdot) const;
  /* x = F X and v = Fdot X for every particle (u1 = 0). */
  void Deform(const Tensor2 &F, const Tensor2 &Fdot, PetscReal *x, PetscReal *v) const;
  /* x = F X + L w for the free particles (the others keep their x). */
  void Place(const Tensor2 &F, const PetscScalar *w, PetscReal *x) const;
  /* Every fluid particle inside its own deformed cell polygon (a relaxation may converge to a state
     with fluid pushed through a wall after a violent trial deformation: one the tissue cannot reach). */
  bool FluidInsideCells(const PetscReal *x, const PeriodicImages &images) const;

private:
  Tissue                tissue_;
  std::vector<PetscInt> free_;
  PetscReal             length_ = 25, mass_ = 0;
};

} // namespace turgor
