#pragma once
/* -mode fe2: the coarse tissue model of FE^2 integrated with PETSc TS on the run skeleton
   (time_run.h; TW 562 §3.3-§5). The integrator is an option: explicit ones (-ts_type rk
   -ts_rk_type 5dp, euler, ssp, am) get the RHS form Udot = Mt^{-1} G(U); implicit ones (radauiia,
   bdf, arkimex -- made fully implicit --, theta, ...) get the IFunction F = Mt Udot - G(U) and the
   IJacobian shift Mt + [[0, -I], [K, C]] assembled from the material tangents. A failed material
   evaluation (no RVE convergence, inverted element) rejects the step and TS retries with a smaller
   one. With -fe2_eigen_monitor N the lowest eigenvalues of the stiffness K are computed every N
   steps (analysis/stability_monitor.h), and the first zero crossing (loss of stability) reported. */
#include <turgor/analysis/stability_monitor.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/coarse/coarse_model.h>
#include <turgor/run/time_run.h>
#include <unordered_map>

namespace turgor {

class FE2Run : public TimeRun {
public:
  explicit FE2Run(MPI_Comm comm) : TimeRun(comm, "fe2"), model_(comm), monitor_(comm) { }
  ~FE2Run() override;

  CoarseModel &Model() { return model_; }
  LoadSpec    &Load() { return load_; }

protected:
  PetscErrorCode           SetTSDefaults() override;
  PetscErrorCode           ModeSetFromOptions() override;
  PetscErrorCode           SetUpModel() override;
  PetscErrorCode           AfterTSSetFromOptions() override;
  PetscErrorCode           Report() override;
  std::vector<std::string> ObservedColumns() const override { return {"tip_displacement_y"}; }
  PetscErrorCode           Observe(PetscReal t, Vec U, std::vector<PetscReal> &row) override;
  PetscErrorCode           WriteSnapshot(PetscReal t, Vec U) override;
  PetscInt                 SnapshotCount() const override { return fields_.Count(); }
  const char              *SnapshotFiles() const override { return "coarse.h5 + coarse.xmf"; }
  PetscInt                 FunctionEvaluations() const override { return model_.Counters().residuals; }
  PetscErrorCode           OpenSnapshots() override;
  PetscErrorCode           CloseOutputs() override { return monitor_.CloseOutputs(); } /* stability.csv */
  PetscErrorCode           AddSummary(JsonObject &js) override;
  PetscErrorCode           DoneDetails(std::string *details) override;
  const char              *FailureAdvice() const override
  {
    return "steps were rejected repeatedly (more than -ts_max_reject in a row): the material-point failures printed above say where and why; lower -ts_dt "
           "or tighten -ts_rtol";
  }

  /* Checkpoints: the scene's fingerprint (mesh coordinates, element, quadrature, material and its
     RVE settings, groups, boundary and load), and the declared state: the Jacobian reuse's counts,
     the coarse model's with every material point's (CoarseModel::DeclareState). The unknowns are
     numbered by their nodes' positions, the material points by their element's position; another
     layout needs RVEs on one rank each. Explicit one-step integrators only (TimeRun refuses the
     others). */
  bool           Checkpointable() const override { return true; }
  PetscErrorCode CheckpointFingerprint(std::vector<std::pair<std::string, std::string>> &fp) override;
  PetscErrorCode DeclareState(std::deque<StateDeclaration> &decls) override;
  std::uint64_t  EntityId(StateEntity e, PetscInt local) const override;
  PetscInt       EntityLocal(StateEntity e, std::uint64_t id) const override;
  bool           EntityOwned(StateEntity e, PetscInt local) const override;
  std::uint64_t  LayoutHash() const override;
  PetscErrorCode AfterStateRead(PetscReal t, Vec U, bool own_layout) override
  {
    failures_by_step_ = model_.StressFailures();
    failures_in_step_ = 0;
    return model_.AfterStateRead(U, own_layout);
  }
  PetscErrorCode StateOrder(IS *order) override { return model_.RankFreeStateOrder(order); }
  bool           RestartsOnOtherRanks(std::string *why) const override;

private:
  static PetscErrorCode IFunction(TS ts, PetscReal t, Vec U, Vec Udot, Vec F, void *ctx);
  static PetscErrorCode IJacobian(TS ts, PetscReal t, Vec U, Vec Udot, PetscReal shift, Mat A, Mat B, void *ctx);
  static PetscErrorCode RHSFunction(TS ts, PetscReal t, Vec U, Vec G, void *ctx);
  static PetscErrorCode CheckDomain(TS ts, PetscReal t, Vec U, PetscBool *accept);
  PetscErrorCode        AfterStep(PetscReal t, Vec U) override;
  PetscErrorCode        EndWhereStuck(PetscReal t, bool crawled, std::string *status, std::string *reason) override;
  void                  AddFailureSummary(JsonObject &js) const override { AddLocalisation(js); }
  void                  AddLocalisation(JsonObject &js) const;
  static PetscErrorCode EigenMonitor(TS ts, PetscInt step, PetscReal t, Vec U, void *ctx);

  LoadSpec    load_;
  CoarseModel model_;
  Mat         J_ = nullptr;
  /* material tangents are recomputed when the Jacobian is older than this many accepted steps, or
     after a step rejection; 0: at every Jacobian request (each Newton iteration) */
  PetscInt jacobian_max_age_ = -1, steps_since_refresh_ = 0, rejections_at_refresh_ = -1;
  /* localisation: the first snapshot whose acoustic field (-coarse_acoustic_field) has an element with
     min det Q <= 0, or the last accepted time beyond which a material point finds no equilibrium
     (the integrator cannot pass it: EndWhereStuck; no_equilibrium_), that element, and whether the
     run stops there (-fe2_stop_at_localisation) */
  PetscReal          localisation_time_ = -1, localisation_det_ = 0;
  PetscInt           localisation_element_ = -1;
  bool               no_equilibrium_       = false;
  PetscInt           failures_by_step_ = 0, failures_in_step_ = 0; /* evaluations without a stress: by the last accepted step, and in its tries */
  PetscBool          stop_at_localisation_ = PETSC_FALSE;
  bool               explicit_             = false;
  CoarseFieldsWriter fields_;
  StabilityMonitor   monitor_;   /* -fe2_eigen_monitor */
  std::string        mesh_hash_; /* the fingerprint's, computed once */
  /* checkpoints: every material point's rank-free id (by the pool's global index), and back */
  std::vector<PetscInt>                          point_ids_;
  mutable std::unordered_map<PetscInt, PetscInt> point_of_id_;
};

} // namespace turgor
