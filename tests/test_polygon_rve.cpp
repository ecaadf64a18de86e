static const char
  help[] = "Polygon RVE material (-material polygon_rve): periodic cells of bars, hinges, turgor, contact and glue:\n"
           " 1. periodicity: 1, 4 and 9 glued cells of a square lattice give the same stress, at rest and deformed;\n"
           " 2. lattice symmetry: the turgor prestress of square and hexagonal lattices in contact is isotropic;\n"
           " 3. objectivity sigma(R F) = R sigma(F) R^T of a glued Voronoi RVE;\n"
           " 4. exact tangents (implicit differentiation) against central differences, with turgor and plastic hinges;\n"
           " 5. history: glue bonds broken at an accepted step stay broken; a rejected step leaves no trace;\n"
           " 6. the square lattice of one-bar walls glued across a lamella: C11 = C22 = 1 / (1/(2 k_b) + 1/(k_n s)), C12 = 0;\n"
           " 7. the hexagonal lattice likewise: C11 + C12 = sqrt(3) / (1/(k_n s) + 3/(2 k_b)), C11 = C22;\n"
           " 8. the warm start's predictor w + (dw/dF) dF (spin included) is second order: its error falls 4x when dF halves;\n"
           " 9. a material's points share their relaxed state at the reference, the first as the second: their next evaluations are the same bits.\n";
#include "rve_test_util.h"
#include <turgor/rve/polygon_rve_material.h>

using namespace turgor;
using turgor_test::CreateRVE;

/* A point of the polygon RVE material configured by `options` alone (the options database is
   cleared first); *material keeps the configuration the point was made from. */
