#pragma once
/* -mode fe2: the coarse tissue model of FE^2 integrated with PETSc TS (TW 562 §3.3-§5). The
   integrator is an option: explicit (-ts_type rk -ts_rk_type 5dp) gets the RHS form
   Udot = Mt^{-1} G(U); implicit ones (bdf, arkimex -- made fully implicit --, radau5, theta, ...)
   get the IFunction F = Mt Udot - G(U) and the IJacobian shift Mt + [[0, -I], [K, C]] assembled
   from the material tangents. A failed material evaluation (no RVE convergence, inverted element)
   rejects the step and TS retries with a smaller one. */
#include <turgor/coarse/coarse_model.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/io/output.h>
#include <turgor/io/time_sampler.h>
#include <petscts.h>

namespace turgor {

class FE2Run {
public:
  explicit FE2Run(MPI_Comm comm) : comm_(comm), model_(comm) { }
  ~FE2Run();
  FE2Run(const FE2Run &)            = delete;
  FE2Run &operator=(const FE2Run &) = delete;

  PetscErrorCode SetFromOptions();
  PetscErrorCode SetUp();
  PetscErrorCode Solve();
  PetscErrorCode WriteSummary();

  CoarseModel &Model() { return model_; }
  TS           GetTS() const { return ts_; }
  Vec          GetState() const { return U_; }
  PetscReal    TipDisplacement() const { return tip_final_; }

private:
  static PetscErrorCode IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx);
  static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx);
  static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec G, void *ctx);
  static PetscErrorCode CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept);
  static PetscErrorCode PostStep(TS ts);
  static PetscErrorCode Monitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx);
  PetscErrorCode        Observe(PetscReal t, Vec U);

  MPI_Comm           comm_;
  LoadSpec           load_;
  CoarseModel        model_;
  TS                 ts_ = nullptr;
  Vec                U_ = nullptr;
  Mat                J_ = nullptr;
  std::string        output_dir_;
  PetscInt           tip_samples_ = 1000, snapshots_ = 20;
  /* material tangents are recomputed when the Jacobian is older than this many accepted steps, or
     after a step rejection; 0: at every Jacobian request (each Newton iteration) */
  PetscInt           jacobian_max_age_ = -1, steps_since_refresh_ = 0, rejections_at_refresh_ = -1;
  PetscReal          progress_interval_ = 10.0, t_final_ = 0, tip_final_ = 0;
  bool               explicit_ = false;
  CsvWriter          tip_csv_;
  CoarseFieldsWriter fields_;
  TimeSampler        sampler_;
  PetscLogDouble     wall_ = 0;
  PetscLogStage      stage_setup_ = 0, stage_solve_ = 0;
};

} // namespace turgor
