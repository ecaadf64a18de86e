#pragma once
/* Many material points evaluated at once on MPI sub-communicators (TW 562 §3.3: one RVE per coarse
   quadrature point, each on its own sub-communicator). The ranks are split into groups of
   -material_comm_size ranks (PetscSubcomm, contiguous); the global points are dealt to the groups in
   balanced contiguous blocks, so a point always lives on the same group (its RVE keeps its warm
   start). With -material_rebalance N the blocks are drawn once more after N evaluations, balanced by
   each point's measured cost so far (its force evaluations: a point near a clamp or a load relaxes
   longer; the time it took for a material without counters), and the points
   that change group move with their whole state (MaterialPoint::SaveState/LoadState), so the
   results stay the same bits. The material is configured once (MaterialModel) and creates every
   point.

   Traffic: two PetscSF built at set-up carry named structs -- the inputs (F, Fdot) from the rank
   that owns a point to the ranks of the group that evaluates it, and the results (stress, density,
   tangents, counts) back from the group's first rank. A rank sends and receives only the points
   whose owner and evaluating group differ; failure reasons travel only when something failed. */
#include <turgor/material/material_point.h>
#include <petscsf.h>
#include <memory>
#include <vector>

namespace turgor {

class MaterialPointPool {
public:
  explicit MaterialPointPool(MPI_Comm comm) : comm_(comm) { }
  ~MaterialPointPool();
  MaterialPointPool(const MaterialPointPool &)            = delete;
  MaterialPointPool &operator=(const MaterialPointPool &) = delete;

  /* API defaults, before SetFromOptions (options still win). */
  void SetMaterialType(const std::string &name) { type_ = name; }
  /* A configured material (tests, programs): -material is then not read. */
  void SetMaterial(std::unique_ptr<MaterialModel> model) { model_ = std::move(model); }
  /* The accuracy the caller needs of a stress evaluation (MaterialModel::SetDefaultTolerance). */
  void            SetDefaultTolerance(PetscReal tol) { default_tol_ = tol; }
  TangentOptions &Tangent() { return tangent_; }
  void            SetCommSize(PetscInt size) { comm_size_ = size; }