static PetscErrorCode MakePoint(const char *options, std::unique_ptr<PolygonRVEMaterial> *material, std::unique_ptr<RVE> *rve)
{
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, options));
  *material = std::make_unique<PolygonRVEMaterial>();
  PetscCall((*material)->SetFromOptions(PETSC_COMM_SELF, nullptr));
  PetscCall(CreateRVE(**material, rve));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Eval(RVE &rve, const Tensor2 &F, MaterialResponse *r, EvaluationKind kind = EvaluationKind::Trial)
{
  PetscFunctionBeginUser;
  PetscCall(rve.Evaluate(F, Tensor2::Zero(), kind, r));
  TG_CHECK(r->ok, "RVE evaluation failed: %s", r->reason.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Diff(const Tensor2 &a, const Tensor2 &b)
{
  return (a - b).Norm() / b.Norm();
}

static const char *kContact     = "-physics bars,hinges,pressure,contact -prve_cell_size 20 -tissue_bar_length 5";
static const char *kGluedSquare = "-physics bars,hinges,pressure,glue -prve_lattice square -prve_cell_size 20 -tissue_bar_length 5";
static const char *kGlued       = "-physics bars,hinges,pressure,glue -prve_lattice voronoi -prve_cells 4 -prve_cell_size 20 -tissue_bar_length 2.5";

/* 1. The images of a one-cell RVE are the cells of a larger one: the same lattice, the same stress
   (to the relaxation tolerance: -rve_psi_atol 1e-12 of the scaled forces gives ~1e-9 of the stress). */
static PetscErrorCode Periodicity()
{
  const Tensor2 Fs[2] = {Tensor2::Identity(), {{{0.996, 0.0}, {0.0, 0.997}}}}; /* compressed: every cell stays in contact */
  Tensor2       ref[2];
  PetscFunctionBeginUser;
  for (PetscInt K : {1, 4, 9}) {
    std::unique_ptr<PolygonRVEMaterial> m;
    std::unique_ptr<RVE>                rve;
    const std::string                   opts = std::string(kGluedSquare) + " -prve_cells " + std::to_string((long long)K);
    PetscCall(MakePoint(opts.c_str(), &m, &rve));
    for (int s = 0; s < 2; s++) {
      MaterialResponse r;
      PetscCall(Eval(*rve, Fs[s], &r));
      if (K == 1) ref[s] = r.sigma;
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "1. square lattice, %2" PetscInt_FMT " cells, %s: sigma = [%.10g %.4g; %.4g %.10g] N/m, %.2e from 1 cell\n", K,
                            s ? "deformed" : "at rest", (double)r.sigma(0, 0), (double)r.sigma(0, 1), (double)r.sigma(1, 0), (double)r.sigma(1, 1),
                            (double)Diff(r.sigma, ref[s])));
      TG_CHECK(Diff(r.sigma, ref[s]) < 1e-8, "%" PetscInt_FMT " cells differ from 1 cell by %.2e", K, (double)Diff(r.sigma, ref[s]));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 2. A regular lattice's prestress has the lattice's symmetry: isotropic for square and hexagonal. */
static PetscErrorCode LatticeSymmetry()
{
  PetscFunctionBeginUser;
  for (const char *lattice : {"-prve_lattice square -prve_cells 1", "-prve_lattice hexagonal -prve_cells 4"}) {
    std::unique_ptr<PolygonRVEMaterial> m;
    std::unique_ptr<RVE>                rve;
    MaterialResponse                    r;
    const std::string                   opts = std::string(kContact) + " " + lattice;
    PetscCall(MakePoint(opts.c_str(), &m, &rve));
    PetscCall(Eval(*rve, Tensor2::Identity(), &r));
    const PetscReal aniso = (std::fabs(r.sigma(0, 0) - r.sigma(1, 1)) + 2 * std::fabs(r.sigma(0, 1))) / r.sigma.Norm();
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "2. %s: sigma = [%.10g %.3g; %.3g %.10g] N/m, anisotropy %.2e\n", lattice, (double)r.sigma(0, 0),
                          (double)r.sigma(0, 1), (double)r.sigma(1, 0), (double)r.sigma(1, 1), (double)aniso));
    TG_CHECK(aniso < 1e-7, "the prestress of a regular lattice is not isotropic (%.2e)", (double)aniso);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 3. Rotating the deformation rotates the stress. */
static PetscErrorCode Objectivity()
{
  std::unique_ptr<PolygonRVEMaterial> m;
  std::unique_ptr<RVE>                a, b;
  const Tensor2                       F = {
                          {{1.006, 0.004}, {-0.003, 0.995}}
  };
  const PetscReal th = 0.5;
  const Tensor2   R  = {
       {{std::cos(th), -std::sin(th)}, {std::sin(th), std::cos(th)}}
  };
  MaterialResponse r, rr;
  PetscFunctionBeginUser;
  PetscCall(MakePoint(kGlued, &m, &a));
  PetscCall(CreateRVE(*m, &b));
  PetscCall(Eval(*a, F, &r));
  PetscCall(Eval(*b, R * F, &rr));
  const Tensor2 Rt = {
    {{R(0, 0), R(1, 0)}, {R(0, 1), R(1, 1)}}
  };
  const Tensor2   rot = R * r.sigma * Rt;
  const PetscReal d   = Diff(rr.sigma, rot);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "3. glued Voronoi RVE rotated by %.2f rad: |sigma(R F) - R sigma(F) R^T| / |sigma| = %.2e\n", (double)th, (double)d));
  TG_CHECK(d < 1e-8, "the stress is not objective (%.2e)", (double)d);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4. Exact tangents against central differences of tightly relaxed RVEs: glued Voronoi cells (bars,
   hinges, glue) and the turgid tissue of config/polygon_rve.yaml with plastic hinges (M_max small
   enough that hinges yield: the stress differs from the elastic hinges'), sheared and stretched.
   Where a hinge sits within the difference step of its yield moment (the law's kink) the two
   differ more: 1e-4 at F12 = 0.003 alone (docs/model.md).
   (With the glue's tension-only law and touching cells, a turgid RVE at rest has bonds and contacts
   at their kinks, where the two differ by 2e-4: docs/model.md.) */
static PetscErrorCode ExactVsCentral()
{
  static const char *kTurgid = "-physics bars,hinges,pressure,contact,glue -prve_lattice voronoi -prve_cells 4 -prve_cell_size 25 -prve_gap 0.05 "
                               "-tissue_bar_length 2.5 -bar_stiffness 2e4 -hinge_stiffness 500 -contact_stiffness 2e4 -pressure_law gas -pressure_p0 5 "
                               "-glue_law softening -glue_compression -glue_strength 200 -glue_fracture_energy 20";
  const struct {
    const char *name;
    std::string options;
    Tensor2     F;
  } cases[] = {
    {"glued, sheared",                                std::string(kGlued) + " -physics bars,hinges,glue", {{{1.004, 0.003}, {-0.002, 0.998}}}},
    {"turgid, plastic hinges, sheared and stretched", std::string(kTurgid) + " -hinge_max_moment 0.05",   {{{1.004, 0.003}, {-0.002, 0.998}}}},
    {"turgid, plastic hinges, stretched",             std::string(kTurgid) + " -hinge_max_moment 0.05",   {{{1.003, 0.0}, {0.0, 0.998}}}     },
  };
  PetscFunctionBeginUser;
  for (const auto &c : cases) {
    std::unique_ptr<PolygonRVEMaterial> m, tight;
    std::unique_ptr<RVE>                exact, ref;
    MaterialResponse                    r, rr, status;
    Tangents                            De, Dc;
    TangentOptions                      opt;
    PetscCall(MakePoint(c.options.c_str(), &m, &exact));
    PetscCall(MakePoint((c.options + " -rve_psi_atol 1e-14 -rve_psi_steptol 1e-14").c_str(), &tight, &ref));
    PetscCall(Eval(*exact, c.F, &r));
    opt.method    = TangentMethod::Implicit;
    opt.viscosity = false;
    PetscCall(ComputeTangents(*exact, c.F, Tensor2::Zero(), r, opt, &De, &status));
    TG_CHECK(status.ok, "exact tangents failed: %s", status.reason.c_str());
    PetscCall(Eval(*ref, c.F, &rr));
    opt.method = TangentMethod::Central;
    opt.U      = 1e-12;
    PetscCall(ComputeTangents(*ref, c.F, Tensor2::Zero(), rr, opt, &Dc, &status));
    TG_CHECK(status.ok, "central tangents failed: %s", status.reason.c_str());
    PetscReal d = 0, scale = 0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) d = std::max(d, std::fabs(De.De[i][j] - Dc.De[i][j])), scale = std::max(scale, std::fabs(Dc.De[i][j]));
    PetscReal plastic = 0; /* the same state with elastic hinges: plasticity is active where the stress differs */
    if (c.options.find("-hinge_max_moment") != std::string::npos) {
      std::unique_ptr<PolygonRVEMaterial> em;
      std::unique_ptr<RVE>                elastic;
      MaterialResponse                    re;
      PetscCall(MakePoint((c.options + " -hinge_max_moment 0").c_str(), &em, &elastic));
      PetscCall(Eval(*elastic, c.F, &re));
      plastic = Diff(re.sigma, r.sigma);
      TG_CHECK(plastic > 1e-6, "no hinge yields: the stress equals the elastic hinges' (%.2e)", (double)plastic);
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "4. %s: D^e exact vs central differences %.2e of its largest entry (C11 %.6g, C22 %.6g, C12 %.6g, C33 %.6g N/m; plastic "
                          "hinges change the stress by %.2e)\n",
                          c.name, (double)(d / scale), (double)Dc.De[0][0], (double)Dc.De[1][1], (double)Dc.De[0][1], (double)Dc.De[2][2], (double)plastic));
    TG_CHECK(d < 1e-6 * scale, "exact tangents differ from central differences (%.2e)", (double)(d / scale));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 5. Glue that breaks: a stretch far past the bonds' strength, evaluated and rejected, leaves no
   trace (back at the reference the prestress is the first one, to the relaxation's tolerance);
   accepted, its broken bonds stay broken (back at the reference the tissue is another). */
static PetscErrorCode History()
{
  std::unique_ptr<PolygonRVEMaterial> m;
  std::unique_ptr<RVE>                rejected, accepted;
  const Tensor2                       F = {
                          {{1.03, 0.0}, {0.0, 1.0}}
  };
  MaterialResponse r0, r1, r2, r3, r4;
  PetscFunctionBeginUser;
  PetscCall(MakePoint((std::string(kGlued) + " -glue_law softening -glue_strength 2 -glue_fracture_energy 0.02").c_str(), &m, &rejected));
  PetscCall(CreateRVE(*m, &accepted));
  PetscCall(Eval(*rejected, Tensor2::Identity(), &r0));
  PetscCall(rejected->Commit());
  PetscCall(Eval(*rejected, F, &r1));
  PetscCall(rejected->Revert());
  PetscCall(Eval(*rejected, Tensor2::Identity(), &r2));
  PetscCall(Eval(*accepted, Tensor2::Identity(), &r3));
  PetscCall(accepted->Commit());
  PetscCall(Eval(*accepted, F, &r3));
  PetscCall(accepted->Commit()); /* the bonds past their strength break here */
  PetscCall(Eval(*accepted, Tensor2::Identity(), &r4));
  PetscCall(
    PetscPrintf(PETSC_COMM_SELF,
                "5. glue softening, stretched 3%%: sigma11 %.6g N/m; back at rest %.8g N/m (rejected: %.2e from the first %.8g), %.8g (accepted: %.2e)\n",
                (double)r1.sigma(0, 0), (double)r2.sigma(0, 0), (double)Diff(r2.sigma, r0.sigma), (double)r0.sigma(0, 0), (double)r4.sigma(0, 0),
                (double)Diff(r4.sigma, r0.sigma)));
  TG_CHECK(Diff(r2.sigma, r0.sigma) < 1e-8, "a rejected step left a trace: %.3e", (double)Diff(r2.sigma, r0.sigma));
  TG_CHECK(Diff(r4.sigma, r0.sigma) > 1e-3, "accepted breaks left the tissue as it was (%.3e)", (double)Diff(r4.sigma, r0.sigma));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The exact tangent at rest of a lattice of K one-bar-walled cells glued across a 50 nm lamella with
   a law linear through zero opening (bars 2e4 N/m, glue 1e4 N/m per µm, cells of 20 µm), for the
   closed forms below. */
static PetscErrorCode LatticeTangentAtRest(const char *lattice, PetscInt K, Tangents *D)
{
  std::unique_ptr<PolygonRVEMaterial> m;
  std::unique_ptr<RVE>                rve;
  MaterialResponse                    r0, status;
  TangentOptions                      opt;
  const std::string opts = std::string("-physics bars,hinges,glue -prve_cell_size 20 -prve_gap 0.05 -tissue_bar_radius 0.5 -bar_stiffness 2e4 "
                                       "-glue_normal_stiffness 1e4 -glue_compression -glue_law energy -glue_fracture_energy 1e6 -prve_lattice ") +
                           lattice + " -prve_cells " + std::to_string((long long)K);
  PetscFunctionBeginUser;
  PetscCall(MakePoint(opts.c_str(), &m, &rve));
  PetscCall(Eval(*rve, Tensor2::Identity(), &r0));
  opt.method    = TangentMethod::Implicit;
  opt.viscosity = false;
  PetscCall(ComputeTangents(*rve, Tensor2::Identity(), Tensor2::Zero(), r0, opt, D, &status));
  TG_CHECK(status.ok, "tangents failed: %s", status.reason.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 6. The closed form of the square lattice (docs/model.md): square cells of side s (one bar per wall,
   corner nodes only) a period a apart, glued across a gap with a law linear through zero opening.
   Stretched along x, the horizontal walls (two per period, bars of stiffness k_b) and the vertical
   interface (glue k_n over its length s) are in series: C11 = 1 / (1/(2 k_b) + 1/(k_n s)); the
   angles do not change (no hinge moment) and nothing acts along y, C12 = 0; by symmetry C22 = C11. */
static PetscErrorCode SquareLatticeClosedForm()
{
  const PetscReal a = 20, r = 0.5, g = 0.05, kb = 2e4, kn = 1e4, s = a - 2 * r - g, C = 1 / (1 / (2 * kb) + 1 / (kn * s));
  PetscFunctionBeginUser;
  for (PetscInt K : {1, 4}) {
    Tangents D;
    PetscCall(LatticeTangentAtRest("square", K, &D));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "6. square lattice, %" PetscInt_FMT " cells: C11 %.10g, C22 %.10g (closed form %.10g), C12 %.2e, C21 %.2e N/m\n", K,
                          (double)D.De[0][0], (double)D.De[1][1], (double)C, (double)D.De[0][1], (double)D.De[1][0]));
    TG_CHECK_CLOSE(D.De[0][0], C, 1e-8, 0, "C11 against the closed form");
    TG_CHECK_CLOSE(D.De[1][1], C, 1e-8, 0, "C22 against the closed form");
    TG_CHECK(std::fabs(D.De[0][1]) < 1e-8 * C && std::fabs(D.De[1][0]) < 1e-8 * C, "C12 = %g, C21 = %g: must vanish", (double)D.De[0][1], (double)D.De[1][0]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 7. The hexagonal lattice's closed form (docs/model.md): regular hexagons of side s (one bar per
   wall), centres d = sqrt(3) s + 2 r + g apart, glued across the gap. An equibiaxial stretch keeps
   every angle (no hinge moment) and opens every interface alike: the six walls (hoop tension
   T = k_b ds) and the three interfaces per cell (k_n s) give C11 + C12 = sqrt(3) / (1/(k_n s) + 3/(2 k_b));
   C11 = C22 by the lattice's symmetry. */
static PetscErrorCode HexagonalLatticeClosedForm()
{
  const PetscReal a = 20, d = a * std::sqrt(2 / std::sqrt(3.0)), r = 0.5, g = 0.05, kb = 2e4, kn = 1e4, s = (d - 2 * r - g) / std::sqrt(3.0);
  const PetscReal bulk = std::sqrt(3.0) / (1 / (kn * s) + 1.5 / kb);
  PetscFunctionBeginUser;
  for (PetscInt K : {4, 16}) {
    Tangents D;
    PetscCall(LatticeTangentAtRest("hexagonal", K, &D));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "7. hexagonal lattice, %2" PetscInt_FMT " cells: C11 + C12 %.10g (closed form %.10g), C22 + C21 %.10g, C11 - C22 %.2e N/m\n", K,
                          (double)(D.De[0][0] + D.De[0][1]), (double)bulk, (double)(D.De[1][1] + D.De[1][0]), (double)(D.De[0][0] - D.De[1][1])));
    TG_CHECK_CLOSE(D.De[0][0] + D.De[0][1], bulk, 1e-8, 0, "C11 + C12 against the closed form");
    TG_CHECK_CLOSE(D.De[1][1] + D.De[1][0], bulk, 1e-8, 0, "C22 + C21 against the closed form");
    TG_CHECK(std::fabs(D.De[0][0] - D.De[1][1]) < 1e-8 * bulk, "C11 - C22 = %g: must vanish", (double)(D.De[0][0] - D.De[1][1]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 8. The predictor from the exact tangent's dw/dF: against the relaxed state at F0 + eps G (G with a
   spin part, which the tangent's three directions do not hold and objectivity supplies), its error
   is O(eps^2) while the unpredicted start's is O(eps). */
static PetscErrorCode PredictorOrder()
{
  const std::string                   tight = std::string(kGlued) + " -rve_psi_atol 1e-14 -rve_psi_steptol 1e-14";
  std::unique_ptr<PolygonRVEMaterial> m;
  std::unique_ptr<RVE>                rve, truth;
  const Tensor2                       F0 = {
                          {{1.004, 0.003}, {-0.002, 0.998}}
  };
  const Tensor2 G = {
    {{0.3, -0.8}, {0.6, -0.2}}
  }; /* a stretch, a shear and a spin */
  MaterialResponse r, status;
  Tangents         D;
  TangentOptions   opt;
  PetscReal        err[2], lin[2];
  PetscFunctionBeginUser;
  PetscCall(MakePoint(tight.c_str(), &m, &rve));
  PetscCall(CreateRVE(*m, &truth));
  PetscCall(Eval(*rve, F0, &r));
  opt.method    = TangentMethod::Implicit;
  opt.viscosity = false;
  PetscCall(ComputeTangents(*rve, F0, Tensor2::Zero(), r, opt, &D, &status));
  TG_CHECK(status.ok, "exact tangents failed: %s", status.reason.c_str());
  const std::vector<PetscScalar> w0 = rve->CurrentState();
  std::vector<PetscScalar>       wp(w0.size());
  for (int k = 0; k < 2; k++) {
    const PetscReal eps = k ? 5e-4 : 1e-3;
    const Tensor2   F   = F0 + eps * G;
    TG_CHECK(rve->Predict(F, Tensor2::Zero(), w0, F0, Tensor2::Zero(), wp.data()), "no prediction after an exact tangent");
    PetscCall(Eval(*truth, F, &r));
    const std::vector<PetscScalar> &wt = truth->CurrentState();
    PetscReal                       e = 0, l = 0;
    for (size_t i = 0; i < wt.size(); i++) e += (wp[i] - wt[i]) * (wp[i] - wt[i]), l += (w0[i] - wt[i]) * (w0[i] - wt[i]);
    err[k] = std::sqrt(e);
    lin[k] = std::sqrt(l);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "8. predictor at F0 + %.0e G: |w_pred - w| = %.3e, |w0 - w| = %.3e\n", (double)eps, (double)err[k], (double)lin[k]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "8. halving the step: the predictor's error falls %.2fx, the unpredicted start's %.2fx\n", (double)(err[0] / err[1]),
                        (double)(lin[0] / lin[1])));
  TG_CHECK(err[0] / err[1] > 3.5 && err[0] / err[1] < 4.5, "the predictor is not second order (its error falls %.2fx)", (double)(err[0] / err[1]));
  TG_CHECK(err[0] < 0.05 * lin[0], "the predictor gains too little (%.2e against %.2e)", (double)err[0], (double)lin[0]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 9. Points first evaluated at the reference take the material's relaxed state there (solved once,
   on a scratch point): the first and the second alike -- the same stress and no iteration of their
   own --, so that their next evaluations are the same bits (which point came first does not
   matter); a point first evaluated elsewhere solves. */
static PetscErrorCode SharedReferenceSolve()
{
  std::unique_ptr<PolygonRVEMaterial> m;
  std::unique_ptr<RVE>                a, b, c;
  const Tensor2                       F = {
                          {{1.004, 0.003}, {-0.002, 0.998}}
  };
  MaterialResponse ra, rb, rc, na, nb;
  PetscFunctionBeginUser;
  PetscCall(MakePoint(kGlued, &m, &a));
  PetscCall(CreateRVE(*m, &b));
  PetscCall(CreateRVE(*m, &c));
  PetscCall(Eval(*a, Tensor2::Identity(), &ra));
  PetscCall(Eval(*b, Tensor2::Identity(), &rb));
  PetscCall(Eval(*c, F, &rc));
  PetscCall(Eval(*a, F, &na));
  PetscCall(Eval(*b, F, &nb));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "9. at the reference: %" PetscInt_FMT " and %" PetscInt_FMT " iterations (stress %s); next, at F: %" PetscInt_FMT " and %" PetscInt_FMT
                        " (stress %s); a point first at F: %" PetscInt_FMT "\n",
                        ra.iterations, rb.iterations, (ra.sigma - rb.sigma).Norm() == 0 ? "identical" : "differs", na.iterations, nb.iterations,
                        (na.sigma - nb.sigma).Norm() == 0 ? "identical" : "differs", rc.iterations));
  TG_CHECK(ra.iterations == 0 && rb.iterations == 0 && (ra.sigma - rb.sigma).Norm() == 0, "the points did not take the shared reference state");
  TG_CHECK(na.iterations == nb.iterations && (na.sigma - nb.sigma).Norm() == 0, "the first and the second point differ afterwards");
  TG_CHECK(rc.iterations > 0, "a point first evaluated away from the reference did not solve");
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(Periodicity());
  PetscCall(LatticeSymmetry());
  PetscCall(Objectivity());
  PetscCall(ExactVsCentral());
  PetscCall(History());
  PetscCall(SquareLatticeClosedForm());
  PetscCall(HexagonalLatticeClosedForm());
  PetscCall(PredictorOrder());
  PetscCall(SharedReferenceSolve());
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_polygon_rve: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
