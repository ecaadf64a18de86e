#pragma once
/* The material-point interface of the coarse model: given a deformation gradient F and its rate
   Fdot, return the Cauchy stress sigma and density rho (TW 562 eq 30, 41), and -- through
   ComputeTangents() -- the elasticity and viscosity matrices D^e, D^v (eqs 37, 39) by the finite
   differences of eqs 46-53, or exactly from the material's StressDerivatives() (an RVE: implicit
   differentiation of its relaxed state).

   A MaterialModel is a material configured once from its options (an RVE's geometry, physics and
   relaxation settings; a closed-form law's constants); it creates the material points, one per
   coarse quadrature point, each on its group's communicator. A new material is one file (a
   MaterialModel and its MaterialPoint) plus one line in src/app/register_all.cpp:
   MaterialModelRegister("name", CreateInstance<MaterialModel, Model>).

   An evaluation never aborts: a material point that cannot answer (no convergence, NaN, inverted
   element) returns ok = false with its reason, so that the caller can reject a step and retry. */
#include <turgor/core/parameters.h>
#include <turgor/core/registry.h>
#include <turgor/io/declared_state.h>
#include <turgor/core/tensor2.h>
#include <petscviewer.h>
#include <memory>
#include <string>
#include <vector>

namespace turgor {

class JsonObject;

struct MaterialResponse {
  Tensor2     sigma;   /* Cauchy stress, 2D [N/m] */
  PetscReal   rho = 0; /* current 2D density [ng/µm^2] */
  bool        ok  = true;
  std::string reason;                 /* why not ok */
  bool        tangent_failed = false; /* not ok only because its tangents failed: the stress was found */
  PetscInt    iterations     = 0;     /* Psi-tc iterations (RVE) */
  PetscInt    snes_its = 0, ksp_its = 0;
  PetscReal   residual = 0; /* final scaled residual norm (RVE) */
};

/* Work done by material points (summed over points and ranks by the pool). */
struct MaterialCounters {
  PetscInt solves = 0, failures = 0, iterations = 0, snes_its = 0, ksp_its = 0, jacobians = 0, force_evals = 0;
  PetscInt tangent_solves     = 0;                          /* perturbed solves (eqs 46-53), included in solves */
  PetscInt output_solves      = 0;                          /* for snapshots, in no other counter */
  PetscInt exact_tangents     = 0;                          /* tangents by StressDerivatives (no perturbed solves) */
  PetscInt tangent_linear_its = 0, tangent_force_evals = 0; /* their Krylov iterations and force evaluations */
  PetscInt predicted_solves = 0;                            /* warm solves that converged from the tangent's prediction */
  PetscInt skipped_solves   = 0;                            /* trial evaluations answered by the last solve's expansion (skipping_point.h) */
  /* Polygon RVEs: glue bonds intact and broken, contacts per evaluation (the points' sum) */
  PetscInt bonds_intact = 0, bonds_broken = 0, contacts = 0;
};

/* Trial: the evaluation becomes the material point's current state (later evaluations start from
   it). Perturbed: a tangent perturbation; starts from the current state and leaves it unchanged.
   Output: as Perturbed, for a snapshot: counted apart (output_solves), so that the work counters
   of a run do not depend on how often it writes. */
enum class EvaluationKind {
  Trial,
  Perturbed,
  Output
};

struct Tangents;

class MaterialPoint {
public:
  virtual ~MaterialPoint()                                                                                           = default;
  virtual PetscErrorCode Evaluate(const Tensor2 &F, const Tensor2 &Fdot, EvaluationKind kind, MaterialResponse *out) = 0;
  /* Accept the current state (after a coarse step is accepted) / return to the last accepted one. */
  virtual PetscErrorCode Commit() { return PETSC_SUCCESS; }
  virtual PetscErrorCode Revert() { return PETSC_SUCCESS; }
  /* The uncertainty U of a stress evaluation: eq 52 takes eps = sqrt(U). */
  virtual PetscReal StressUncertainty() const = 0;
  /* Exact directional derivatives of the stress at the state of the last evaluation, which was at
     (F, Fdot) and succeeded: dsigma[k] = d/de sigma(F + e dF[k], Fdot + e dFdot[k]) at e = 0, for
     k < n, through the material's inner unknowns (an RVE's relaxed fine structure) by implicit
     differentiation. Leaves the material's state as it is; kind says how the work is counted. On
     failure status->ok = false and its reason. The default has none (MaterialModel::
     HasStressDerivatives). */
  virtual PetscErrorCode StressDerivatives(const Tensor2 &F, const Tensor2 &Fdot, PetscInt n, const Tensor2 *dF, const Tensor2 *dFdot, EvaluationKind kind,
                                           Tensor2 *dsigma, MaterialResponse *status);
  /* The tangents the pool computed at this point's last trial evaluation, (F, Fdot) and its response
     r (a point that expands about its solved states keeps them: skipping_point.h). */
  virtual void KeepTangents(const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &r, const Tangents &D) { }
  virtual void AddCounters(MaterialCounters &c) const { }
  /* Declared state (io/declared_state.h; nested in the pool's table of points, whole, since a point
     moves whole): everything the point keeps between evaluations that decides its next answer bit
     for bit (an RVE: its current and committed fine state, the kept Jacobian, the neighbour lists)
     and its work counters. Each rank of the point's group declares its own part. AfterStateRead,
     once the state was read into the declaration (or a rebalance moved the point here), rebuilds
     what derives from it (collective on the group). A point without such state (a closed-form law)
     declares nothing. */
  virtual void           DeclareState(StateDeclaration &d) { }
  virtual PetscErrorCode AfterStateRead() { return PETSC_SUCCESS; }
};

class MaterialModel {
public:
  virtual ~MaterialModel()         = default;
  virtual const char *Name() const = 0;
  /* The accuracy a caller needs of a stress evaluation, as a default before SetFromOptions (the
     material's own options still win); materials without an iterative solve ignore it. */
  virtual void           SetDefaultTolerance(PetscReal tol) { }
  virtual PetscErrorCode SetFromOptions(MPI_Comm comm, ParameterList *params) = 0; /* params: the physics parameters read (may be NULL) */
  /* A material point on `group` (collective on it). */
  virtual PetscErrorCode CreatePoint(MPI_Comm group, std::unique_ptr<MaterialPoint> *point) const = 0;
  /* For summaries: the physics inside a point, and its particles (0 for closed forms). */
  virtual std::vector<std::string> Physics() const = 0;
  virtual void                     ParticlesPerPoint(PetscInt *wall, PetscInt *fluid) const { *wall = *fluid = 0; }
  /* Memory of one material point (estimates before the points are created). */
  virtual PetscReal BytesPerPoint() const { return 256; }
  /* Its points implement MaterialPoint::StressDerivatives (-material_tangent implicit). */
  virtual bool           HasStressDerivatives() const { return false; }
  virtual PetscErrorCode View(PetscViewer viewer) const = 0;
  /* A material point's make-up for summary.json (a polygon RVE: its cells, nodes, bars, images). */
  virtual void Describe(JsonObject &js) const { }
};

using MaterialModelCreator = Registry<MaterialModel>::Creator;
PetscErrorCode MaterialModelRegister(const char name[], MaterialModelCreator create);
PetscErrorCode MaterialModelCreate(MPI_Comm comm, const std::string &name, std::unique_ptr<MaterialModel> *model);
std::string    MaterialModelNames();

/* D^e, D^v as 3 x 3 matrices in the order (11, 22, 12) of eqs 37 and 39. */
struct Tangents {
  PetscReal De[3][3] = {}, Dv[3][3] = {};
};

/* -material_tangent: forward differences (eqs 46-53, the seed's), central differences (two
   evaluations per column), or implicit: the exact derivatives of MaterialPoint::StressDerivatives
   (for an RVE, implicit differentiation of its relaxed state: no perturbed solves). */
enum class TangentMethod {
  Forward,
  Central,
  Implicit
};

inline const char *TangentMethodName(TangentMethod m)
{
  return m == TangentMethod::Implicit ? "implicit" : m == TangentMethod::Central ? "central" : "forward";
}

struct TangentOptions {
  TangentMethod method    = TangentMethod::Forward;
  PetscReal     Fdot_typ  = 1.0;  /* eq 53's typical velocity gradient [1/µs] */
  PetscReal     U         = 0;    /* eq 52's U; 0 = the material's StressUncertainty() */
  bool          viscosity = true; /* also D^v (3 more evaluations) */
};

/* Eqs 46-53: perturb F by eps (e_k (x) e_l) F for (kl) = (11), (22), (12) and Fdot likewise, and
   difference the stress with the Truesdell-rate correction of eq 48. `base` is the response at
   (F, Fdot), already computed (the material's last evaluation). With opt.method Implicit the same
   columns come from the exact derivatives along those directions (MaterialPoint::
   StressDerivatives). On failure of a perturbed evaluation, *status says why. The perturbed
   evaluations are of `kind` (Perturbed; Output for tangents written or analysed only, counted
   apart like any output evaluation). */
PetscErrorCode ComputeTangents(MaterialPoint &mp, const Tensor2 &F, const Tensor2 &Fdot, const MaterialResponse &base, const TangentOptions &opt, Tangents *D,
                               MaterialResponse *status, EvaluationKind kind = EvaluationKind::Perturbed);

} // namespace turgor
