/* Integrator history for checkpoints (include/turgor/ts/ts_checkpoint.h). */
#include <turgor/ts/ts_checkpoint.h>
#include <turgor/ts/adams_moulton.h>
#include <turgor/ts/radau_iia.h>
#include <turgor/ts/velocity_verlet.h>
#include <petsc/private/tsimpl.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>

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
  PetscBool ok, is;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)ts, &ok, TSRK, TSEULER, TSSSP, TSBASICSYMPLECTIC, TSVERLET, ""));
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

/* The first step after a restore keeps what was restored (TSCheckpointPreStep). */
static PetscErrorCode MarkRestored(TS ts)
{
  PetscContainer c;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)ts, "TurgorCheckpointRestored", (PetscObject *)&c));
  if (c) {
    Restored *r;
    PetscCall(PetscContainerGetPointer(c, (void **)&r));
    r->pending = PETSC_TRUE;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  Restored *r = new Restored();
  r->pending  = PETSC_TRUE;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ts), &c));
  PetscCall(PetscContainerSetPointer(c, r));
  PetscCall(PetscContainerSetUserDestroy(c, [](void *p) -> PetscErrorCode {
    delete (Restored *)p;
    return PETSC_SUCCESS;
  }));
  PetscCall(PetscObjectCompose((PetscObject)ts, "TurgorCheckpointRestored", (PetscObject)c));
  PetscCall(PetscContainerDestroy(&c));
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
      PetscCall(MarkRestored(ts));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The first step after a restore: the TS would restart (discard the FSAL derivative, reset a DSP
   controller's history) because TSSolve begins; keep them, as the uninterrupted run does (whose
   TSStep cleared the flag after its first step). */
PetscErrorCode TSCheckpointPreStep(TS ts)
{
  PetscContainer c;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)ts, "TurgorCheckpointRestored", (PetscObject *)&c));
  if (!c) PetscFunctionReturn(PETSC_SUCCESS);
  Restored *r;
  PetscCall(PetscContainerGetPointer(c, (void **)&r));
  if (r->pending) {
    ts->steprestart = PETSC_FALSE;
    r->pending      = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* PETSc 3.18's TSAdapt_DSP (src/ts/adapt/impls/dsp/adaptdsp.c, not installed): the filter, then
   the history. Checked at run time against what TSAdaptView prints of the filter, so a PETSc whose
   layout differs is refused, not misread. */
struct DSPHead {
  PetscReal kBeta[3], Alpha[2], cerror[3], hratio[3];
  PetscBool rollback;
};

static PetscErrorCode DSPLayoutMatches(TSAdapt adapt, PetscBool *match)
{
  PetscViewer v;
  char       *buf = NULL;
  size_t      len = 0;
  FILE       *f;
  PetscFunctionBeginUser;
  *match = PETSC_FALSE;
  f      = open_memstream(&buf, &len);
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_SYS, "open_memstream failed");
  PetscCall(PetscViewerASCIIOpenWithFILE(PETSC_COMM_SELF, f, &v));
  PetscCall(TSAdaptView(adapt, v));
  PetscCall(PetscViewerDestroy(&v));
  fclose(f);
  const DSPHead *d = (const DSPHead *)adapt->data;
  char           want[256];
  PetscCall(PetscSNPrintf(want, sizeof want, "kBeta=[%g,%g,%g] Alpha=[%g,%g]", (double)d->kBeta[0], (double)d->kBeta[1], (double)d->kBeta[2],
                          (double)d->Alpha[0], (double)d->Alpha[1]));
  *match = buf && std::strstr(buf, want) && (d->rollback == PETSC_TRUE || d->rollback == PETSC_FALSE) ? PETSC_TRUE : PETSC_FALSE;
  free(buf);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointGetAdaptState(TS ts, const char **type, PetscInt *n, PetscReal state[])
{
  TSAdapt   adapt;
  PetscBool dsp;
  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, (TSAdaptType *)type));
  state[0] = (PetscReal)adapt->timestepjustdecreased;
  *n       = 1;
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTDSP, &dsp));
  if (dsp) {
    PetscBool match;
    PetscCall(DSPLayoutMatches(adapt, &match));
    PetscCheck(match, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
               "Checkpoints with -ts_adapt_type dsp need PETSc 3.18's TSAdapt_DSP layout, which this PETSc does not have: use -ts_adapt_type basic");
    const DSPHead *d = (const DSPHead *)adapt->data;
    for (int k = 0; k < 3; k++) {
      state[1 + k] = d->cerror[k];
      state[4 + k] = d->hratio[k];
    }
    state[7] = d->rollback ? 1 : 0;
    *n       = 8;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointSetAdaptState(TS ts, PetscInt n, const PetscReal state[])
{
  TSAdapt   adapt;
  PetscBool dsp;
  PetscFunctionBeginUser;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)adapt, TSADAPTDSP, &dsp));
  PetscCheck(n == (dsp ? 8 : 1), PetscObjectComm((PetscObject)ts), PETSC_ERR_FILE_UNEXPECTED,
             "the step-size controller's state has %" PetscInt_FMT " numbers, %s", n, dsp ? "-ts_adapt_type dsp has 8" : "this adapter has 1");
  adapt->timestepjustdecreased = (PetscInt)state[0];
  if (dsp) {
    PetscBool match;
    PetscCall(DSPLayoutMatches(adapt, &match));
    PetscCheck(match, PetscObjectComm((PetscObject)ts), PETSC_ERR_SUP,
               "Checkpoints with -ts_adapt_type dsp need PETSc 3.18's TSAdapt_DSP layout, which this PETSc does not have: use -ts_adapt_type basic");
    DSPHead *d = (DSPHead *)adapt->data;
    for (int k = 0; k < 3; k++) {
      d->cerror[k] = state[1 + k];
      d->hratio[k] = state[4 + k];
    }
    d->rollback = state[7] != 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(MarkRestored(ts));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSCheckpointSetRejections(TS ts, PetscInt rejections)
{
  PetscFunctionBeginUser;
  ts->reject = rejections;
  PetscFunctionReturn(PETSC_SUCCESS);
}
