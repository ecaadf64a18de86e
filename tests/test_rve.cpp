static const char help[] = "RVE material point (TW 562 §3.2, eq 30, eqs 46-53):\n"
                           " 1. stress symmetry under 10%% shear with a shear rate, with and without the Bonet-Lok correction;\n"
                           " 2. objectivity sigma(R F, R Fdot) = R sigma(F, Fdot) R^T for 10, 45 and 90 degrees;\n"
                           " 3. the relaxed state does not depend on the start (cold vs warm), and D^v = 0 without rate terms;\n"
                           " 4. forward- vs central-difference tangents;\n"
                           " 5. a springs-only square lattice against its analytic stiffness diag(k/s, k/s, 0);\n"
                           " 6. relaxed vs Cauchy-Born stress: equal for the lattice, different for the turgid cell;\n"
                           " 7. failures (inverted F, no convergence) are reported, not aborted;\n"
                           " 8. a large shear path with a rate (a corner element of the 8 x 8 FE^2 bar) converges at every point;\n"
                           " 9. exact tangents (implicit differentiation of the relaxed state, -material_tangent implicit) against\n"
                           "    central differences of tightly relaxed RVEs, on a sheared and a stretched RVE with rates: 1e-6.\n";
#include "rve_test_util.h"
#include <turgor/physics/repulsion.h>
#include <turgor/physics/sph_fluid.h>
#include <turgor/physics/wall_springs.h>

using namespace turgor;
using turgor_test::CreateRVE;

