#include <turgor/rve/periodic_cell.h>

namespace turgor {

PetscErrorCode PeriodicCell::SetUp(MPI_Comm comm, const SquareGridSpec &cell, PetscInt cells)
{
  SquareGridSpec spec = cell;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = cells;
  PetscCall(GeneratePeriodicSquareGridTissue(comm, spec, &tissue_));
  const ParticleSet &P = tissue_.particles;
  free_.clear();
  for (PetscInt i = 0; i < P.n; i++)
    if (!P.fixed[i]) free_.push_back(i);
  length_ = spec.cell_size;
  mass_   = 0;
  for (PetscReal m : P.mass) mass_ += m;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PeriodicImages PeriodicCell::Lattice(const Tensor2 &F, const Tensor2 &Fdot) const
{
  const PetscReal A1[2] = {tissue_.period[0], 0}, A2[2] = {0, tissue_.period[1]};
  PetscReal       a1[2], a2[2], va1[2], va2[2];
  PeriodicImages  images;
  F.Apply(A1, a1);
  F.Apply(A2, a2);
  Fdot.Apply(A1, va1);
  Fdot.Apply(A2, va2);
  images.Set(a1, a2, va1, va2);
  return images;
}

void PeriodicCell::Deform(const Tensor2 &F, const Tensor2 &Fdot, PetscReal *x, PetscReal *v) const
{
  for (PetscInt i = 0; i < tissue_.particles.n; i++) {
    F.Apply(&tissue_.X[2 * i], &x[2 * i]);
    Fdot.Apply(&tissue_.X[2 * i], &v[2 * i]);
  }
}

void PeriodicCell::Place(const Tensor2 &F, const PetscScalar *w, PetscReal *x) const
{
  for (size_t k = 0; k < free_.size(); k++) {
    const PetscInt i = free_[k];
    PetscReal      X[2];
    F.Apply(&tissue_.X[2 * i], X);
    x[2 * i]     = X[0] + length_ * w[2 * k];
    x[2 * i + 1] = X[1] + length_ * w[2 * k + 1];
  }
}

bool PeriodicCell::FluidInsideCells(const PetscReal *x, const PeriodicImages &images) const
{
  const ParticleSet &P = tissue_.particles;
  for (PetscInt p = 0; p < P.n; p++) {
    if (P.kind[p] != KIND_FLUID) continue;
    const auto     &ring = tissue_.cell_walls[P.cell[p]];
    const auto     &img  = tissue_.cell_wall_images[P.cell[p]];
    const PetscReal px = x[2 * p], py = x[2 * p + 1];
    bool            in = false; /* crossing-number test */
    for (size_t e = 0, n = ring.size(); e < n; e++) {
      const size_t    f  = (e + 1) % n;
      const PetscReal ax = x[2 * ring[e]] + images.x[img[e]][0], ay = x[2 * ring[e] + 1] + images.x[img[e]][1];
      const PetscReal bx = x[2 * ring[f]] + images.x[img[f]][0], by = x[2 * ring[f] + 1] + images.x[img[f]][1];
      if ((ay > py) != (by > py) && px < ax + (py - ay) * (bx - ax) / (by - ay)) in = !in;
    }
    if (!in) return false;
  }
  return true;
}

} // namespace turgor
