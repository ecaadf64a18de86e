#include <turgor/core/log.h>

namespace turgor {

PetscErrorCode RegisterLogStage(const char *name, PetscLogStage *stage)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogStageGetId(name, stage));
  if (*stage < 0) PetscCall(PetscLogStageRegister(name, stage));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
