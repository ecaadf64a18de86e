/* The "dsp" step-size controller (include/turgor/ts/adapt_dsp.h). */
#include <turgor/ts/adapt_dsp.h>
#include <petsc/private/tsimpl.h>
#include <petscdm.h>
#include <cmath>

namespace {

struct DSP {
  PetscReal beta[3]   = {0, 0, 0}; /* filter: weights of the last three control errors */
  PetscReal alpha[2]  = {0, 0};    /* ... and of the last two step ratios */
  PetscReal cerror[3] = {1, 1, 1}, hratio[3] = {1, 1, 1};
  PetscBool rollback = PETSC_FALSE;
  PetscBool restored = PETSC_FALSE; /* a checkpoint's history: kept at the restart's first step */
};

/* The filters by name: scale, beta, alpha (the controller's parameters are these over the scale). */
struct Filter {
  const char *name;
  PetscReal   scale, beta[3], alpha[2];
};
const Filter kFilters[] = {
  {"basic",   1,  {1, 0, 0},   {0, 0}   },
  {"PI30",    3,  {1, 0, 0},   {0, 0}   },
  {"PI42",    5,  {3, -1, 0},  {0, 0}   },
  {"PI33",    3,  {2, -1, 0},  {0, 0}   },
  {"PI34",    10, {7, -4, 0},  {0, 0}   },
  {"PC11",    1,  {2, -1, 0},  {-1, 0}  },
  {"PC47",    10, {11, -7, 0}, {-10, 0} },
  {"PC36",    10, {9, -6, 0},  {-10, 0} },
  {"H0211",   2,  {1, 1, 0},   {1, 0}   },
  {"H211b",   4,  {1, 1, 0},   {1, 0}   },
  {"H211PI",  6,  {1, 1, 0},   {0, 0}   },
  {"H0312",   4,  {1, 2, 1},   {3, 1}   },
  {"H312b",   8,  {1, 2, 1},   {3, 1}   },
  {"H312PID", 18, {1, 2, 1},   {0, 0}   },
  {"H0321",   4,  {5, 2, -3},  {-1, -3} },
  {"H321",    18, {6, 1, -5},  {-15, -3}},
};
const PetscInt kNumFilters = (PetscInt)(sizeof kFilters / sizeof kFilters[0]);
const PetscInt kDefault    = 2; /* PI42 */

void ResetHistory(DSP *d)
{
  for (int k = 0; k < 3; k++) d->cerror[k] = d->hratio[k] = 1;
}

/* A rejected step undone: the history of before its last accepted step comes back. */
void RollBack(DSP *d)
{
  d->cerror[0] = d->cerror[1], d->cerror[1] = d->cerror[2], d->cerror[2] = 1;
  d->hratio[0] = d->hratio[1], d->hratio[1] = d->hratio[2], d->hratio[2] = 1;
}

/* A soft limiter of the step ratio (Söderlind 2006): 1 + atan(r - 1). */
PetscReal Limiter(PetscReal r)
{
  return 1 + PetscAtanReal(r - 1);
}

PetscErrorCode SetFilter(TSAdapt adapt, const char *name)
{
  DSP *d = (DSP *)adapt->data;
  PetscFunctionBeginUser;
  for (const Filter &f : kFilters) {
    PetscBool match;
    PetscCall(PetscStrcasecmp(name, f.name, &match));
    if (!match) continue;
    for (int k = 0; k < 3; k++) d->beta[k] = f.beta[k] / f.scale;
    for (int k = 0; k < 2; k++) d->alpha[k] = f.alpha[k] / f.scale;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  SETERRQ(PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_UNKNOWN_TYPE, "Option -ts_adapt_dsp_filter %s: no such filter", name);
}

PetscErrorCode SetPID(TSAdapt adapt, PetscReal kI, PetscReal kP, PetscReal kD)
{
  DSP *d = (DSP *)adapt->data;
  PetscFunctionBeginUser;
  d->beta[0] = kI + kP + kD, d->beta[1] = -(kP + 2 * kD), d->beta[2] = kD;
  d->alpha[0] = d->alpha[1] = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The weighted error norm of the step just taken, and the order it belongs to (< 0: none). */
PetscErrorCode ErrorNorm(TSAdapt adapt, TS ts, PetscInt *order, PetscReal *enorm)
{
  PetscFunctionBeginUser;
  *order = PETSC_DECIDE;
  *enorm = -1;
  if (ts->ops->evaluatewlte) {
    PetscCall(TSEvaluateWLTE(ts, adapt->wnormtype, order, enorm));
    PetscCheck(*enorm < 0 || *order >= 1, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_OUTOFRANGE,
               "Computed error order %" PetscInt_FMT " must be positive", *order);
  } else if (ts->ops->evaluatestep) {
    DM        dm;
    Vec       Y;
    PetscReal ea, er;
    PetscCheck(adapt->candidates.n >= 1, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_WRONGSTATE, "No candidate has been registered");
    PetscCheck(adapt->candidates.inuse_set, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_WRONGSTATE, "The scheme in use is not among the candidates");
    *order = adapt->candidates.order[0];
    PetscCall(TSGetDM(ts, &dm));
    PetscCall(DMGetGlobalVector(dm, &Y));
    PetscCall(TSEvaluateStep(ts, *order - 1, Y, NULL));
    PetscCall(TSErrorWeightedNorm(ts, ts->vec_sol, Y, adapt->wnormtype, enorm, &ea, &er));
    PetscCall(DMRestoreGlobalVector(dm, &Y));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Choose(TSAdapt adapt, TS ts, PetscReal h, PetscInt *next_sc, PetscReal *next_h, PetscBool *accept, PetscReal *wlte, PetscReal *wltea,
                      PetscReal *wlter)
{
  DSP            *d      = (DSP *)adapt->data;
  const PetscReal safety = adapt->safety * (PetscReal)0.9;
  const PetscReal hmin   = adapt->dt_min * (1 + PETSC_SQRT_MACHINE_EPSILON);
  PetscInt        order;
  PetscReal       enorm;
  PetscFunctionBeginUser;
  *next_sc = 0;
  *wltea = *wlter = -1;
  PetscCall(ErrorNorm(adapt, ts, &order, &enorm));
  if (enorm < 0) { /* no error estimate: accept, keep the step, start the history afresh */
    ResetHistory(d);
    *accept = PETSC_TRUE;
    *next_h = h;
    *wlte   = -1;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!ts->steprollback) d->rollback = PETSC_FALSE;
  else if (!d->rollback) {
    d->rollback = PETSC_TRUE;
    RollBack(d);
  }
  if (ts->steprestart && !d->restored) ResetHistory(d);
  d->restored = PETSC_FALSE;
  /* the step ratio: the filtered control errors and past ratios (the order of the products is
     PETSc's, so that the steps are the same to the last bit) */
  const PetscReal k    = (PetscReal)order;
  const PetscReal ctr0 = PetscPowReal(1 / PetscMax(enorm, PETSC_SMALL), 1 / k);
  PetscReal       rho0 = PetscPowReal(ctr0, d->beta[0]);
  rho0 *= PetscPowReal(d->cerror[0], d->beta[1]);
  rho0 *= PetscPowReal(d->cerror[1], d->beta[2]);
  rho0 *= PetscPowReal(d->hratio[0], -d->alpha[0]);
  rho0 *= PetscPowReal(d->hratio[1], -d->alpha[1]);
  rho0    = Limiter(rho0);
  *accept = rho0 >= safety || adapt->always_accept || h < hmin ? PETSC_TRUE : PETSC_FALSE;
  if (*accept) {
    d->cerror[2] = d->cerror[1], d->cerror[1] = d->cerror[0], d->cerror[0] = ctr0;
    d->hratio[2] = d->hratio[1], d->hratio[1] = d->hratio[0], d->hratio[0] = rho0;
    d->rollback = PETSC_FALSE;
  }
  const PetscReal hnew = h * PetscClipInterval(rho0, adapt->clip[0], adapt->clip[1]);
  *next_h              = PetscClipInterval(hnew, adapt->dt_min, adapt->dt_max);
  *wlte                = PetscMax(enorm, PETSC_SMALL);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetFromOptions(TSAdapt adapt, PetscOptionItems *PetscOptionsObject)
{
  DSP        *d = (DSP *)adapt->data;
  const char *names[kNumFilters];
  PetscInt    index  = kDefault, n;
  PetscReal   pid[3] = {1, 0, 0};
  PetscBool   set;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < kNumFilters; i++) names[i] = kFilters[i].name;
  PetscOptionsHeadBegin(PetscOptionsObject, "DSP adaptive controller options");
  PetscCall(PetscOptionsEList("-ts_adapt_dsp_filter", "Filter name", "TSAdaptDSPSetFilter", names, kNumFilters, names[index], &index, &set));
  if (set) PetscCall(SetFilter(adapt, names[index]));
  n = 3;
  PetscCall(PetscOptionsRealArray("-ts_adapt_dsp_pid", "PID parameters <kkI,kkP,kkD>", "TSAdaptDSPSetPID", pid, &n, &set));
  PetscCheck(!set || n, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_WRONG, "Option -ts_adapt_dsp_pid: give at least one value");
  if (set) PetscCall(SetPID(adapt, pid[0], pid[1], pid[2]));
  n = 3;
  PetscCall(PetscOptionsRealArray("-ts_adapt_dsp_kbeta", "Filter parameters", "", d->beta, &n, &set));
  PetscCheck(!set || n, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_WRONG, "Option -ts_adapt_dsp_kbeta: give at least one value");
  for (PetscInt i = n; set && i < 3; i++) d->beta[i] = 0;
  n = 2;
  PetscCall(PetscOptionsRealArray("-ts_adapt_dsp_alpha", "Filter parameters", "", d->alpha, &n, &set));
  PetscCheck(!set || n, PetscObjectComm((PetscObject)adapt), PETSC_ERR_ARG_WRONG, "Option -ts_adapt_dsp_alpha: give at least one value");
  for (PetscInt i = n; set && i < 2; i++) d->alpha[i] = 0;
  PetscOptionsHeadEnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode View(TSAdapt adapt, PetscViewer viewer)
{
  DSP      *d = (DSP *)adapt->data;
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "filter parameters kBeta=[%g,%g,%g] Alpha=[%g,%g]\n", (double)d->beta[0], (double)d->beta[1], (double)d->beta[2],
                                     (double)d->alpha[0], (double)d->alpha[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Destroy(TSAdapt adapt)
{
  PetscFunctionBeginUser;
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPSetFilter_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPSetPID_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPGetHistory_C", NULL));
  delete (DSP *)adapt->data;
  adapt->data = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetHistory(TSAdapt adapt, PetscReal **cerror, PetscReal **hratio, PetscBool **rollback, PetscBool **restored)
{
  DSP *d = (DSP *)adapt->data;
  PetscFunctionBeginUser;
  *cerror = d->cerror, *hratio = d->hratio, *rollback = &d->rollback, *restored = &d->restored;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

PetscErrorCode TSAdaptCreate_TurgorDSP(TSAdapt adapt)
{
  PetscFunctionBeginUser;
  adapt->data                = new DSP();
  adapt->reject_safety       = 1.0; /* not used by this controller */
  adapt->ops->choose         = Choose;
  adapt->ops->setfromoptions = SetFromOptions;
  adapt->ops->destroy        = Destroy;
  adapt->ops->view           = View;
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPSetFilter_C", SetFilter));
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPSetPID_C", SetPID));
  PetscCall(PetscObjectComposeFunction((PetscObject)adapt, "TSAdaptDSPGetHistory_C", GetHistory));
  PetscCall(SetFilter(adapt, kFilters[kDefault].name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAdaptDSPGetHistory(TSAdapt adapt, PetscBool *is_dsp, PetscReal **cerror, PetscReal **hratio, PetscBool **rollback)
{
  PetscErrorCode (*get)(TSAdapt, PetscReal **, PetscReal **, PetscBool **, PetscBool **) = NULL;
  PetscBool *restored;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQueryFunction((PetscObject)adapt, "TSAdaptDSPGetHistory_C", &get));
  *is_dsp = get ? PETSC_TRUE : PETSC_FALSE;
  if (get) PetscCall(get(adapt, cerror, hratio, rollback, &restored));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TSAdaptDSPSetRestored(TSAdapt adapt)
{
  PetscErrorCode (*get)(TSAdapt, PetscReal **, PetscReal **, PetscBool **, PetscBool **) = NULL;
  PetscReal *c, *h;
  PetscBool *rollback, *restored;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQueryFunction((PetscObject)adapt, "TSAdaptDSPGetHistory_C", &get));
  if (!get) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(get(adapt, &c, &h, &rollback, &restored));
  *restored = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
