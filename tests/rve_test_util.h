#pragma once
/* What the RVE tests share: a point of a configured RVE material as an RVE (the tests use its
   RVE-only accessors: the cell, the positions). */
#include "test_util.h"
#include <turgor/rve/rve.h>
#include <memory>

namespace turgor_test {

inline PetscErrorCode CreateRVE(const turgor::RVEMaterialBase &material, std::unique_ptr<turgor::RVE> *rve)
{
  std::unique_ptr<turgor::MaterialPoint> point;
  PetscFunctionBeginUser;
  PetscCall(material.CreatePoint(PETSC_COMM_SELF, &point));
  turgor::RVE *r = dynamic_cast<turgor::RVE *>(point.get());
  TG_CHECK(r, "material %s must create RVE points", material.Name());
  point.release();
  rve->reset(r);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor_test