/* A point of `material` after its options (the members set by the caller are the defaults). */
static PetscErrorCode MakeRVE(RVEMaterial &material, std::unique_ptr<RVE> *rve)
{
  PetscFunctionBeginUser;
  PetscCall(material.SetFromOptions(PETSC_COMM_SELF, nullptr));
  PetscCall(CreateRVE(material, rve));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A point of the default RVE material. */
static PetscErrorCode MakeRVE(std::unique_ptr<RVE> *rve)
{
  RVEMaterial material;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(material, rve));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Eval(RVE &rve, const Tensor2 &F, const Tensor2 &Fd, MaterialResponse *r)
{
  PetscFunctionBeginUser;
  PetscCall(rve.Evaluate(F, Fd, EvaluationKind::Trial, r));
  TG_CHECK(r->ok, "RVE evaluation failed: %s", r->reason.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscReal Asymmetry(const Tensor2 &s)
{
  return std::fabs(s(0, 1) - s(1, 0)) / s.Norm();
}

static PetscReal MaxRel(const PetscReal A[3][3], const PetscReal B[3][3], PetscReal scale)
{
  PetscReal d = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) d = PetscMax(d, std::fabs(A[i][j] - B[i][j]));
  return d / scale;
}

static PetscReal MaxAbs(const PetscReal A[3][3])
{
  PetscReal d = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) d = PetscMax(d, std::fabs(A[i][j]));
  return d;
}

/* 1. The SPH viscous stress under a shear rate is torque-free only with the correction. */
static PetscErrorCode Symmetry()
{
  const Tensor2 F =
                  {
                    {{1, 0.1}, {0, 1}}
  },
                Fd = {{{0, 0.1}, {0, 0}}};
  PetscReal asym[2];
  PetscFunctionBeginUser;
  for (int c = 0; c < 2; c++) {
    /* the default physics with its SPH fluid configured here: viscosity 5, correction on / off */
    RVEMaterial               material;
    std::unique_ptr<SPHFluid> sph(new SPHFluid);
    std::unique_ptr<RVE>      rve;
    MaterialResponse          r;
    sph->viscosity         = 5;
    sph->correction        = c ? PETSC_FALSE : PETSC_TRUE;
    material.physics.names = {"springs", "repulsion"};
    material.physics.Add(std::move(sph));
    PetscCall(MakeRVE(material, &rve));
    PetscCall(Eval(*rve, F, Fd, &r));
    asym[c] = Asymmetry(r.sigma);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "1. |sigma - sigma^T| / |sigma| under 10%% shear, shear rate 0.1/µs: with correction %.2e, without %.2e (ratio %.1e)\n",
                        (double)asym[0], (double)asym[1], (double)(asym[1] / asym[0])));
  TG_CHECK(asym[0] * 10 <= asym[1], "the correction must make the stress at least 10x more symmetric");
  TG_CHECK(asym[0] < 1e-10, "corrected stress not symmetric to round-off: %.3e", (double)asym[0]);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 2. A rigid rotation superposed on (F, Fdot) rotates the stress. */
static PetscErrorCode Objectivity()
{
  const Tensor2 F =
                  {
                    {{1.04, 0.05}, {-0.02, 0.97}}
  },
                Fd = {{{0.002, 0.01}, {0, -0.001}}};
  MaterialResponse r0;
  RVEMaterial      material; /* configured once, a fresh point for every rotation */
  PetscFunctionBeginUser;
  PetscCall(material.SetFromOptions(PETSC_COMM_SELF, nullptr));
  {
    std::unique_ptr<RVE> rve;
    PetscCall(CreateRVE(material, &rve));
    PetscCall(Eval(*rve, F, Fd, &r0));
  }
  for (PetscReal deg : {10.0, 45.0, 90.0}) {
    const Tensor2        R = Tensor2::Rotation(deg * PETSC_PI / 180);
    std::unique_ptr<RVE> rve;
    MaterialResponse     r;
    PetscCall(CreateRVE(material, &rve));
    PetscCall(Eval(*rve, R * F, R * Fd, &r));
    const Tensor2   expect = R * r0.sigma * R.T();
    const PetscReal err    = (r.sigma - expect).Norm() / expect.Norm();
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "2. rotation %4.0f deg: |sigma(RF) - R sigma(F) R^T| / |sigma| = %.2e, rho %.12g vs %.12g\n", (double)deg,
                          (double)err, (double)r.rho, (double)r0.rho));
    TG_CHECK(err < 1e-8, "not objective at %g degrees: %.3e", (double)deg, (double)err);
    TG_CHECK_CLOSE(r.rho, r0.rho, 1e-14, 0, "density under rotation");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 3. The relaxed state is a function of (F, Fdot), not of where Psi-tc starts; no rate terms, no D^v. */
static PetscErrorCode StaticState()
{
  const Tensor2 F = {
    {{1.03, 0.02}, {0.0, 0.99}}
  };
  MaterialResponse     cold, warm, detour;
  RVEMaterial          standard; /* two points of one material */
  std::unique_ptr<RVE> a, b;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(standard, &a));
  PetscCall(Eval(*a, F, Tensor2::Zero(), &cold));
  PetscCall(CreateRVE(standard, &b));
  PetscCall(Eval(*b,
                 {
                   {{0.95, -0.05}, {0.03, 1.06}}
  },
                 Tensor2::Zero(), &detour)); /* elsewhere first */
  PetscCall(Eval(*b, F, Tensor2::Zero(), &warm));
  const PetscReal d = (cold.sigma - warm.sigma).Norm() / cold.sigma.Norm();
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "3. sigma(F, 0): cold start (%" PetscInt_FMT " its) vs warm start from another F (%" PetscInt_FMT " its): relative difference %.2e\n",
                        cold.iterations, warm.iterations, (double)d));
  TG_CHECK(d < 1e-10, "relaxed stress depends on the start: %.3e", (double)d);

  /* the default physics without its rate terms: undamped springs and repulsion, inviscid fluid */
  RVEMaterial                  material;
  std::unique_ptr<WallSprings> springs(new WallSprings);
  std::unique_ptr<Repulsion>   repulsion(new Repulsion);
  std::unique_ptr<SPHFluid>    sph(new SPHFluid);
  springs->damping_ratio = 0;
  repulsion->damping     = PETSC_FALSE;
  sph->viscosity         = 0;
  material.physics.names.clear();
  material.physics.Add(std::move(springs));
  material.physics.Add(std::move(repulsion));
  material.physics.Add(std::move(sph));
  std::unique_ptr<RVE> c;
  MaterialResponse     r, r2, status;
  Tangents             D;
  PetscCall(MakeRVE(material, &c));
  PetscCall(Eval(*c, F, Tensor2::Zero(), &r));
  PetscCall(Eval(*c, F,
                 {
                   {{0.01, 0.02}, {-0.01, 0.0}}
  },
                 &r2));
  PetscCall(ComputeTangents(*c, F, Tensor2::Zero(), r, TangentOptions(), &D, &status));
  TG_CHECK(status.ok, "tangents failed");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "   without rate terms: |sigma(F, Fdot) - sigma(F, 0)| = %.2e N/m, max |D^v| = %.2e (max |D^e| = %.4g)\n",
                        (double)(r2.sigma - r.sigma).Norm(), (double)MaxAbs(D.Dv), (double)MaxAbs(D.De)));
  TG_CHECK((r2.sigma - r.sigma).Norm() < 1e-10 * r.sigma.Norm(), "stress depends on Fdot without rate terms");
  TG_CHECK(MaxAbs(D.Dv) == 0.0, "D^v must vanish without rate terms");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4. Forward differences (eqs 46-53) against central differences. */
