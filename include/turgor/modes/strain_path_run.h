#pragma once
/* -mode rve: one material point driven along a strain path (uniaxial, biaxial, simple shear,
   rigid rotation, or hold; options path_*), writing sigma, rho, D^e, D^v and iteration counts per
   step to rve.csv and a summary.json. The material is chosen by -material (the RVE by default). */
#include <turgor/material/material_pool.h>
#include <turgor/modes/single_shot_run.h>
#include <turgor/io/output.h>

namespace turgor {

class StrainPathRun : public SingleShotRun {
public:
  explicit StrainPathRun(MPI_Comm comm) : SingleShotRun(comm, "rve"), pool_(comm) { }
  PetscErrorCode SetFromOptions() override;
  PetscErrorCode SetUp() override;
  PetscErrorCode Solve() override;
  PetscErrorCode WriteSummary() override;

  /* The imposed deformation at time t. */
  void Path(PetscReal t, Tensor2 *F, Tensor2 *Fdot) const;

private:
  MaterialPointPool pool_;
  PetscInt          path_ = 0, steps_ = 20;
  PetscReal         rate_ = 1e-3, t_final_ = 50.0; /* [1/µs], [µs] */
  PetscBool         tangents_       = PETSC_TRUE;
  PetscBool         allow_failures_ = PETSC_FALSE;
  PetscInt          stop_after_     = 0; /* the path ends after this many failed evaluations in a row; 0: never */
  /* results */
  CsvWriter        csv_;
  PetscInt         failures_ = 0, evaluations_ = 0, failed_in_a_row_ = 0;
  MaterialResponse last_; /* the last evaluation that succeeded */
  PetscReal        t_last_ = 0, max_asymmetry_ = 0, wall_ = 0;
  PetscReal        ellipticity_lost_ = -1; /* the first t whose tangent lost ellipticity; -1: none */
  std::string      first_failure_;

  PetscErrorCode AddSummary(JsonObject &js) override;
  PetscErrorCode AddFailure(const std::string &reason, JsonObject &js) override;
};

} // namespace turgor
