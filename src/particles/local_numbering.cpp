#include <turgor/particles/local_numbering.h>

namespace turgor {

LocalNumbering::LocalNumbering(const ParticleSet &P)
{
  particle_.reserve((size_t)P.n);
  for (PetscInt i = 0; i < P.n; i++) particle_.emplace(P.gid[i], i);
  spring_.reserve(P.springs.size());
  for (size_t s = 0; s < P.springs.size(); s++) spring_.emplace(P.SpringGid(s), (PetscInt)s);
  polygon_.reserve(P.polygons.size());
  for (size_t c = 0; c < P.polygons.size(); c++) polygon_.emplace(P.PolygonGid(c), (PetscInt)c);
}

} // namespace turgor