static PetscErrorCode ForwardVsCentral()
{
  const Tensor2 F =
                  {
                    {{1.02, 0.03}, {-0.01, 0.99}}
  },
                Fd = {{{0.01, 0.0}, {0.005, -0.01}}};
  std::unique_ptr<RVE> rve;
  MaterialResponse     r, status;
  Tangents             fwd, cen;
  TangentOptions       opt;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(&rve));
  PetscCall(Eval(*rve, F, Fd, &r));
  PetscCall(ComputeTangents(*rve, F, Fd, r, opt, &fwd, &status));
  TG_CHECK(status.ok, "forward tangents failed: %s", status.reason.c_str());
  opt.method = TangentMethod::Central;
  PetscCall(ComputeTangents(*rve, F, Fd, r, opt, &cen, &status));
  TG_CHECK(status.ok, "central tangents failed: %s", status.reason.c_str());
  const PetscReal de = MaxRel(fwd.De, cen.De, MaxAbs(cen.De)), dv = MaxRel(fwd.Dv, cen.Dv, MaxAbs(cen.Dv));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "4. forward vs central differences: D^e %.2e, D^v %.2e (relative to the largest entry; D^e_11,11 = %.6g N/m, D^v_11,11 = %.6g ng/µs)\n",
                        (double)de, (double)dv, (double)cen.De[0][0], (double)cen.Dv[0][0]));
  TG_CHECK(de < 1e-4 && dv < 1e-4, "forward and central tangents differ");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 5 and 6a. Springs only: pin-jointed square lattice; docs/model.md derives D^e = diag(k/s, k/s, 0). */
static PetscErrorCode SpringLattice()
{
  PetscFunctionBeginUser;
  RVEMaterial          material;
  std::unique_ptr<RVE> rve;
  MaterialResponse     r, status;
  Tangents             D;
  material.physics.names = {"springs"};
  material.spec.cells    = 2;
  PetscCall(MakeRVE(material, &rve));
  PetscCall(Eval(*rve, Tensor2::Identity(), Tensor2::Zero(), &r));
  PetscCall(ComputeTangents(*rve, Tensor2::Identity(), Tensor2::Zero(), r, TangentOptions(), &D, &status));
  const PetscReal k = 4000.0 / 2, exact[3][3] = {
                                    {k, 0, 0},
                                    {0, k, 0},
                                    {0, 0, 0}
  };
  const PetscReal err = MaxRel(D.De, exact, k);
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "5. springs-only lattice (2 x 2 cells, s = 2): D^e = [%.6g %.3g %.3g; %.3g %.6g %.3g; %.3g %.3g %.3g], analytic diag(%g, %g, 0): max "
                        "error %.2e k/s\n",
                        (double)D.De[0][0], (double)D.De[0][1], (double)D.De[0][2], (double)D.De[1][0], (double)D.De[1][1], (double)D.De[1][2],
                        (double)D.De[2][0], (double)D.De[2][1], (double)D.De[2][2], (double)k, (double)k, (double)err));
  TG_CHECK(err < 1e-5, "lattice stiffness differs from the analytic value");
  /* a bravais-like lattice without prestress relaxes affinely: relaxed = Cauchy-Born */
  const Tensor2 F = {
    {{1.05, 0.02}, {0.01, 0.98}}
  };
  MaterialResponse relaxed, cb;
  PetscCall(Eval(*rve, F, Tensor2::Zero(), &relaxed));
  rve->SetMode(RelaxationMode::CauchyBorn);
  PetscCall(Eval(*rve, F, Tensor2::Zero(), &cb));
  const PetscReal d = (relaxed.sigma - cb.sigma).Norm() / relaxed.sigma.Norm();
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "6. springs-only lattice at 5%% strain: |relaxed - Cauchy-Born| / |sigma| = %.2e\n", (double)d));
  TG_CHECK(d < 1e-10, "the lattice should relax affinely");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 6b. The turgid cell: Cauchy-Born about the relaxed state at F = I matches the relaxed response to
   leading order (the difference vanishes linearly with the strain), and relaxation matters at 5%. */
