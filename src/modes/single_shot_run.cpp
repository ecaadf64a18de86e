#include <turgor/modes/single_shot_run.h>

namespace turgor {

PetscErrorCode SingleShotRun::PrepareOutputDirectory()
{
  PetscFunctionBeginUser;
  if (shared_dir_) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(OutputDirectory(comm_, &output_dir_, &overwrite_, &have_dir_));
  if (have_dir_) PetscCall(ReserveSummary(comm_, OutputPath("summary.json"), mode_));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SingleShotRun::Summary(JsonObject &js, const char *status)
{
  PetscFunctionBeginUser;
  js.Set("mode", mode_);
  js.Set("status", status);
  PetscCall(AddSummary(js));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SingleShotRun::WriteSummaryFile(const JsonObject &js, bool reports_failure)
{
  PetscFunctionBeginUser;
  PetscCall(js.Write(comm_, OutputPath("summary.json")));
  failure_reported_ = reports_failure;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SingleShotRun::CloseOutput(CsvWriter &csv)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank == 0) csv.Finish(); /* said below, on every rank */
  PetscCall(CheckOutputError(comm_, rank == 0 ? csv.Error() : std::string()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SingleShotRun::WriteFailure(const std::string &reason, const char status[])
{
  JsonObject  js;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (rank != 0 || !have_dir_ || failure_reported_) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(Summary(js, status));
  js.Set("reason", reason);
  PetscCall(AddFailure(reason, js));
  PetscCall(js.Write(PETSC_COMM_SELF, OutputPath("summary.json")));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
