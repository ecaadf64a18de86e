#pragma once
/* -mode eigen: spectra of the coarse FE^2 model's stiffness at a state (any -material, either
   -coarse_quadrature, any number of ranks):
     the state (-eigen_state): reference (u = 0), relaxed (the static equilibrium under the scene's
     loads, solved by -mode fe2_static's load stepping: its -fe2_static_* options, tip.csv and
     coarse.h5 of the relaxed state), or snapshot (the displacement of a coarse.h5 snapshot,
     -eigen_snapshot_file, -eigen_snapshot_time); v = 0 in every case;
   K (initial-stress and constitutive parts, from the material points' D^e) and M of the free
   displacements (analysis/coarse_operators.h), then with SLEPc
     the lowest modes, K phi = omega^2 M phi (EPS GHEP, shift-and-invert about 0, -eigen_eps_*,
     -eigen_st_*): frequencies, periods, residuals; a negative eigenvalue is a loss of positive
     definiteness (of stability) of K at that state;
     the largest, omega_max^2 (-eigen_max_eps_*, -eigen_max_st_*): the explicit stability limit of
     the coarse system and the stiffness ratio omega_max / omega_min;
     the damped modes (K + s C + s^2 M) phi = 0 with C from D^v (PEP, -eigen_damped_pep_*,
     -eigen_damped_st_*; -eigen_damping 0: not computed) and the modal damping ratio of the highest
     mode, which with omega_max gives DOPRI's step limit (analysis/explicit_stability.h).
   Outputs: eigen.csv, summary.json, modes.h5/.xmf (a temporal collection whose "time" is the mode
   number: each mode shape as the vertex vector "mode" on the analysed state). Units: lambda =
   omega^2 in 1/µs^2, omega in rad/µs, frequency omega / 2 pi in 1/µs = MHz, period in µs. */
#include <turgor/analysis/coarse_operators.h>
#include <turgor/analysis/damped_modes.h>
#include <turgor/analysis/pencil_eigensolver.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/modes/fe2_static_run.h>
#include <turgor/io/output.h>
#include <turgor/modes/single_shot_run.h>
#include <memory>

namespace turgor {

enum class EigenState {
  Reference,
  Relaxed,
  Snapshot
};

/* -eigen_* options (API defaults; options win). */
struct EigenSpec {
  EigenState  state   = EigenState::Relaxed;
  PetscInt    modes   = 6;    /* lowest eigenpairs (the EPS's nev; -eigen_eps_nev overrides) */
  bool        largest = true; /* omega_max and the stiffness ratio */
  bool        damping = true; /* damped modes (PEP) with C from D^v, the highest mode's damping ratio */
  bool        shapes  = true; /* modes.h5/.xmf */
  std::string snapshot_file;
  bool        has_snapshot_time = false;
  PetscReal   snapshot_time     = 0;

  PetscErrorCode SetFromOptions(MPI_Comm comm);
};

class EigenRun : public SingleShotRun {
public:
  explicit EigenRun(MPI_Comm comm) : SingleShotRun(comm, "eigen"), lowest_(comm), largest_(comm), damped_(comm) { }
  ~EigenRun() override;
  EigenRun(const EigenRun &)            = delete;
  EigenRun &operator=(const EigenRun &) = delete;

  PetscErrorCode SetFromOptions() override;
  PetscErrorCode SetUp() override;
  PetscErrorCode Solve() override;
  PetscErrorCode WriteSummary() override;
  /* SIGINT/SIGTERM during the relaxed state's static solve (the eigen analysis is then not made) */
  bool Interrupted() const override { return static_ && static_->Interrupted(); }

  EigenSpec               &Spec() { return spec_; }
  CoarseModel             &Model() { return *model_; } /* after SetFromOptions */
  const PencilEigensolver &Lowest() const { return lowest_; }
  const PencilEigensolver &Largest() const { return largest_; }
  const DampedModes       &Damped() const { return damped_; }
  const CoarseOperators   &Operators() const { return *ops_; }
  PetscReal                OmegaMax() const { return omega_max_; }
  /* sqrt of the lowest positive eigenvalue computed (NaN if none) */
  PetscReal OmegaMin() const;

private:
  PetscErrorCode AddSummary(JsonObject &js) override;
  PetscErrorCode AddFailure(const std::string &reason, JsonObject &js) override;
  PetscErrorCode WriteModes();

  EigenSpec                        spec_;
  LoadSpec                         load_;
  std::unique_ptr<FE2StaticRun>    static_; /* the relaxed state's solve, and its model */
  std::unique_ptr<CoarseModel>     own_;    /* the model otherwise */
  CoarseModel                     *model_ = nullptr;
  std::unique_ptr<CoarseOperators> ops_;
  PencilEigensolver                lowest_, largest_;
  DampedModes                      damped_;
  Vec                              U_           = nullptr;
  bool                             solved_      = false;
  PetscLogStage                    stage_setup_ = 0, stage_solve_ = 0;
  PetscLogEvent                    ev_assemble_ = 0, ev_output_ = 0;
  /* results */
  PetscReal      state_time_ = 0, omega_max_ = NAN, omega_max_residual_ = NAN, zeta_max_ = NAN;
  PetscLogDouble t0_ = 0, wall_ = 0, assemble_time_ = 0;
};

} // namespace turgor
