#pragma once
/* What the run modes that are not time integrations (fe2_static, eigen, rve) share: the output
   directory (prepared first in SetFromOptions, so that an option refused later still leaves a
   summary.json that says so), summary.json with the keys "mode" and "status" first, and the
   summary a failure leaves (WriteFailure). A mode supplies its own keys (AddSummary) and what a
   failure adds to them (AddFailure). TimeRun, the time-dependent modes' base, keeps its own. */
#include <turgor/io/output.h>
#include <turgor/modes/simulation.h>
#include <string>

namespace turgor {

class SingleShotRun : public Simulation {
public:
  /* On rank 0, once the output directory is prepared: summary.json with `status` ("failed", or
     "interrupted"), the reason and AddFailure's keys -- unless WriteSummary wrote one that reports
     the failure itself. Not collective (the failure may be one rank's). */
  PetscErrorCode WriteFailure(const std::string &reason, const char status[]) final;
  /* A run inside another (eigen's relaxed state is fe2_static's run): its outputs go to the
     owner's directory, which the owner prepared (before this run's SetFromOptions). */
  void ShareOutputDirectory(const SingleShotRun &owner)
  {
    output_dir_ = owner.output_dir_;
    have_dir_   = owner.have_dir_;
    shared_dir_ = true;
  }

protected:
  /* `mode`: the -mode name, summary.json's "mode" */
  SingleShotRun(MPI_Comm comm, const char mode[]) : comm_(comm), mode_(mode) { }

  /* -output_dir and -output_overwrite (OutputDirectory), and summary.json reserved ("running"):
     first in the mode's SetFromOptions. Under -help nothing is prepared and HasOutputDirectory()
     stays false. */
  PetscErrorCode     PrepareOutputDirectory();
  bool               HasOutputDirectory() const { return have_dir_; }
  const std::string &OutputDir() const { return output_dir_; }
  std::string        OutputPath(const char name[]) const { return output_dir_ + "/" + name; }
  /* "mode", "status", then AddSummary's keys. Not collective. */
  PetscErrorCode Summary(JsonObject &js, const char *status);
  /* summary.json (collective). `reports_failure`: its status is "failed" (the mode found the
     failure itself and raises it next): WriteFailure then leaves it as it is. */
  PetscErrorCode WriteSummaryFile(const JsonObject &js, bool reports_failure = false);
  /* A CSV file of the mode (rank 0's), closed: a write that failed is an error on every rank,
     naming the file (collective; call it before the summary). */
  PetscErrorCode CloseOutput(CsvWriter &csv);
  /* The closing report's list of the files in the output directory. */
  std::string OutputFiles() const { return OutputFileList(output_dir_); }

  /* The mode's keys, in a summary of any status (rank-local where it matters: not collective). */
  virtual PetscErrorCode AddSummary(JsonObject &js) = 0;
  /* After a failure, on rank 0, before the failed summary is written: close the mode's files and
     add to `js` (which has the summary's keys and the reason) what the mode knows. */
  virtual PetscErrorCode AddFailure(const std::string &reason, JsonObject &js) { return PETSC_SUCCESS; }

  MPI_Comm comm_;

private:
  const char *mode_;
  std::string output_dir_;
  bool        overwrite_ = false, have_dir_ = false, failure_reported_ = false, shared_dir_ = false;
};

} // namespace turgor