  /* -material (API default rve) and that material's options; -material_comm_size,
     -material_tangent forward|central|implicit, -material_tangent_fdot_typ. */
  PetscErrorCode SetFromOptions(ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
  /* This rank owns n_local points. Creates the groups, the points of this rank's group and the
     communication pattern. */
  PetscErrorCode SetUp(PetscInt n_local);
  /* Collective. F, Fdot, out: n_local each. With `tangents` (the same on every rank) also the
     tangents into D (eqs 46-53; NULL on a rank without points: its group still computes the
     tangents of the points it evaluates for the others). kind Perturbed: an evaluation that leaves
     the points' current states as they are (output). */
  PetscErrorCode Evaluate(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, bool tangents, Tangents *D,
                          EvaluationKind kind = EvaluationKind::Trial);
  PetscErrorCode Commit();
  PetscErrorCode Revert();
  /* Declared state: this group's points as records keyed by their ids (ids[g]: a numbering of the
     points that does not depend on the ranks; each rank of a group writes its own part of each), every
     point's state nested in its row (MaterialPoint::DeclareState), and the block of points the group
     evaluates. AfterStateRead (collective) takes the checkpoint's block where this rank holds what its
     writer held (a rebalanced run's blocks), else keeps its blocks by count, and hands each point its
     state. */
  PetscErrorCode DeclareState(StateDeclaration &d, const std::vector<PetscInt> &ids);
  PetscErrorCode AfterStateRead(bool own_layout);
  PetscInt       CommSize() const { return comm_size_; }

  /* Totals over all points and ranks (collective). */
  PetscErrorCode GlobalCounters(MaterialCounters *c) const;
  /* summary.json: the material's make-up (MaterialModel::Describe) and, where its points have glue or
     contact, the bonds intact and broken and the contacts per point, averaged over the `points`
     points (collective). */
  PetscErrorCode DescribePoints(JsonObject &js, PetscInt points) const;
  /* Seconds spent in trial evaluations and in tangents, the largest over ranks (collective):
     always measured (two clock reads per point), unlike -log_view's events, whose per-call
     overhead on millions of small RVE solves would distort the timings being broken down. */
  PetscErrorCode GlobalTimes(PetscReal *trial_s, PetscReal *tangent_s) const;
  void           ResetTimes() { time_trial_ = time_tangents_ = 0; } /* from here on */
  /* Bytes that cross between ranks in one evaluation, summed over all ranks (inputs + results). */
  PetscInt             RemoteBytesPerEvaluation() const { return remote_bytes_; }
  PetscInt             NumGlobal() const { return n_global_; }
  PetscInt             NumGroups() const { return n_groups_; }
  const MaterialModel &Model() const { return *model_; }
  const char          *MaterialName() const { return model_ ? model_->Name() : type_.c_str(); }
  /* The material points this rank's group evaluates (for inspection, tests). */
  MaterialPoint *GroupPoint(PetscInt k) const { return points_[k].get(); }
  PetscInt       GroupBegin() const { return begin_; }
  PetscInt       GroupEnd() const { return end_; }
  /* -material_rebalance: the largest group's measured cost over the mean, before and after the
     rebalancing (1 before it happened), and the points moved. */
  PetscReal CostImbalanceBefore() const { return imbalance_before_; }
  PetscReal CostImbalanceAfter() const { return imbalance_after_; }
  PetscInt  PointsMoved() const { return moved_; }

private:
  MPI_Comm                                    comm_;
  std::string                                 type_ = "rve";
  std::unique_ptr<MaterialModel>              model_; /* before points_: they are destroyed first */
  PetscReal                                   default_tol_ = 0;
  PetscSubcomm                                subcomm_     = nullptr;
  PetscInt                                    comm_size_ = 1, n_local_ = 0, n_global_ = 0, n_groups_ = 1, begin_ = 0, end_ = 0;
  PetscMPIInt                                 group_rank_ = 0;
  std::vector<std::unique_ptr<MaterialPoint>> points_; /* [begin_, end_) of this group */
  TangentOptions                              tangent_;
  PetscSF                                     in_sf_ = nullptr, out_sf_ = nullptr; /* roots: owned points; leaves: the group's block */
  MPI_Datatype                                in_type_ = MPI_DATATYPE_NULL, out_type_ = MPI_DATATYPE_NULL, reason_type_ = MPI_DATATYPE_NULL;
  PetscInt                                    remote_bytes_ = 0;
  PetscLogEvent                               ev_evaluate_ = 0, ev_tangents_ = 0;
  PetscLogDouble                              time_trial_ = 0, time_tangents_ = 0;
  /* -material_rebalance */
  PetscInt               rebalance_after_ = 0, evaluations_ = 0, moved_ = 0;
  PetscReal              skip_tolerance_ = 0; /* -material_skip_tolerance [N/m]; 0: every evaluation solves */
  std::vector<PetscReal> cost_;               /* [block] seconds each point of this group took so far */
  PetscReal              imbalance_before_ = 1, imbalance_after_ = 1;
  PetscErrorCode         BuildTraffic(); /* the SFs of [begin_, end_) */
  /* this group's points become [begin, end); the new ones take their state from states[g - begin]
     (PackPoint's numbers; none: they start afresh) */
  PetscErrorCode SetBlock(PetscInt begin, PetscInt end, std::vector<std::vector<PetscReal>> *states);
  /* a point's declared state as one sequence of numbers (a rebalance moves it), and back */
  /* A point of the material on `group`, wrapped in a SkippingPoint with -material_skip_tolerance. */
  PetscErrorCode        CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const;
  static PetscErrorCode PackPoint(MaterialPoint &p, std::vector<PetscReal> &out);
  static PetscErrorCode UnpackPoint(MaterialPoint &p, const PetscReal *in, size_t n);
  struct SavedPoint { /* a point's row of a checkpoint: its global index here, its nested state */
    PetscInt                            point;
    std::vector<std::vector<PetscReal>> columns;
  };
  std::vector<SavedPoint>        saved_;
  PetscErrorCode                 ShareSavedStates(); /* the group's first rank's saved_ to the others */
  std::unique_ptr<MaterialPoint> prototype_;         /* a point of this material, for the names of its state */
  PetscInt                       saved_begin_ = 0, saved_end_ = 0;
  PetscErrorCode                 Rebalance();
  PetscErrorCode                 EvaluateBlock(const Tensor2 *F, const Tensor2 *Fdot, MaterialResponse *out, bool tangents, Tangents *D, EvaluationKind kind);
  std::vector<PetscInt>          offsets_; /* [ranks + 1] the owners' blocks of points */
};

} // namespace turgor
