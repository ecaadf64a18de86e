#pragma once
/* This rank's numbers of the tissue's particles, springs and polygons (ParticleSet gid, spring_gid,
   polygon_gid inverted). A restart on another number of ranks reads the terms' internal state as
   records in the tissue's numbering, which every rank translates into its own. */
#include <turgor/particles/particles.h>
#include <unordered_map>

namespace turgor {

class LocalNumbering {
public:
  explicit LocalNumbering(const ParticleSet &P);
  /* the local number, or -1 where the particle (spring, polygon) is not on this rank */
  PetscInt Particle(PetscInt gid) const { return Find(particle_, gid); }
  PetscInt Spring(PetscInt gid) const { return Find(spring_, gid); }
  PetscInt Polygon(PetscInt gid) const { return Find(polygon_, gid); }

private:
  static PetscInt Find(const std::unordered_map<PetscInt, PetscInt> &m, PetscInt g)
  {
    auto it = m.find(g);
    return it == m.end() ? -1 : it->second;
  }
  std::unordered_map<PetscInt, PetscInt> particle_, spring_, polygon_;
};

} // namespace turgor
