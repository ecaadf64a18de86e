#pragma once
/* Loss of stability along a run: every N steps (-fe2_eigen_monitor N, -mode fe2) or converged load
   levels (-fe2_static_eigen_monitor N, -mode fe2_static) the lowest eigenvalues of the stiffness K
   with M as the metric (K phi = lambda M phi, shift-and-invert about 0: PencilEigensolver) at the
   current state. The first check whose lowest eigenvalue is <= 0 after one > 0 is the loss of
   stability (a bifurcation or limit point: buckling, a snap-through, K no longer positive definite);
   its place is interpolated linearly in lambda between the two checks (lambda of a buckling mode is
   close to linear in the load). Outputs: stability.csv (one row per check), and at the first
   crossing stability.h5/.xmf with both states (the last stable one and the first unstable one)
   and each one's lowest mode (vertex vector "mode", largest vertex displacement 1 µm), for
   ParaView; the summary gets the crossing.

   The material points are evaluated for output (CoarseModel::AssembleTangentAt): a monitored run
   takes the same steps as an unmonitored one; the monitor's material work counts as output solves.
   Its EPS: -<prefix>eigen_monitor_eps_*, -<prefix>eigen_monitor_st_*. */
#include <turgor/analysis/coarse_operators.h>
#include <turgor/analysis/pencil_eigensolver.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/io/output.h>
#include <memory>
#include <string>

namespace turgor {

class StabilityMonitor {
public:
  explicit StabilityMonitor(MPI_Comm comm) : comm_(comm), solver_(comm) { }
  ~StabilityMonitor();
  StabilityMonitor(const StabilityMonitor &)            = delete;
  StabilityMonitor &operator=(const StabilityMonitor &) = delete;

  /* -<prefix>eigen_monitor N (0: off), -<prefix>eigen_monitor_modes k; `unit` names what N counts
     ("steps", "converged load levels") and `abscissa` the column of stability.csv ("time",
     "load_factor"). */
  PetscErrorCode SetFromOptions(const std::string &prefix, const char *unit, const char *abscissa);
  bool           Active() const { return every_ > 0; }
  bool           Lost() const { return lost_; }
  /* After the model's SetUp; `dir` the run's output directory, or empty for no files (-help). */
  PetscErrorCode SetUp(CoarseModel &model, const std::string &dir);
  /* At the count-th step or level (0: the initial state) with abscissa value t and model state U:
     checks when count is a multiple of N. */
  PetscErrorCode Check(PetscInt count, PetscReal t, Vec U);
  /* Summary keys: eigen_monitor_every, eigen_monitor_checks, eigen_monitor_lowest (the last
     check's lowest eigenvalue), stability_lost, stability_crossing (and its bracket). */
  void AddSummary(JsonObject &js) const;
  /* For the run's final report: "" or the crossing. */
  std::string Report() const;
  /* stability.csv closed (collective): a write that failed is an error naming it. */
  PetscErrorCode CloseOutputs();

private:
  PetscErrorCode WriteCrossing(Vec U, PetscReal t);

  MPI_Comm                         comm_;
  PetscInt                         every_ = 0, modes_ = 3, checks_ = 0;
  std::string                      prefix_, unit_, abscissa_, dir_;
  CoarseModel                     *model_ = nullptr;
  std::unique_ptr<CoarseOperators> ops_;
  PencilEigensolver                solver_;
  CsvWriter                        csv_;
  CoarseFieldsWriter               fields_;
  Vec                              U_prev_ = nullptr, mode_prev_ = nullptr, work_ = nullptr, x_ = nullptr;
  PetscReal                        t_prev_ = 0, lambda_prev_ = NAN, lambda_last_ = NAN;
  bool                             lost_     = false;
  PetscReal                        crossing_ = NAN, bracket_[2] = {NAN, NAN};
  PetscLogEvent                    ev_check_ = 0;
};

} // namespace turgor
