#pragma once
/* One physics term of the fine-scale model. A scene lists the terms it wants (-physics); a term
   not in the list is never constructed, so it costs nothing: no neighbour lists, no passes. */
#include <turgor/particles/neighbour_search.h>
#include <turgor/particles/particles.h>
#include <petscviewer.h>
#include <string>

namespace turgor {

/* Everything a kernel reads. Positions/velocities are interleaved [2n] arrays. */
struct ForceInput {
  const ParticleSet     *P;
  const PetscReal       *x, *v;
  const NeighbourSearch *nb;
  const PeriodicImages  *images; /* never NULL; all zero shifts unless periodic */
};

/* A stable-time-step bound for explicit integrators, with its reason (for the start-up report). */
struct TimeStepLimit {
  PetscReal   dt = PETSC_MAX_REAL;
  std::string why;
};

class ForceTerm {
public:
  virtual ~ForceTerm() = default;
  virtual const char *Name() const = 0;
  /* Read this term's parameters (one options block with the term's prefix) and validate them. */
  virtual PetscErrorCode SetFromOptions(MPI_Comm comm) = 0;
  /* Precompute per-particle/per-bond data and ask the neighbour search for the lists needed. */
  virtual PetscErrorCode SetUp(const ParticleSet &P, NeighbourSearch &nb) = 0;
  /* f[2n] += forces. If virial is not NULL, virial[4] += -sum_k f_k (x) x_k over this term's
     interactions (row-major, translation invariant), so that sigma = virial / area (TW 562 eq 30). */
  virtual PetscErrorCode AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial) = 0;
  /* Potential energy of the conservative part; *has = PETSC_FALSE if the term has none. */
  virtual PetscErrorCode Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
  {
    *E   = 0;
    *has = PETSC_FALSE;
    return PETSC_SUCCESS;
  }
  /* Stability bounds for an explicit step at the current state (TW 562 eq 40 and bond frequencies). */
  virtual PetscErrorCode AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits) { return PETSC_SUCCESS; }
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
};

} // namespace turgor
