#pragma once
/* The fine-scale force model: the physics terms a scene enables (-physics), one neighbour search
   shared by them, and the evaluation of forces / accelerations on plain arrays. Used by the full
   fine-scale run and (later) by the RVE, which calls it on its own periodic patch. */
#include <turgor/particles/neighbour_search.h>
#include <turgor/physics/force_term.h>
#include <memory>
#include <string>
#include <vector>

namespace turgor {

/* Names accepted by -physics, in evaluation order. */
const std::vector<std::string> &KnownPhysicsTerms();
/* Create a term by name; an unknown name is an error naming `option` and the known names. */
PetscErrorCode CreateForceTerm(MPI_Comm comm, const std::string &name, const char *option, std::unique_ptr<ForceTerm> *term);

class ForceModel {
public:
  /* Reads -physics (comma-separated term names; default: all) and each term's own options. Terms
     named in `skip` are not constructed even if listed (an RVE skips the body force, a load). */
  PetscErrorCode SetFromOptions(MPI_Comm comm, const std::vector<std::string> &skip = {});
  /* Add a term programmatically (tests); call before SetUp. */
  void           AddTerm(std::unique_ptr<ForceTerm> term) { terms_.push_back(std::move(term)); }
  PetscErrorCode SetUp(const ParticleSet &P);

  /* f[2n] = sum of all terms' forces; virial[4] (may be NULL) = -sum f_k (x) x_k of internal forces. */
  PetscErrorCode ComputeForces(const PetscReal *x, const PetscReal *v, PetscReal *f, PetscReal *virial);
  /* a[2n] = f / m, zero for fixed particles (whose flags are read at SetUp). */
  PetscErrorCode ComputeAcceleration(const PetscReal *x, const PetscReal *v, PetscReal *a);
  /* Sum of the conservative terms' energies; *complete = PETSC_FALSE if some active term has none. */
  PetscErrorCode PotentialEnergy(const PetscReal *x, PetscReal *E, PetscBool *complete);
  /* Stability bounds of an explicit step at state (x, v): every term's, plus eq 40's force bound. */
  PetscErrorCode TimeStepLimits(const PetscReal *x, const PetscReal *v, std::vector<TimeStepLimit> &limits);

  std::vector<std::string> ActiveTerms() const;
  ForceTerm               *Term(const std::string &name) const;
  NeighbourSearch         &Neighbours() { return nb_; }
  const NeighbourSearch   &Neighbours() const { return nb_; }
  /* Periodic lattice for RVEs (positions and rates of the image shifts); default: not periodic. */
  void                     SetPeriodicImages(const PeriodicImages &images) { images_ = images; }
  const PeriodicImages    &Images() const { return images_; }
  PetscInt                 Evaluations() const { return evaluations_; }
  PetscErrorCode           View(PetscViewer viewer) const;

private:
  const ParticleSet                      *P_ = nullptr;
  std::vector<std::unique_ptr<ForceTerm>> terms_;
  std::vector<PetscLogEvent>              events_;
  NeighbourSearch                         nb_;
  PeriodicImages                          images_;
  std::vector<PetscReal>                  inv_mass_; /* 0 for fixed particles */
  PetscInt                                evaluations_ = 0;
  PetscLogEvent                           ev_forces_ = 0, ev_neighbours_ = 0;
};

} // namespace turgor
