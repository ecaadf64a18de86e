#pragma once
/* turgor's step-size controller "dsp": Söderlind's digital-filter controllers (ACM TOMS 29, 2003;
   Söderlind and Wang, JCAM 185, 2006), the same filters, options and arithmetic as PETSc 3.18's
   TSADAPTDSP, registered under its name (TurgorTSRegisterAll), so that -ts_adapt_type dsp,
   -ts_adapt_dsp_filter, -ts_adapt_dsp_pid, TSAdaptDSPSetFilter() and TSAdaptDSPSetPID() work as
   before. It is turgor's so that its history -- the last control errors and step ratios -- is a
   declared part of a checkpoint (TSAdaptDSPGetHistory) and a restarted run goes on with it
   (TSAdaptDSPSetRestored) instead of resetting it at the restart's first step. A C header. */
#include <turgor/core/petsc_compat.h>
#include <petscts.h>

PETSC_EXTERN PetscErrorCode TSAdaptCreate_TurgorDSP(TSAdapt adapt);
/* Whether `adapt` is this controller, and its history: cerror[3], hratio[3] and the rollback flag
   (the storage itself, for a checkpoint to read and write). */
PETSC_EXTERN PetscErrorCode TSAdaptDSPGetHistory(TSAdapt adapt, PetscBool *is_dsp, PetscReal **cerror, PetscReal **hratio, PetscBool **rollback);
/* The history was restored: the next choice keeps it although the TS restarts its first step. */
PETSC_EXTERN PetscErrorCode TSAdaptDSPSetRestored(TSAdapt adapt);