static PetscErrorCode TurgidRelaxation()
{
  std::unique_ptr<RVE>   rve;
  MaterialResponse       ref;
  std::vector<PetscReal> diff;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(&rve));
  PetscCall(Eval(*rve, Tensor2::Identity(), Tensor2::Zero(), &ref));
  PetscCall(rve->Commit());
  for (PetscReal e : {1e-4, 1e-3, 5e-2}) {
    const Tensor2 F = {
      {{1 + e, 0.5 * e}, {0, 1 - 0.3 * e}}
    };
    MaterialResponse relaxed, frozen, cb;
    rve->SetMode(RelaxationMode::Relaxed);
    PetscCall(Eval(*rve, F, Tensor2::Zero(), &relaxed));
    PetscCall(rve->Revert());
    rve->SetMode(RelaxationMode::Frozen);
    PetscCall(Eval(*rve, F, Tensor2::Zero(), &frozen));
    rve->SetMode(RelaxationMode::CauchyBorn);
    PetscCall(Eval(*rve, F, Tensor2::Zero(), &cb));
    const PetscReal dinc = (relaxed.sigma - frozen.sigma).Norm() / (relaxed.sigma - ref.sigma).Norm();
    const PetscReal dabs = (relaxed.sigma - frozen.sigma).Norm() / relaxed.sigma.Norm();
    const PetscReal dcb  = (relaxed.sigma - cb.sigma).Norm() / relaxed.sigma.Norm();
    diff.push_back(dabs);
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "6. turgid cell, strain %.0e: relaxed vs Cauchy-Born about the relaxed F = I state: %.2e of |sigma| (%.1f%% of the stress "
                          "increment); vs plain Cauchy-Born (u1 = 0): %.2e of |sigma|\n",
                          (double)e, (double)dabs, 100 * (double)dinc, (double)dcb));
    if (e == 5e-2) TG_CHECK(dabs > 1e-3, "relaxation should change the stress measurably at 5%% strain");
  }
  TG_CHECK(diff[0] < 1e-3, "at 1e-4 strain the relaxed and Cauchy-Born stresses should agree");
  TG_CHECK(diff[1] / diff[0] > 5 && diff[1] / diff[0] < 20, "the difference should vanish linearly with the strain (ratio %.2f for 10x strain)",
           (double)(diff[1] / diff[0]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 7. Failed evaluations come back with a reason. */
static PetscErrorCode Failures()
{
  std::unique_ptr<RVE> rve;
  MaterialResponse     r;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(&rve));
  PetscCall(rve->Evaluate(
    {
      {{1, 0}, {0, -0.2}}
  },
    Tensor2::Zero(), EvaluationKind::Trial, &r));
  TG_CHECK(!r.ok, "an inverted F must fail");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "7. inverted F: %s\n", r.reason.c_str()));
  {
    RVEMaterial material;
    material.spec.max_it = 2;
    PetscCall(MakeRVE(material, &rve));
  }
  PetscCall(rve->Evaluate(
    {
      {{1.05, 0}, {0, 1}}
  },
    Tensor2::Zero(), EvaluationKind::Trial, &r));
  TG_CHECK(!r.ok, "two Psi-tc iterations cannot converge from a cold start");
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "   -rve_max_it 2: %s\n", r.reason.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 8. The state an FE^2 corner element reached on the 8 x 8 bending bar (33% shear at a shear rate
   of 0.26/µs), approached in 40 warm-started increments: every point must relax. With the literal
   repulsion damping (discontinuous at the cutoff) points of this path stalled at ||G|| ~ 3e-5. */
static PetscErrorCode LargeShearPath()
{
  std::unique_ptr<RVE> rve;
  MaterialResponse     r;
  const Tensor2        Fe =
                  {
                    {{0.982305, -0.00986765}, {0.334984, 1.01572}}
  },
                Fde = {{{0.205426, -0.000847104}, {-0.262493, -0.00539697}}};
  const int n       = 40;
  PetscInt  its = 0, failed = 0;
  PetscFunctionBeginUser;
  PetscCall(MakeRVE(&rve));
  for (int k = 0; k <= n; k++) {
    const PetscReal s = (PetscReal)k / n;
    const Tensor2   F = {
        {{1 + s * (Fe(0, 0) - 1), s * Fe(0, 1)}, {s * Fe(1, 0), 1 + s * (Fe(1, 1) - 1)}}
    };
    const Tensor2 Fd = {
      {{s * Fde(0, 0), s * Fde(0, 1)}, {s * Fde(1, 0), s * Fde(1, 1)}}
    };
    PetscCall(rve->Evaluate(F, Fd, EvaluationKind::Trial, &r));
    if (!r.ok) failed++;
    else PetscCall(rve->Commit());
    its = PetscMax(its, r.iterations);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "8. large shear path: %" PetscInt_FMT " of %d points failed, at most %" PetscInt_FMT " iterations; final sigma12 = %.4g N/m\n", failed,
                        n + 1, its, (double)r.sigma(0, 1)));
  TG_CHECK(failed == 0, "%" PetscInt_FMT " points of the shear path did not relax", failed);
  TG_CHECK(its <= 20, "warm increments should need few iterations (max %" PetscInt_FMT ")", its);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 9. Implicit (exact) tangents against central differences: the reference relaxes to 1e-14 and
   differences with eps = 1e-5 (truncation ~eps^2, noise ~1e-14 / eps), so that it is itself
   accurate to ~1e-8 of the largest entry; the exact tangents come from an RVE at the default
   Psi-tc tolerance (1e-12), whose relaxed w enters only through the state differentiated. Both
   D^e and D^v, each relative to its largest entry. */
