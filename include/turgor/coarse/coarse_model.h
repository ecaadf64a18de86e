#pragma once
/* The coarse (tissue) model of FE^2 (TW 562 §3.3): a DMPlex of quadrilaterals carrying Lagrange
   elements (-coarse_element): bilinear Q1 (the seed's; nodes at the vertices) or biquadratic Q2
   (also at the edge midpoints and the cell centres), the displacement u and velocity v at every
   node (state per node [ux, uy, vx, vy]), material points from a MaterialPointPool at the points
   of the element's quadrature rule (-coarse_quadrature): sri, selective reduced integration, the
   deviatoric stress at the full Gauss points and the pressure tr(sigma)/2 at fewer points (Q1: the
   2 x 2 Gauss points and the centre, 5 per element, the seed's; Q2: 3 x 3 and 2 x 2, 13), or full,
   the whole stress at the full Gauss points (Q1: 2 x 2, 4 per element; Q2: 3 x 3, 9).

   Semi-discrete system (eqs 31-33) as a linearly implicit first-order system
       F(U, Udot) = Mt Udot - G(U) = 0,   Mt = diag(I, M),   G = [v; f_ext - f_int(u, v)],
   with M the consistent (or lumped) mass matrix, f_int the internal force from the Cauchy stress,
   f_ext the body force. Its Jacobian dF/dU + shift dF/dUdot = shift Mt + [[0, -I], [K, C]] uses
   the stiffness K = initial-stress part + constitutive part with D^e (eqs 35-37) and the damping C
   with D^v (eqs 38-39), consistent with the residual of either rule (one assembly: each point's
   stress and tangent enter through its part, whole, deviatoric or pressure). The mesh and the
   essential condition are PETSc's (DMSetFromOptions, a Q1 PetscFE section, DMAddBoundary): the
   vertices on the Dirichlet label values are constrained (all four dofs; displacement from
   SetBoundaryDisplacement, zero by default, velocity zero); the assembly is our own. */
#include <turgor/coarse/surface_membrane.h>
#include <turgor/core/parameters.h>
#include <turgor/material/material_pool.h>
#include <turgor/material/second_order_work.h>
#include <turgor/physics/load_spec.h>
#include <petscdmplex.h>
#include <petscksp.h>
#include <functional>
#include <memory>
#include <string>
#include <deque>
#include <vector>

namespace turgor {

struct ReferenceElement; /* src/coarse/reference_element.h */

/* -coarse_element: the Lagrange quadrilateral (src/coarse/q1_element.h, q2_element.h) */
enum class CoarseElement {
  Q1, /* bilinear, 4 nodes (the seed's) */
  Q2  /* biquadratic, 9 nodes */
};

/* -coarse_quadrature: the material points of an element */
enum class CoarseQuadrature {
  SRI, /* selective reduced integration: deviator at the full Gauss points, pressure at fewer */
  Full /* the whole stress at the full Gauss points */
};

struct CoarseCounters {
  PetscInt residuals = 0, jacobians = 0, material_evals = 0, tangent_evals = 0, failures = 0;
};

/* -coarse_ options besides the mesh's (API defaults; options win). */
struct CoarseSpec {
  std::string           dirichlet_label  = "Face Sets";
  std::vector<PetscInt> dirichlet_values = {4}; /* box: 1 bottom, 2 right, 3 top, 4 left */
  bool                  lumped_mass      = false;
  CoarseElement         element          = CoarseElement::Q1;
  CoarseQuadrature      quadrature       = CoarseQuadrature::SRI;
  bool                  acoustic_field   = true;  /* snapshots carry the acoustic-tensor field (material tangents at output) */
  bool                  metis            = false; /* -coarse_partitioner metis: the serial mesh distributed by METIS (a PETSCPARTITIONERSHELL) */
  /* -coarse_boundary_gradient: the clamped vertices at u = lambda H X (-mode fe2_static's load factor
     lambda; H = 0: clamped in place) */
  Tensor2 boundary_gradient;

  bool HasBoundaryGradient() const { return boundary_gradient.Norm() > 0; }
  /* modes without a load factor refuse a boundary gradient, naming themselves */
  PetscErrorCode RequireNoBoundaryGradient(MPI_Comm comm, const char *mode) const;

  PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params = nullptr); /* params: where the physics parameters are recorded */
};

class CoarseModel {
public:
  explicit CoarseModel(MPI_Comm comm);
  ~CoarseModel();
  CoarseModel(const CoarseModel &)            = delete;
  CoarseModel &operator=(const CoarseModel &) = delete;

  /* -coarse_* options (Dirichlet label and values, mass; the mesh's -coarse_dm_* are read by
     DMSetFromOptions at SetUp) and the pool's. */
  PetscErrorCode SetFromOptions(ParameterList *params = nullptr);
  /* The scene's loads (the body force); before SetUp. */
  void SetLoad(const LoadSpec &load)
  {
    for (int d = 0; d < 2; d++) g_[d] = load.body_acceleration[d];
  }
  /* Override the mesh before SetUp (tests distort it); the model takes a reference. */
  PetscErrorCode SetMesh(DM dm);
  PetscErrorCode SetUp();
  /* Boundary displacement g(X) on constrained vertices (default 0); call before SetUp or between
     evaluations. */
  PetscErrorCode SetBoundaryDisplacement(std::function<void(const PetscReal X[2], PetscReal u[2])> g);

  /* F = Mt Udot - G(U). *ok = false (F filled with NaN) when a material point failed. */
  PetscErrorCode IFunction(Vec U, Vec Udot, Vec F, PetscBool *ok);
  /* J = shift Mt + [[0, -I], [K, C]] at U. With refresh = false the K and C of the last fresh
     Jacobian are reused (a modified Newton iteration: no material tangents); only the shift part
     changes. */
  PetscErrorCode IJacobian(Vec U, PetscReal shift, Mat J, PetscBool *ok, bool refresh = true);
  /* [[0, -I], [K, C]] at U into J (a matrix of MassMatrix()'s pattern), without the shift: the same
     assembly as IJacobian's, with C from D^v when `damping` (C = 0 otherwise: D^v is then not
     computed). The material points are evaluated for output (EvaluationKind::Output, tangents
     included): their states, the material cache and the K, C kept for the integrator stay as they
     are, so an analysis during a run (an eigen monitor) does not change the run; the work is
     counted as output solves. *ok = false when a material point failed, *why says where. Also
     fills CellAcoustic() at U. */
  PetscErrorCode AssembleTangentAt(Vec U, bool damping, Mat J, PetscBool *ok, std::string *why);
  /* Seconds this rank spent in the coarse model's own work inside IFunction, IJacobian and
     RHSFunction: the assembly of f_int, K, C and the explicit integrators' mass solves (the
     material points excluded: MaterialPointPool::GlobalTimes). */
  PetscReal CoarseAssemblyTime() const { return (PetscReal)coarse_time_; }
  /* Jacobians assembled from the same K, C since they were last computed. */
  PetscInt TangentAge() const { return tangent_age_; }
  /* Udot = Mt^{-1} G(U) (explicit integrators). */
  PetscErrorCode RHSFunction(Vec U, Vec G, PetscBool *ok);
  /* Evaluate (and cache) the material points at U; *ok = false on any failure, *why says which. */
  PetscErrorCode EvaluateMaterials(Vec U, bool tangents, PetscBool *ok, std::string *why);
  PetscErrorCode CommitMaterials() { return pool_.Commit(); }
  /* Declared state (at an accepted state, after CommitMaterials): the counters, the material cache
     (the last evaluation's deformations and responses by point id: an explicit integrator's next
     stage at the accepted state finds it, as in the uninterrupted run) and every material point's
     state (MaterialPointPool::DeclareState). The K, C kept for implicit integrators are not kept
     (their checkpoints are refused). AfterStateRead: on another layout the cache is kept when it was
     of the checkpoint's state U on every writing rank (an explicit integrator's last stage). The
     unknowns are numbered in an order of their nodes' reference positions (RankFreeStateOrder:
     each local entry's index in it), the material points in an order of their element's centre
     (RankFreePointIds: in the pool's global order, all points) -- coarse_numbering.cpp. */
  PetscErrorCode DeclareState(std::deque<StateDeclaration> &decls, Vec U);
  PetscErrorCode AfterStateRead(Vec U, bool own_layout);
  PetscErrorCode RankFreeStateOrder(IS *order);
  PetscErrorCode RankFreePointIds(std::vector<PetscInt> &global);
  /* The pool's global index of this rank's first point (the coarse model's points are this rank's
     cells' points in turn). */
  PetscInt FirstPoint() const { return first_point_; }
  /* The lowest global element number with a failed material point in the last failed evaluation
     (-1: none failed yet); the same on every rank. */
  PetscInt LastFailedElement() const { return failed_element_; }
  /* Did the last EvaluateMaterials find no stress at some material point (its relaxation failed;
     not only its tangents' linear solve)? And how many evaluations did so, since the set-up (not
     checkpointed)? A tangent that fails at a found equilibrium is not a missing equilibrium. */
  bool     LastStressFailed() const { return last_stress_failed_; }
  PetscInt StressFailures() const { return stress_failures_; }
  /* Back to the material points' last committed states (a rejected load increment); the cache is
     dropped. */
  PetscErrorCode RevertMaterials();
  /* The time of the states evaluated next (failure reports say when). */
  void SetEvaluationTime(PetscReal t)
  {
    eval_time_ = t;
    eval_where_.clear();
  }
  /* Failure reports say this instead of a time (a static solve: "at load factor 0.5"). */
  void SetEvaluationWhere(const std::string &where) { eval_where_ = where; }
  /* f_ext = factor x the body force and the clamped vertices at factor x H X (load stepping;
     default 1). */
  PetscErrorCode SetLoadFactor(PetscReal factor);
  PetscReal      LoadFactor() const { return load_factor_; }
  /* The global rows of the displacement dofs (ux, uy) and of the velocity dofs (vx, vy; there
     f_int - f_ext) of the owned, unclamped vertices, vertex by vertex in the same order. */
  PetscErrorCode CreateFreeIS(IS *displacement, IS *velocity) const;

