#pragma once
#include <turgor/core/petsc_compat.h>
#include <petscsys.h>
#include <algorithm>
#include <vector>

namespace turgor {

/* Internal state as numbers (a force term's, a run's), for checkpoints (-checkpoint_interval, -restart): Put
   appends, Get reads back in the same order (indices and flags are stored as reals, exact below
   2^53). A reader that runs out or is left with numbers means a checkpoint of other physics. */
class StateBlob {
public:
  std::vector<PetscReal> data;
  size_t                 pos = 0;
  void                   Put(PetscReal v) { data.push_back(v); }
  void                   Put(const std::vector<PetscReal> &v)
  {
    data.push_back((PetscReal)v.size());
    data.insert(data.end(), v.begin(), v.end());
  }
  void Put(const PetscReal *v, size_t n) /* as a vector of n numbers */
  {
    data.push_back((PetscReal)n);
    data.insert(data.end(), v, v + n);
  }
  bool Get(PetscReal *v)
  {
    if (pos >= data.size()) return false;
    *v = data[pos++];
    return true;
  }
  bool Get(PetscInt *v)
  {
    PetscReal r;
    if (!Get(&r)) return false;
    *v = (PetscInt)r;
    return true;
  }
  bool Get(std::vector<PetscReal> &v)
  {
    PetscReal n;
    if (!Get(&n) || n < 0 || pos + (size_t)n > data.size()) return false;
    v.assign(data.begin() + pos, data.begin() + pos + (size_t)n);
    pos += (size_t)n;
    return true;
  }
  bool Get(PetscReal *v, size_t n) /* a vector that must have n numbers */
  {
    PetscReal m;
    if (!Get(&m) || m != (PetscReal)n || pos + n > data.size()) return false;
    std::copy(data.begin() + pos, data.begin() + pos + n, v);
    pos += n;
    return true;
  }
  bool Done() const { return pos == data.size(); }
};

} // namespace turgor
