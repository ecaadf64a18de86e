#pragma once
/* The geometry of an RVE (TW 562 §3.2): one period of the tissue, k x k cells, deformed by the
   coarse F. Particles sit at x = F X + u1 and move with v = Fdot X (the seed's v1 = 0); the corner
   particle (the four RVE corners are one particle under periodicity) is held at F X; interactions
   see the deformed periodic lattice a_i = F A_i, moving with Fdot A_i. The unknowns are
   w = u1 / L of the free particles, L the cell size.

   A polygonal RVE (SetUpPolygons) is K whole cells, each with its own nodes and bars; what crosses
   the box's faces is the cells' contact and glue with their neighbours' images. Those images are
   explicit: copies of the cells near the box (the halo, after the K cells' nodes, bars and
   polygons, as the halo of a distributed run), placed at x_owner + n1 a1 + n2 a2 and returning
   their forces to their owners; the force terms see a plain, non-periodic system (ModelImages) and
   compute each interaction once, from its owned anchor. One node (the first) is held at F X. */
#include <turgor/core/tensor2.h>
#include <turgor/tissue/polygon_tissue.h>
#include <turgor/tissue/square_grid.h>
#include <string>
#include <vector>

namespace turgor {

class PeriodicCell {
public:
  PetscErrorCode SetUp(MPI_Comm comm, const SquareGridSpec &cell, PetscInt cells);
  /* The polygonal cells `rings` in the box [0, period) (periodic_polygons.h), built into nodes and
     bars by `poly`, with the images of every cell whose reference box lies within reach + margin of
     a cell of the box: `reach` is the farthest an interaction goes (the terms' reach plus the
     neighbour skin), `margin` what the deformation may take of it (Admissible). */
  PetscErrorCode SetUpPolygons(MPI_Comm comm, const std::vector<PolygonRing> &rings, const PolygonTissueSpec &poly, const PetscReal period[2], PetscReal reach,
                               PetscReal margin);

  const Tissue                &GetTissue() const { return tissue_; }
  const std::vector<PetscInt> &Free() const { return free_; } /* particle of each unknown pair */
  PetscInt                     NumUnknowns() const { return 2 * (PetscInt)free_.size(); }
  PetscReal                    LengthScale() const { return length_; }
  PetscReal                    ReferenceArea() const { return tissue_.period[0] * tissue_.period[1]; }
  PetscReal                    Mass() const { return mass_; }

  /* The periodic images of the lattice under (F, Fdot). */
  PeriodicImages Lattice(const Tensor2 &F, const Tensor2 &Fdot) const;
  /* What the force terms see: the lattice, or (polygons: the images are explicit) no images. */
  PeriodicImages ModelImages(const Tensor2 &F, const Tensor2 &Fdot) const { return HasHalo() ? PeriodicImages() : Lattice(F, Fdot); }
  /* x = F X and v = Fdot X for every particle (u1 = 0). */
  void Deform(const Tensor2 &F, const Tensor2 &Fdot, PetscReal *x, PetscReal *v) const;
  /* x = F X + L w for the free particles (the others keep their x; the halo follows its owners). */
  void Place(const Tensor2 &F, const PetscScalar *w, PetscReal *x) const;
  /* Polygons: the first owned closed cell whose area at x is not positive, or -1 (always -1 for the
     square grid, whose fluid keeps its cells open). */
  PetscInt InvertedCell(const PetscReal *x) const;
  /* f[owner] += f[image] for the halo (its forces are its owners'); nothing without a halo. */
  void ReturnHaloForces(PetscReal *f) const;
  /* Can the relaxed state at F be the tissue's? Square grid: every fluid particle inside its own
     deformed cell (a relaxation may converge with fluid pushed through a wall after a violent trial
     deformation). Polygons: no cell inverted, and the halo still holds every image within reach
     (the deformation and fluctuation have not used up the margin). Else *why says what. */
  bool Admissible(const PetscReal *x, const Tensor2 &F, const PeriodicImages &images, std::string *why) const;
  /* Polygons: the halo (particles after NumOwned(), each an image of an owned one). */
  bool      HasHalo() const { return !halo_owner_.empty(); }
  PetscReal Reach() const { return reach_; }
  /* Polygons: the Jacobian pattern of the relaxation at positions x: columns (unknown pairs) of each
     unknown pair. Every node of a cell with every other (a cell's turgor couples all its nodes
     through its area; bars and hinges are the cell's own), and every node with the two ends of each
     bar of another cell within reach (contact, glue), an image standing for its owner. */
  void PolygonCouplings(const PetscReal *x, std::vector<std::vector<PetscInt>> &cols) const;

private:
  bool FluidInsideCells(const PetscReal *x, const PeriodicImages &images) const;

  Tissue                tissue_;
  std::vector<PetscInt> free_;
  PetscReal             length_ = 25, mass_ = 0;
  std::vector<PetscInt> halo_owner_; /* [halo particles] the owned particle each copies */
  std::vector<int>      halo_image_; /* [halo particles] its image, PeriodicImages::Index */
  PetscReal             reach_ = 0, margin_ = 0;
};

} // namespace turgor