  DM                       GetDM() const { return dm_; }
  Mat                      MassMatrix() const { return Mt_; }
  MaterialPointPool       &Pool() { return pool_; }
  const MaterialPointPool &Pool() const { return pool_; }
  const CoarseCounters    &Counters() const { return counters_; }
  PetscInt                 NumElements() const { return n_elements_; } /* global */
  PetscInt                 NumMaterialPoints() const { return pool_.NumGlobal(); }
  PetscReal                ReferenceDensity() const { return rho0_; }
  bool                     LumpedMass() const { return spec_.lumped_mass; }
  CoarseSpec              &Spec() { return spec_; }
  const CoarseSpec        &Spec() const { return spec_; }
  /* The element and quadrature rule in use (after SetUp): material points and nodes per element,
     their names. */
  PetscInt    PointsPerElement() const;
  PetscInt    NodesPerElement() const;
  const char *ElementName() const;
  const char *QuadratureName() const;
  const char *QuadratureDescription() const;
  /* Displacement of the middle of the right side, vertical and (ux) horizontal (all ranks). */
  PetscErrorCode TipDisplacement(Vec U, PetscReal *uy, PetscReal *ux = nullptr);
  /* Per local cell, [s11, s22, s12]: the mean Cauchy stress of its material points (sri: the mean
     deviator of the Gauss points with the centre pressure), at U, into CellStress(). For output:
     the material points' states and the cache of EvaluateMaterials stay as they are, so writing a
     snapshot does not change the run. */
  PetscErrorCode                EvaluateCellStress(Vec U, PetscBool *ok);
  const std::vector<PetscReal> &CellStress() const { return cell_stress_; }
  /* Per local cell, the smallest over its material points of min_n det Q(n), Q the acoustic tensor
     of the point's D^e and stress (material/acoustic_tensor.h) [(N/m)^2]: <= 0 where the
     incremental problem loses ellipticity. Filled by EvaluateCellStress when
     Spec().acoustic_field (tangents at output: 3 more material evaluations per point), and by
     AssembleTangentAt; NaN for a cell whose points failed. */
  const std::vector<PetscReal> &CellAcoustic() const { return cell_acoustic_; }
  /* The smallest CellAcoustic() over all elements and its element's global number (collective;
     PETSC_MAX_REAL and -1 where no element has one). */
  PetscErrorCode LowestAcoustic(PetscReal *det, PetscInt *element) const;
  /* Hill's second-order work (material/second_order_work.h) of every material point from the
     state of the previous call to this one, both the cached evaluation when called (a quasi-static
     solve calls it at each converged load level): the lowest cosine of dS : dE over all points and
     its element's global number (collective; 1 and -1 at the first call, which only records the
     state). A cosine below zero is a point whose stress fell along its strain increment. Stress
     increments below stress_floor x |S| are not judged (the materials' own accuracy). */
  PetscErrorCode SofteningSinceLast(PetscReal stress_floor, PetscReal *cosine, PetscInt *element);
  /* The mean Cauchy stress [s11, s22, s12] of the cached evaluation over the mesh, the material
     points weighted by their quadrature weights (reference area); collective. */
  PetscErrorCode MeanStress(PetscReal s[3]) const;
  PetscErrorCode CreateGlobalVector(Vec *U) const { return DMCreateGlobalVector(dm_, U); }
  /* U (global) from a function of the reference position: f(X, state) gives [ux, uy, vx, vy] of the
     node at X, or false when it has none; the clamped nodes are left out. The nodes are the
     vertices (Q1), and also the edge midpoints and cell centres (Q2). Collective: *missing is the
     first position without a value on any rank ("" when every node got one). */
  PetscErrorCode NodeState(Vec U, const std::function<bool(const PetscReal X[2], PetscReal state[4])> &f, std::string *missing);
  /* Global vector with the boundary values inserted into the local constrained dofs. */
  PetscErrorCode GlobalToLocal(Vec U, Vec Uloc);
  /* The boundary values (u = g(X), v = 0) into the constrained dofs of a local vector. */
  PetscErrorCode InsertBoundaryValues(Vec Uloc);

private:
  static PetscErrorCode BoundaryValues(PetscInt dim, PetscReal time, const PetscReal X[], PetscInt Nc, PetscScalar *u, void *ctx);
  PetscErrorCode        CreateMesh();
  PetscErrorCode        DistributeWithMetis(); /* -coarse_partitioner metis */
  /* for failure reports: point m of the evaluation (F, Fdot, r) */
  PetscErrorCode DescribePoint(PetscInt m, const std::vector<Tensor2> &F, const std::vector<Tensor2> &Fdot, const std::vector<MaterialResponse> &r,
                               std::string *text) const;
  PetscErrorCode CheckSize(PetscReal elements); /* memory and PetscInt range of the material points */
  PetscErrorCode CreateSection();
  PetscErrorCode PrecomputeElements();
  PetscErrorCode AssembleMass();
  PetscErrorCode InternalForce(Vec Floc); /* local [0; f_int - f_ext] from the cached materials */
  /* [[0, -I], [K, C]] into J from the material points' F, responses and tangents (per local point) */
  PetscErrorCode AssembleKC(const std::vector<Tensor2> &F, const std::vector<MaterialResponse> &r, const std::vector<Tangents> &D, Mat J);
  /* the material points at the local state Uloc for output, with tangents (D^v when viscous) into
     out_tangent_, leaving the points and the cache as they are; *ok on all ranks, *why this rank's
     first failure */
  PetscErrorCode EvaluateForOutput(Vec Uloc, bool viscous, PetscBool *ok, std::string *why);
  void           AcousticFromOutput(); /* cell_acoustic_ from out_response_, out_tangent_ */
  /* F and Fdot at the material points of this rank's cells, from the local state */
  PetscErrorCode DeformationAt(Vec Uloc, std::vector<Tensor2> &F, std::vector<Tensor2> &Fdot);
  /* true when the cached evaluation is of this local state (collective) */
  PetscErrorCode CacheHolds(Vec Uloc, bool tangents, bool *holds);
  PetscErrorCode FillNaN(Vec F);
  /* the smallest finite per-cell value and its element's global number (collective; PETSC_MAX_REAL
     and -1 where no cell has one; ties: the lowest number) */
  PetscErrorCode        LowestOverCells(const std::vector<PetscReal> &per_cell, PetscReal *value, PetscInt *element) const;
  PetscErrorCode        ComputeRankFreeStateOrder(IS *order);
  PetscErrorCode        ComputeRankFreeCellIds();   /* cell_id_ */
  IS                    rank_free_order_ = nullptr; /* RankFreeStateOrder's, made at the first call */
  std::vector<PetscInt> rank_free_ids_;             /* RankFreePointIds', likewise */

