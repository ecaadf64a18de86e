/* Integrator history for checkpoints (include/turgor/ts/ts_checkpoint.h). */
#include <turgor/ts/ts_checkpoint.h>
#include <turgor/ts/velocity_verlet.h>
#include <petsc/private/tsimpl.h>

namespace {

/* The leading members of PETSc 3.18's TS_RK (src/ts/impls/explicit/rk/rk.h, not installed): the
   tableau, the step's start X0, the stage states Y and their derivatives YdotRHS. The layout is checked at run time
   against TSGetStages (which returns Y), so a PETSc whose TS_RK differs is refused, not misread. */
struct RKHead {
  void *tableau;
  Vec   X0;
  Vec  *Y;
  Vec  *YdotRHS;
};

/* The FSAL derivative of an RK TS: its Vec, or NULL when the tableau is not FSAL. */
PetscErrorCode RKFsalVec(TS ts, Vec *H)
{
  PetscInt  s, ns;
  PetscBool fsal;
  Vec      *Y;
  PetscFunctionBeginUser;
  *H = NULL;
  PetscCall(TSRKGetTableau(ts, &s, NULL, NULL, NULL, NULL, NULL, NULL, &fsal));
  if (!fsal) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSGetStages(ts, &ns, &Y));
  const RKHead *rk = (const RKHead *)ts->data;
  PetscCheck(rk && rk->Y == Y && ns == s && rk->YdotRHS, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
             "Checkpoints of -ts_type rk with an FSAL tableau need PETSc 3.18's TS_RK layout, which this PETSc does not have: use -ts_rk_type 5f or rk4");
  *H = rk->YdotRHS[s - 1];
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct Restored {
  PetscBool pending = PETSC_FALSE;
};

} // namespace

PetscErrorCode TSCheckpointSupported(TS ts, PetscBool *supported, const char **why)
{
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts, &ok, TSRK, TSEULER, TSSSP, TSBASICSYMPLECTIC, TSVERLET, ""));
  *supported = ok;
  *why       = ok
               ? ""
               : "only one-step explicit integrators (rk, euler, ssp, basicsymplectic, verlet) are checkpointed; multistep ones (am) keep several steps of history";
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointGetHistory(TS ts, Vec *H)
{
  PetscBool is_rk, is_verlet;
  PetscFunctionBeginUser;
  *H = NULL;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is_rk));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is_verlet));
  if (is_rk) PetscCall(RKFsalVec(ts, H));
  else if (is_verlet) {
    PetscBool have;
    PetscCall(TSVerletGetLastAcceleration(ts, H, &have));
    if (!have) *H = NULL;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointHistorySize(TS ts, PetscInt *n)
{
  PetscBool is_rk, is_verlet;
  Vec       H = NULL;
  PetscFunctionBeginUser;
  *n = 0;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is_rk));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is_verlet));
  if (is_rk) PetscCall(RKFsalVec(ts, &H));
  else if (is_verlet) {
    PetscBool have;
    PetscCall(TSVerletGetLastAcceleration(ts, &H, &have));
  }
  if (H) PetscCall(VecGetLocalSize(H, n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointSetHistory(TS ts, Vec H)
{
  PetscBool is_rk, is_verlet;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is_rk));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is_verlet));
  if (is_verlet) PetscCall(TSVerletSetLastAcceleration(ts, H));
  else if (is_rk) {
    Vec F;
    PetscCall(RKFsalVec(ts, &F));
    if (F) {
      PetscCall(VecCopy(H, F));
      PetscContainer c;
      Restored      *r = new Restored();
      r->pending       = PETSC_TRUE;
      PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ts), &c));
      PetscCall(PetscContainerSetPointer(c, r));
      PetscCall(PetscContainerSetUserDestroy(c, [](void *p) -> PetscErrorCode {
        delete (Restored *)p;
        return PETSC_SUCCESS;
      }));
      PetscCall(PetscObjectCompose((PetscObject)ts, "TurgorCheckpointFSAL", (PetscObject)c));
      PetscCall(PetscContainerDestroy(&c));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The first step after a restore: the TS would restart (discard the FSAL derivative) because
   TSSolve begins; keep it, as the uninterrupted run does. */
PetscErrorCode TSCheckpointPreStep(TS ts)
{
  PetscContainer c;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)ts, "TurgorCheckpointFSAL", (PetscObject *)&c));
  if (!c) PetscFunctionReturn(PETSC_SUCCESS);
  Restored *r;
  PetscCall(PetscContainerGetPointer(c, (void **)&r));
  if (r->pending) {
    ts->steprestart = PETSC_FALSE;
    r->pending      = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointSetRejections(TS ts, PetscInt rejections)
{
  PetscFunctionBeginUser;
  ts->reject = rejections;
  PetscFunctionReturn(PETSC_SUCCESS);
}
