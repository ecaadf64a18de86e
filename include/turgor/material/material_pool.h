#pragma once
/* Many material points evaluated at once on MPI sub-communicators (TW 562 §3.3: one RVE per coarse
   quadrature point, each on its own sub-communicator). The ranks are split into groups of
   -rve_comm_size ranks (PetscSubcomm, contiguous); the global points are dealt to the groups in
   balanced contiguous blocks, so a point always lives on the same group (its RVE keeps its warm
   start); inputs are gathered, each group evaluates its block, and the results come back to the
   ranks that own the points. */
#include <turgor/material/material_point.h>
#include <turgor/rve/rve.h>
#include <memory>
#include <vector>

namespace turgor {

class MaterialPointPool {
public:
  explicit MaterialPointPool(MPI_Comm comm) : comm_(comm) { }
  ~MaterialPointPool();
  MaterialPointPool(const MaterialPointPool &)            = delete;
  MaterialPointPool &operator=(const MaterialPointPool &) = delete;

  /* -material rve|neo_hookean, -rve_comm_size, -rve_tangent forward|central */
  PetscErrorCode SetFromOptions();
  /* This rank owns n_local points. Creates the groups and the points of this rank's group. */
  PetscErrorCode SetUp(PetscInt n_local);
  /* Collective. F, Fdot, out: n_local each. With D != NULL also the tangents (eqs 46-53). */
  PetscErrorCode Evaluate(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, Tangents *D = NULL);
  PetscErrorCode Commit();
  PetscErrorCode Revert();

  /* Totals over all points and ranks (collective). */
  PetscErrorCode GlobalCounters(RVECounters *c) const;
  /* Seconds spent in trial evaluations and in tangents, the largest over ranks (collective):
     always measured (two clock reads per point), unlike -log_view's events, whose per-call
     overhead on millions of small RVE solves would distort the timings being broken down. */
  PetscErrorCode GlobalTimes(PetscReal *trial_s, PetscReal *tangent_s) const;
  PetscInt       NumGlobal() const { return n_global_; }
  PetscInt       NumGroups() const { return n_groups_; }
  const char    *MaterialName() const { return material_; }
  TangentOptions &Tangent() { return tangent_; }
  /* The material points this rank's group evaluates (for inspection, tests). */
  MaterialPoint *GroupPoint(PetscInt k) const { return points_[k].get(); }
  PetscInt       GroupBegin() const { return begin_; }
  PetscInt       GroupEnd() const { return end_; }

private:
  MPI_Comm                                    comm_;
  PetscSubcomm                                subcomm_ = nullptr;
  char                                        material_[32] = "rve";
  PetscInt                                    comm_size_ = 1, n_local_ = 0, n_global_ = 0, offset_ = 0, n_groups_ = 1, begin_ = 0, end_ = 0;
  std::vector<std::unique_ptr<MaterialPoint>> points_; /* [begin_, end_) of this group */
  TangentOptions                              tangent_;
  PetscLogEvent                               ev_evaluate_ = 0, ev_tangents_ = 0;
  PetscLogDouble                              time_trial_ = 0, time_tangents_ = 0;
};

} // namespace turgor
