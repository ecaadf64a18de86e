#pragma once
/* The per-particle fields of a fine run, each declared once, by name, by the object that owns it,
   with where it goes:
   - Halo: copied from its owner to the neighbouring ranks' halo copies before every force
     evaluation (the model reads it on every local particle);
   - Snapshot: written in every snapshot (in particle-id order, with its unit);
   - Checkpoint: a column of the checkpoint's particle table (read back on any rank count).
   A field's values are this rank's particles', owned first (the halo's after them for a halo
   field), `components` per particle, found through `values` when they are used (a field may live
   in a work array that moves, or be computed for a snapshot). */
#include <petscsys.h>
#include <deque>
#include <functional>
#include <string>
#include <vector>

namespace turgor {

enum ParticleFieldUse : unsigned {
  kHalo       = 1u,
  kSnapshot   = 2u,
  kCheckpoint = 4u,
};

struct ParticleField {
  std::string                  name, unit;
  int                          components = 2;
  unsigned                     uses       = 0;
  std::function<PetscReal *()> values; /* the current values (owned first) */
};

class ParticleFields {
public:
  /* A second declaration of a name replaces the first (a scene's set-up may declare again). */
  void Declare(const std::string &name, const std::string &unit, int components, unsigned uses, std::function<PetscReal *()> values)
  {
    for (ParticleField &f : fields_)
      if (f.name == name) {
        f = {name, unit, components, uses, std::move(values)};
        return;
      }
    fields_.push_back({name, unit, components, uses, std::move(values)});
  }
  /* The fields with this use, in the order declared (their addresses stay valid). */
  std::vector<const ParticleField *> With(ParticleFieldUse use) const
  {
    std::vector<const ParticleField *> out;
    for (const ParticleField &f : fields_)
      if (f.uses & use) out.push_back(&f);
    return out;
  }

private:
  std::deque<ParticleField> fields_; /* a deque: the fields' addresses stay while more are declared */
};

} // namespace turgor