static PetscErrorCode ExactVsCentral()
{
  const struct {
    const char *name;
    Tensor2     F, Fd;
  } states[] = {
    {"sheared 10%",           {{{1.0, 0.1}, {0.0, 1.0}}},      {{{0.0, 0.01}, {0.0, 0.0}}}    },
    {"stretched 5% / -3%",    {{{1.05, 0.0}, {0.0, 0.97}}},    {{{0.01, 0.0}, {0.0, -0.005}}} },
    {"stretched and sheared", {{{1.03, 0.04}, {-0.02, 0.98}}}, {{{0.005, 0.01}, {0.0, 0.002}}}}
  };
  PetscFunctionBeginUser;
  for (const auto &st : states) {
    RVEMaterial          tight;
    std::unique_ptr<RVE> exact, ref;
    MaterialResponse     r, rr, status;
    Tangents             De, Dc, Df;
    TangentOptions       opt;
    MaterialCounters     c0, c1, c2;
    tight.spec.psi_atol = tight.spec.psi_steptol = 1e-14;
    PetscCall(MakeRVE(&exact));
    PetscCall(MakeRVE(tight, &ref));
    PetscCall(Eval(*exact, st.F, st.Fd, &r));
    exact->AddCounters(c0);
    opt.method = TangentMethod::Implicit;
    PetscCall(ComputeTangents(*exact, st.F, st.Fd, r, opt, &De, &status));
    TG_CHECK(status.ok, "exact tangents failed: %s", status.reason.c_str());
    exact->AddCounters(c1);
    opt.method = TangentMethod::Forward; /* the seed's, for the cost */
    PetscCall(ComputeTangents(*exact, st.F, st.Fd, r, opt, &Df, &status));
    TG_CHECK(status.ok, "forward tangents failed: %s", status.reason.c_str());
    exact->AddCounters(c2);
    PetscCall(Eval(*ref, st.F, st.Fd, &rr));
    opt.method = TangentMethod::Central;
    opt.U      = 1e-10;
    PetscCall(ComputeTangents(*ref, st.F, st.Fd, rr, opt, &Dc, &status));
    TG_CHECK(status.ok, "central tangents failed: %s", status.reason.c_str());
    const PetscReal de = MaxRel(De.De, Dc.De, MaxAbs(Dc.De)), dv = MaxRel(De.Dv, Dc.Dv, MaxAbs(Dc.Dv));
    const PetscReal fe = MaxRel(Df.De, Dc.De, MaxAbs(Dc.De)), fv = MaxRel(Df.Dv, Dc.Dv, MaxAbs(Dc.Dv));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "9. exact vs central tangents, %s: D^e %.2e, D^v %.2e (forward differences: %.2e, %.2e); exact: %" PetscInt_FMT
                          " force evaluations, %" PetscInt_FMT " Krylov iterations, 0 RVE solves; forward: %" PetscInt_FMT
                          " force evaluations in %" PetscInt_FMT " RVE solves (%" PetscInt_FMT " Psi-tc iterations)\n",
                          st.name, (double)de, (double)dv, (double)fe, (double)fv, c1.tangent_force_evals - c0.tangent_force_evals,
                          c1.tangent_linear_its - c0.tangent_linear_its, c2.force_evals - c1.force_evals, c2.solves - c1.solves,
                          c2.iterations - c1.iterations));
    TG_CHECK(c1.solves == c0.solves, "exact tangents made RVE solves");
    TG_CHECK(de < 1e-6 && dv < 1e-6, "exact tangents differ from central differences (%.2e, %.2e)", (double)de, (double)dv);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(Symmetry());
  PetscCall(Objectivity());
  PetscCall(StaticState());
  PetscCall(ForwardVsCentral());
  PetscCall(SpringLattice());
  PetscCall(TurgidRelaxation());
  PetscCall(Failures());
  PetscCall(LargeShearPath());
  PetscCall(ExactVsCentral());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_rve: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
