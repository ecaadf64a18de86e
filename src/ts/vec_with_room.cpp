/* TurgorVecDuplicateWithRoom (ts_types_internal.h): work vectors of turgor's TS types with scratch room. */
#include <turgor/core/petsc_compat.h>
#include "ts_types_internal.h"

PetscErrorCode TurgorVecDuplicateWithRoom(Vec U, PetscInt room, Vec *R, PetscScalar **array)
{
  PetscInt n, N, bs, any_room = room;
  PetscFunctionBeginUser;
  *array = NULL;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any_room, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)U)));
  if (!any_room) {
    PetscCall(VecDuplicate(U, R));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecGetLocalSize(U, &n));
  PetscCall(VecGetSize(U, &N));
  PetscCall(VecGetBlockSize(U, &bs));
  PetscCall(PetscCalloc1(n + room, array));
  PetscCall(VecCreateMPIWithArray(PetscObjectComm((PetscObject)U), bs, n, N, *array, R));
  PetscFunctionReturn(PETSC_SUCCESS);
}
