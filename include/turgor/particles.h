#pragma once
/* Particle storage for the force kernels: plain structure-of-arrays, free of DMSwarm, so that
   the fine-scale driver (which keeps its record in a DMSwarm) and an RVE (which owns a small
   periodic patch) call the same kernels on their own arrays.

   Positions and velocities are NOT stored here: they are the integrator's state and are passed
   to the kernels as interleaved arrays x[2*i+d], v[2*i+d]. */
#include <turgor/petsc_compat.h>
#include <vector>

namespace turgor {

enum ParticleKind : PetscInt { KIND_WALL = 0, KIND_FLUID = 1 };

/* A wall spring (bonded pair) with its rest length. */
struct Spring {
  PetscInt  i, j;
  PetscReal rest_length;
};

/* Constant per-particle data. Layout is ready for distribution: the first n_owned particles are
   owned by this rank, the rest (none yet) would be halo copies; gid is the global id. */
struct ParticleSet {
  PetscInt               n       = 0; /* local particles (owned + halo) */
  PetscInt               n_owned = 0;
  std::vector<PetscReal> mass;        /* [n] */
  std::vector<PetscInt>  kind;        /* [n] ParticleKind */
  std::vector<PetscInt>  cell;        /* [n] cell id for fluid particles, -1 for walls */
  std::vector<PetscInt>  gid;         /* [n] global id */
  std::vector<char>      fixed;       /* [n] 1 if clamped (position and velocity held) */
  std::vector<Spring>    springs;

  PetscInt Count(ParticleKind k) const
  {
    PetscInt c = 0;
    for (PetscInt i = 0; i < n; i++) c += (kind[i] == k);
    return c;
  }
};

} // namespace turgor
