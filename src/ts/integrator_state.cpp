/* Integrator history for checkpoints (include/turgor/ts/integrator_state.h). */
#include <turgor/ts/integrator_state.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/adapt_dsp.h>
#include <turgor/ts/low_storage_rk.h>
#include <turgor/ts/radau_iia.h>
#include <turgor/ts/velocity_verlet.h>
#include <petsc/private/tsimpl.h> /* the controller's step-increase delay, the rejections: no public setter */

namespace turgor {

PetscErrorCode TSIsExplicit(TS ts, PetscBool *is)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts, is, TSRK, TSEULER, TSSSP, TSBASICSYMPLECTIC, TSVERLET, TSLSRK, TSAM, ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAdaptGetTypeAndNorm(TS ts, TSAdaptType *type, NormType *norm)
{
  TSAdapt adapt;
  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, type));
  *norm = adapt->wnormtype;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointSupported(TS ts, PetscBool *supported, const char **why)
{
  PetscBool ok, is;
  PetscFunctionBeginUser;
  PetscCall(TSIsExplicit(ts, &ok));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSAM, &is));
  ok         = (PetscBool)(ok && !is); /* Adams-Moulton carries its steps' history */
  *supported = ok;
  *why       = "";
  if (ok) PetscFunctionReturn(PETSC_SUCCESS);
  /* what each refused type carries between steps besides the solution and the step size */
  static const struct {
    const char *type, *why;
  } refused[] = {
    {TSAM,       "-ts_type am (Adams-Moulton) keeps several steps of history"                                                                       },
    {TSBDF,      "-ts_type bdf keeps the previous solutions (-ts_bdf_order of them, and order 1 too for its Newton start by extrapolation)"         },
    {TSRADAUIIA,
     "-ts_type radauiia carries its collocation polynomial (the next Newton start), the Jacobian and its factors, and its step controller's history"},
    {TSARKIMEX,  "-ts_type arkimex carries its last stage derivative and its Newton start from step to step"                                        },
  };
  *why = "this -ts_type carries more than the solution and the step size from step to step";
  for (const auto &r : refused) {
    PetscCall(PetscObjectTypeCompare((PetscObject)ts, r.type, &is));
    if (is) *why = r.why;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

IntegratorState::~IntegratorState()
{
  PetscCallVoid(VecDestroy(&pending_));
}

PetscErrorCode IntegratorState::KindOf(TS ts, Kind *kind)
{
  PetscBool is;
  PetscFunctionBeginUser;
  *kind = NONE;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSVERLET, &is));
  if (is) *kind = VERLET;
  PetscCall(PetscObjectTypeCompare((PetscObject)ts, TSRK, &is));
  if (is) {
    PetscBool fsal;
    PetscCall(TSRKGetTableau(ts, NULL, NULL, NULL, NULL, NULL, NULL, NULL, &fsal));
    if (fsal) *kind = FSAL;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IntegratorState::ObserveRHS(TS ts, PetscReal t, Vec U, Vec F, PetscBool *answered)
{
  PetscInt ns;
  Vec     *Y;
  PetscFunctionBeginUser;
  *answered = PETSC_FALSE;
  if (!ts) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TSGetStages(ts, &ns, &Y));
  if (ns < 1 || !Y) PetscFunctionReturn(PETSC_SUCCESS);
  if (pending_ && U == Y[0] && t == t_pending_) { /* the restart's first stage: the derivative its step would have carried */
    PetscCall(VecCopy(pending_, F));
    PetscCall(VecDestroy(&pending_));
    *answered = PETSC_TRUE;
  } else if (U == Y[ns - 1]) fsal_ = F;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IntegratorState::Declare(TS ts, StateDeclaration &d, const KeepVector &keep)
{
  Kind    kind;
  TSAdapt adapt;
  PetscFunctionBeginUser;
  PetscCall(KindOf(ts, &kind));
  PetscCall(TSGetStepRejections(ts, &rejections_));
  d.Scalar("rejections", &rejections_, Combine::Owner);
  PetscCall(TSGetAdapt(ts, &adapt));
  d.Scalar("adapt_increase_delay", &adapt->timestepjustdecreased, Combine::Owner);
  {
    PetscBool  dsp;
    PetscReal *cerror, *hratio;
    PetscBool *rollback;
    PetscCall(TSAdaptDSPGetHistory(adapt, &dsp, &cerror, &hratio, &rollback));
    if (dsp) {
      d.Array("dsp_control_errors", cerror, 3, Combine::Owner);
      d.Array("dsp_step_ratios", hratio, 3, Combine::Owner);
      d.Scalar("dsp_rollback", rollback, Combine::Owner);
    }
  }
  Vec H = NULL;
  if (kind == VERLET) {
    PetscBool have;
    PetscCall(TSVerletGetLastAcceleration(ts, &H, &have));
  } else if (kind == FSAL) {
    if (fsal_) H = fsal_;
    else PetscCall(TSGetSolution(ts, &H)); /* (a restart: only the layout, which the derivative shares) */
  }
  history_.clear();
  if (H) {
    const PetscScalar *h;
    PetscInt           n, N;
    PetscCall(VecGetLocalSize(H, &n));
    PetscCall(VecGetSize(H, &N));
    PetscCall(VecGetArrayRead(H, &h));
    history_.assign(h, h + n);
    PetscCall(VecRestoreArrayRead(H, &h));
    if (!(keep && keep(history_, N))) d.Table("history", StateEntity::StateEntry).Rows([this] { return history_.size(); }).Column("value", history_);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode IntegratorState::Restore(TS ts)
{
  Kind    kind;
  TSAdapt adapt;
  PetscFunctionBeginUser;
  PetscCall(KindOf(ts, &kind));
  ts->reject = rejections_;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptDSPSetRestored(adapt));
  if (kind == VERLET) {
    Vec       A, H;
    PetscBool have;
    PetscCall(TSVerletGetLastAcceleration(ts, &A, &have));
    PetscCall(VecDuplicate(A, &H));
    PetscCall(VecPlaceArray(H, history_.data()));
    PetscCall(TSVerletSetLastAcceleration(ts, H));
    PetscCall(VecResetArray(H));
    PetscCall(VecDestroy(&H));
  } else if (kind == FSAL) {
    Vec U;
    PetscCall(TSGetSolution(ts, &U));
    PetscCall(VecDestroy(&pending_));
    PetscCall(VecDuplicate(U, &pending_));
    PetscCall(VecPlaceArray(pending_, history_.data()));
    Vec copy;
    PetscCall(VecDuplicate(U, &copy));
    PetscCall(VecCopy(pending_, copy));
    PetscCall(VecResetArray(pending_));
    PetscCall(VecDestroy(&pending_));
    pending_ = copy;
    PetscCall(TSGetTime(ts, &t_pending_));
  }
  std::vector<PetscReal>().swap(history_);
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
