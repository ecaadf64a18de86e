#pragma once
/* -mode fe2_static: static equilibrium of the coarse FE^2 model under the scene's loads,
     R(u) = f_int(u) - lambda f_ext = 0,   v = 0 (so Fdot = 0 at every material point),
   solved by PETSc SNES (Newton on the stiffness K assembled from the materials' D^e, eqs 35-37)
   with load stepping: the body force is applied in increments of the load factor lambda up to 1
   (-fe2_static_load_steps), an increment whose nonlinear solve or material evaluation fails is
   halved and retried from the last converged state (material points reverted), a converged one is
   committed and may grow again; below -fe2_static_min_increment the run fails, naming the lambda
   reached. Outputs: tip.csv (one row per converged load level), summary.json, coarse.h5/.xmf (the
   final state). Any -material, any -coarse_quadrature, any number of ranks. With
   -fe2_static_eigen_monitor N the lowest eigenvalues of K are computed every N converged load levels
   (analysis/stability_monitor.h): the first zero crossing along the load path is a loss of
   stability (buckling), reported by its load factor.

   Prescribed displacements (-coarse_boundary_gradient H: the clamped vertices at lambda H X) are
   load too: each increment starts from the last converged state moved by the increment's affine
   field on the free nodes as well (a homogeneous deformation is then solved at once). At every
   converged level each material point's second-order work since the last level is checked
   (CoarseModel::SofteningSinceLast): the first level at which a point's stress falls along its
   strain increment (cos(dS, dE) below -fe2_static_softening_cosine) is reported as localisation --
   the point's material gave way (a periodic RVE that cracks across its period), and beyond it
   first-order homogenisation no longer describes the tissue. A point whose evaluation fails at every
   increment down to -fe2_static_min_increment has no equilibrium near its last one (a limit point
   of its response: the RVE gives way with no nearby state to go to) and is reported so at the last
   converged level. -fe2_static_stop_at_localisation ends the run at either with status localised. */
#include <turgor/analysis/stability_monitor.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/coarse/coarse_model.h>
#include <turgor/io/output.h>
#include <turgor/modes/single_shot_run.h>
#include <petscsnes.h>

namespace turgor {

/* -fe2_static_* options (API defaults; options win). */
struct StaticLoadSpec {
  PetscInt  load_steps    = 1;    /* initial increments of lambda: the first is 1/load_steps */
  PetscReal min_increment = 1e-4; /* the smallest increment of lambda tried before giving up */
  bool      snapshot      = true; /* coarse.h5/.xmf with the final (or last converged) state */
  /* localisation: a point softened when cos(dS, dE) of its increment is below this */
  PetscReal softening_cosine     = 0;
  bool      stop_at_localisation = false; /* end the run (status localised) at the first */

  PetscErrorCode SetFromOptions(MPI_Comm comm);
};

class FE2StaticRun : public SingleShotRun {
public:
  explicit FE2StaticRun(MPI_Comm comm) : SingleShotRun(comm, "fe2_static"), model_(comm), monitor_(comm) { }
  ~FE2StaticRun() override;
  FE2StaticRun(const FE2StaticRun &)            = delete;
  FE2StaticRun &operator=(const FE2StaticRun &) = delete;

  PetscErrorCode SetFromOptions() override;
  PetscErrorCode SetUp() override;
  PetscErrorCode Solve() override;
  PetscErrorCode WriteSummary() override;
  bool           Interrupted() const override { return interrupted_; }

  CoarseModel    &Model() { return model_; }
  LoadSpec       &Load() { return load_; }
  StaticLoadSpec &Stepping() { return spec_; }
  SNES            GetSNES() const { return snes_; }
  /* The last converged load factor and the tip displacement there. */
  PetscReal LoadFactor() const { return lambda_; }
  PetscReal TipDisplacement() const { return tip_; }
  /* The last converged state [u; 0] into U (a global vector of Model()). */
  PetscErrorCode ConvergedState(Vec U);

private:
  static PetscErrorCode Residual(SNES snes, Vec x, Vec r, void *ctx);
  static PetscErrorCode Jacobian(SNES snes, Vec x, Mat A, Mat B, void *ctx);
  PetscErrorCode        ToState(Vec x); /* U_ = [x; 0] */
  /* one nonlinear solve at load factor lambda from x (the last converged state); *converged */
  PetscErrorCode SolveAt(PetscReal lambda, bool *converged, std::string *why);
  PetscErrorCode Record(PetscReal lambda, PetscInt its); /* a converged level: tip.csv */
  PetscErrorCode AddSummary(JsonObject &js) override;
  PetscErrorCode AddFailure(const std::string &reason, JsonObject &js) override;

  LoadSpec           load_;
  StaticLoadSpec     spec_;
  CoarseModel        model_;
  SNES               snes_ = nullptr;
  Mat                J_ = nullptr, K_ = nullptr; /* the model's [[0, -I], [K, C]] and its K block */
  IS                 is_u_ = nullptr, is_v_ = nullptr;
  Vec                U_ = nullptr, Udot_ = nullptr, Ffull_ = nullptr; /* full states [u; v] */
  Vec                x_ = nullptr, x_conv_ = nullptr;                 /* displacements */
  Vec                x_affine_ = nullptr;                             /* H X on the free nodes (-coarse_boundary_gradient; null without one) */
  bool               solving_ = false, interrupted_ = false;
  CsvWriter          tip_csv_;
  CoarseFieldsWriter fields_;
  StabilityMonitor   monitor_; /* -fe2_static_eigen_monitor: eigenvalues of K along the load path */
  PetscLogStage      stage_setup_ = 0, stage_solve_ = 0;
  PetscLogEvent      ev_increment_ = 0, ev_output_ = 0;
  /* results */
  PetscReal      lambda_ = 0, tip_ = 0, tip_x_ = 0, increment_ = 0, force_scale_ = 0, residual_conv_ = 0; /* |f| at the last converged state */
  PetscInt       levels_ = 0, increments_ = 0, cutbacks_ = 0, snes_its_ = 0, ksp_its_ = 0, solves_ = 0, failed_solves_ = 0;
  PetscLogDouble t0_ = 0, wall_ = 0;
  std::string    last_failure_;
  /* the last level's mean stress and lowest softening cosine (CoarseModel::SofteningSinceLast), the
     lowest seen, and where localisation was first found (load factor -1: nowhere) */
  PetscReal mean_stress_[3] = {0, 0, 0}, softening_cosine_ = 1, softening_min_ = 1;
  PetscReal localisation_load_factor_ = -1, localisation_cosine_ = 1;
  PetscInt  softening_element_ = -1, localisation_element_ = -1;
  bool      localised_          = false; /* stopped there (-fe2_static_stop_at_localisation) */
  bool      failed_in_material_ = false; /* the last failed increment had a material point find no stress */
  /* "softening" (a point's stress fell along its strain increment) or "no_equilibrium" (a point's
     evaluation failed at every increment down to the smallest); "" before either */
  std::string localisation_criterion_;
};

} // namespace turgor