  MPI_Comm          comm_;
  DM                dm_ = nullptr;
  MaterialPointPool pool_;
  Mat               Mt_          = nullptr; /* diag(I, M) */
  Mat               KC_          = nullptr; /* [[0, -I], [K, C]] of the last fresh Jacobian */
  PetscInt          tangent_age_ = 0;
  KSP               mass_ksp_    = nullptr;
  Vec               Uloc_ = nullptr, Floc_ = nullptr;
  Vec               rhs_r_ = nullptr, rhs_z_ = nullptr; /* RHSFunction work vectors */

  /* options */
  CoarseSpec                                                spec_;
  SurfaceMembrane                                           skin_; /* -coarse_skin_*: a membrane along boundary faces */
  PetscReal                                                 g_[2]        = {0.0, -0.2};
  PetscReal                                                 load_factor_ = 1.0;
  std::function<void(const PetscReal X[2], PetscReal u[2])> boundary_;

  /* the element tabulated at its rule: material points and nodes per element (from spec_ at SetUp) */
  std::unique_ptr<ReferenceElement> ref_;
  PetscInt                          npts_ = 0, nn_ = 0;
  /* per local cell: reference vertex coordinates, gradients and weights at the material points */
  PetscInt                 c_start_ = 0, c_end_ = 0;
  std::vector<PetscReal>   Xref_;      /* [cell][4][2] (the geometry: the vertices) */
  std::vector<PetscReal>   dN_;        /* [cell][point][node][2] */
  std::vector<PetscReal>   wdet_;      /* [cell][point]: weight x det(dX/dxi) */
  std::vector<PetscReal>   f_ext_;     /* [cell][node][2] */
  std::vector<PetscInt>    free_rows_; /* global row of ux of each owned, unclamped node */
  std::vector<PetscScalar> work_;      /* an element vector and matrix, (4 nodes)^2 + 4 nodes */
  PetscInt                 v_start_ = 0, v_end_ = 0;
  struct {
    PetscInt  a = -1, b = -1, e = -1; /* the tip's mesh edge and its end vertices (e = -1: on another rank) */
    PetscReal sp = 0;                 /* the tip's position along it, 0 at a, 1 at b */
  } tip_;
  PetscReal             rho0_       = 0;
  PetscInt              n_elements_ = 0;
  std::vector<PetscInt> cell_gid_; /* global element number of each local cell (PETSc's: it depends on the partition) */
  /* each local cell's element number in the order of the elements' centres (row by row: y, then x;
     a box's serial numbering), the same on any number of ranks: the number reports give */
  std::vector<PetscInt> cell_id_;
  PetscMPIInt           rank_               = 0;
  PetscReal             eval_time_          = 0;                                /* time of the state being evaluated (for reports) */
  PetscInt              failed_element_     = -1;                               /* LastFailedElement() */
  bool                  last_stress_failed_ = false, cached_stress_ok_ = false; /* LastStressFailed(), and that of the cached evaluation */
  PetscInt              stress_failures_ = 0;                                   /* StressFailures() */
  std::string           eval_where_;                                            /* or where, when not a time */

  /* material cache */
  std::vector<PetscScalar>      cached_U_;
  bool                          cache_stale_  = false; /* a checkpoint's: some writer's cache was not of its state */
  PetscInt                      first_point_  = 0;
  bool                          cached_valid_ = false, cached_tangents_ = false, cached_ok_ = false;
  std::vector<Tensor2>          F_, Fdot_;
  std::vector<MaterialResponse> response_;
  std::vector<Tangents>         tangent_;
  std::vector<PetscReal>        cell_stress_;
  std::vector<Tensor2>          out_F_, out_Fdot_; /* EvaluateCellStress's own, outside the cache */
  std::vector<MaterialResponse> out_response_;
  std::vector<Tangents>         out_tangent_;
  std::vector<PetscReal>        cell_acoustic_;
  std::vector<StrainStress>     softening_last_; /* SofteningSinceLast's previous state, per local point */
  CoarseCounters                counters_;
  PetscLogDouble                coarse_time_ = 0; /* CoarseAssemblyTime() */
  PetscLogEvent                 ev_residual_ = 0, ev_jacobian_ = 0, ev_tangent_at_ = 0;
};

} // namespace turgor
