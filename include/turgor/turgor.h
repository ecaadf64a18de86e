#pragma once
/* turgor: PETSc-native simulation of plant tissue mechanics -- the C API, for C and C++ programs
   that link libturgor (see makefile.inc). Only C declarations with C linkage (PETSC_EXTERN) and C
   types; C++ programs that want turgor's C++ classes include <turgor/turgor.hpp> instead.

     PetscCall(PetscInitialize(&argc, &argv, NULL, help));
     PetscCall(TurgorRegisterAll());                  TS types radauiia and am, turgor's modes
     ... TSSetType(ts, TSRADAUIIA); TSRadauIIASetJacobianReuse(ts, 0.1); ...
     PetscCall(TurgorRunMode(PETSC_COMM_WORLD, "rve")); what the turgor executable does
     PetscCall(PetscFinalize());

   examples/c_api.c is a complete C program. */
#include <petscts.h>
#include <turgor/app/register_all.h>   /* TurgorRegisterAll() */
#include <turgor/ts/ts_register.h>     /* TurgorTSRegisterAll() */
#include <turgor/ts/radau_iia.h>       /* TSRADAUIIA, TSRadauIIA*() */
#include <turgor/ts/adams_moulton.h>   /* TSAM, TSAM*() */
#include <turgor/ts/velocity_verlet.h> /* TSVERLET, TSVerletGetCounters() */
#include <turgor/ts/low_storage_rk.h>  /* TSLSRK, TSLSRKGetTableau(), TSLSRKGetCounters() */

#define TURGOR_VERSION_STRING "0.1.0"

/* Runs one of turgor's modes (fine, rve, fe2; see `turgor -help`) on comm, as the turgor executable
   does: reads its options from the options database (-mode, -output_dir, -ts_*, the mode's own
   options), sets it up, solves, and writes its outputs and summary (summary.json in -output_dir,
   the "Done:" line). `mode` is the default mode, which the option -mode overrides, as options
   override any default set through PETSc's API; NULL means fe2, the executable's default. With
   -help every option is listed and nothing is solved. Calls TurgorRegisterAll() itself. Collective
   on comm. A C++ exception inside turgor is caught and returned as a PETSc error (PETSC_ERR_MEM for
   std::bad_alloc, PETSC_ERR_LIB otherwise) with its message; none reaches the caller. */
PETSC_EXTERN PetscErrorCode TurgorRunMode(MPI_Comm comm, const char mode[]);
