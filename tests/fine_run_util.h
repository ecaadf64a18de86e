#pragma once
/* Fine runs and tissues that test programs set up in code: the test's own quiet output directory,
   a fixed number of fixed steps, the default square grid of N x N cells. */
#include <turgor/turgor.hpp>

namespace turgor_test {

/* Outputs into the test's own directory `dir`, reused by each of its runs: `samples` tip samples,
   no snapshots, no progress lines. */
inline void QuietOutput(turgor::FineRun &run, const char *dir, PetscInt samples = 1)
{
  run.Output().dir               = dir;
  run.Output().samples           = samples;
  run.Output().overwrite         = true;
  run.Output().snapshots         = 0;
  run.Output().progress_interval = 0;
}

/* Exactly `steps` steps of the TS's step size: no step-size control, no final time before them. */
inline PetscErrorCode FixedSteps(TS ts, PetscInt steps)
{
  TSAdapt adapt;
  PetscFunctionBeginUser;
  PetscCall(TSSetMaxSteps(ts, steps));
  PetscCall(TSSetMaxTime(ts, 1e6));
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The square grid of cells x cells cells, every other parameter the generator's default. */
inline PetscErrorCode SquareGridTissue(PetscInt cells, turgor::Tissue *T)
{
  turgor::SquareGridSpec spec;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = cells;
  PetscCall(turgor::GenerateSquareGridTissue(PETSC_COMM_SELF, spec, T));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor_test
