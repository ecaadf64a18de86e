static const char help[] = "Tangent machinery (TW 562 eqs 46-53) on the closed-form neo-Hookean material:\n"
                           "forward- and central-difference D^e and D^v against the analytic tangents (1e-6), and the exact\n"
                           "ones of -material_tangent implicit (1e-13),\n"
                           "for several deformations including shear and rotation; inverted F is a failed evaluation;\n"
                           "the skipping point's first-order expansion about a solved state (-material_skip_tolerance): its error falls 4x\n"
                           "when the step halves, with stretch, shear, spin and rate; and a skipped evaluation within the tolerance;\n"
                           "Hill's second-order work (material/second_order_work.h): the closed-form cosine of a neo-Hookean point in\n"
                           "uniaxial strain, blind to a rigid rotation (where dP:dF of a pressurised point is negative), -1 for a stress\n"
                           "that falls, no decision below the floors.\n";
#include "test_util.h"
#include <turgor/material/neo_hookean.h>
#include <turgor/material/second_order_work.h>
#include <turgor/material/skipping_point.h>

using namespace turgor;

static PetscReal MaxRelDiff(const PetscReal A[3][3], const PetscReal B[3][3])
{
  PetscReal d = 0, s = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      d = PetscMax(d, std::fabs(A[i][j] - B[i][j]));
      s = PetscMax(s, std::fabs(B[i][j]));
    }
  return d / s;
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  /* the material configured once (-nh_* options), one point from it */
  NeoHookeanMaterial             material;
  std::unique_ptr<MaterialPoint> point;
  PetscCall(material.SetFromOptions(PETSC_COMM_SELF, nullptr));
  PetscCall(material.CreatePoint(PETSC_COMM_SELF, &point));
  NeoHookean *const nhp = dynamic_cast<NeoHookean *>(point.get());
  TG_CHECK(nhp, "the neo_hookean material must create NeoHookean points");
  NeoHookean   &nh   = *nhp;
  const Tensor2 Fs[] = {Tensor2::Identity(),
                        {{{1.1, 0.0}, {0.0, 0.95}}},
                        {{{1.0, 0.2}, {0.0, 1.0}}},
                        Tensor2::Rotation(0.7) * Tensor2{{{1.05, 0.1}, {-0.05, 0.9}}}};
  for (const Tensor2 &F : Fs) {
    Tangents         fd, cd, exact;
    MaterialResponse base, status;
    PetscCall(nh.Evaluate(F, Tensor2::Zero(), EvaluationKind::Trial, &base));
    nh.AnalyticTangents(F, &exact);
    TangentOptions opt;
    PetscCall(ComputeTangents(nh, F, Tensor2::Zero(), base, opt, &fd, &status));
    TG_CHECK(status.ok, "tangent evaluation failed: %s", status.reason.c_str());
    opt.method = TangentMethod::Central;
    opt.U      = 1e-10; /* central differences tolerate a larger step */
    PetscCall(ComputeTangents(nh, F, Tensor2::Zero(), base, opt, &cd, &status));
    Tangents id; /* -material_tangent implicit: the closed form's own derivatives */
    opt.method = TangentMethod::Implicit;
    PetscCall(ComputeTangents(nh, F, Tensor2::Zero(), base, opt, &id, &status));
    TG_CHECK(status.ok, "exact tangents failed: %s", status.reason.c_str());
    const PetscReal efe = MaxRelDiff(fd.De, exact.De), efv = MaxRelDiff(fd.Dv, exact.Dv), ece = MaxRelDiff(cd.De, exact.De), ecv = MaxRelDiff(cd.Dv, exact.Dv);
    const PetscReal eie = MaxRelDiff(id.De, exact.De), eiv = MaxRelDiff(id.Dv, exact.Dv);
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "F = [%5.3f %5.3f; %5.3f %5.3f]: D^e forward %.2e central %.2e implicit %.2e, D^v forward %.2e central %.2e implicit %.2e "
                          "(relative to max entry)\n",
                          (double)F(0, 0), (double)F(0, 1), (double)F(1, 0), (double)F(1, 1), (double)efe, (double)ece, (double)eie, (double)efv, (double)ecv,
                          (double)eiv));
    TG_CHECK(efe < 1e-6 && ece < 1e-6, "D^e differs from the analytic tangent");
    TG_CHECK(efv < 1e-6 && ecv < 1e-6, "D^v differs from the analytic tangent");
    TG_CHECK(eie < 1e-13 && eiv < 1e-13, "the exact (implicit) tangents differ from the analytic ones");
  }
  {
    MaterialResponse r;
    PetscCall(nh.Evaluate(
      {
        {{1, 0}, {0, -0.5}}
    },
      Tensor2::Zero(), EvaluationKind::Trial, &r));
    TG_CHECK(!r.ok, "an inverted deformation must be a failed evaluation");
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "inverted F: ok = %d, reason: %s\n", (int)r.ok, r.reason.c_str()));
  }
  {
    /* the expansion about (F0, Fdot0) against the viscous material's own stress at F0 + e G, Fdot0 + e H */
    std::unique_ptr<MaterialPoint> inner;
    PetscCall(PetscOptionsSetValue(NULL, "-nh_viscosity", "0.3"));
    NeoHookeanMaterial viscous;
    PetscCall(viscous.SetFromOptions(PETSC_COMM_SELF, nullptr));
    PetscCall(viscous.CreatePoint(PETSC_COMM_SELF, &inner));
    SkippingPoint sp(std::move(inner), 1e-3, 1.0);
    const Tensor2 F0 = Tensor2::Rotation(0.3) *
                       Tensor2{
                         {{1.05, 0.1}, {-0.05, 0.9}}
    },
                  Fd0 = {{{0.01, -0.02}, {0.03, 0.005}}};
    const Tensor2 G =
                    {
                      {{0.3, -0.8}, {0.6, -0.2}}
    },
                  H = {{{-0.5, 0.4}, {0.2, 0.7}}};
    MaterialResponse r0, r, status;
    Tangents         D;
    TangentOptions   opt;
    opt.method = TangentMethod::Implicit;
    PetscCall(sp.Evaluate(F0, Fd0, EvaluationKind::Trial, &r0));
    PetscCall(ComputeTangents(sp, F0, Fd0, r0, opt, &D, &status));
    TG_CHECK(status.ok, "exact tangents failed: %s", status.reason.c_str());
    sp.KeepTangents(F0, Fd0, r0, D);
    PetscReal err[2];
    for (int k = 0; k < 2; k++) {
      const PetscReal e = k ? 5e-4 : 1e-3;
      Tensor2         s;
      PetscReal       d2;
      TG_CHECK(sp.Expand(F0 + e * G, Fd0 + e * H, &s, &d2), "no expansion after tangents were kept");
      MaterialResponse rr;
      PetscCall(viscous.CreatePoint(PETSC_COMM_SELF, &inner));
      PetscCall(inner->Evaluate(F0 + e * G, Fd0 + e * H, EvaluationKind::Trial, &rr));
      err[k] = (s - rr.sigma).Norm();
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "expansion at e = %.0e: |error| = %.3e of |sigma - sigma0| = %.3e\n", (double)e, (double)err[k],
                            (double)(rr.sigma - r0.sigma).Norm()));
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "expansion: the error falls %.2fx when the step halves\n", (double)(err[0] / err[1])));
    TG_CHECK(err[0] / err[1] > 3.5 && err[0] / err[1] < 4.5, "the expansion is not first order exact (its error falls %.2fx)", (double)(err[0] / err[1]));
    /* a solve measures the constant; then a trial within the tolerance is answered without one */
    PetscCall(sp.Evaluate(F0 + 1e-2 * G, Fd0, EvaluationKind::Trial, &r));
    MaterialCounters c;
    PetscCall(sp.Evaluate(F0 + 1e-4 * G, Fd0, EvaluationKind::Trial, &r));
    sp.AddCounters(c);
    TG_CHECK(c.skipped_solves == 1, "a trial 1e-4 from the base was solved (%" PetscInt_FMT " skipped)", c.skipped_solves);
    PetscCall(PetscOptionsClearValue(NULL, "-nh_viscosity"));
  }
  {
    /* second-order work: a neo-Hookean point stretched along x in plane strain has dS = [lambda +
       2 mu, lambda] dE11 at F = I, so cos(dS, dE) = (lambda + 2 mu) / sqrt((lambda + 2 mu)^2 +
       lambda^2) (the closed form; O(strain) off it at 1e-4) */
    NeoHookeanSpec   p;
    NeoHookean       nhs(p);
    MaterialResponse ra, rb;
    const Tensor2    Fa =
                    {
                      {{1 + 1e-4, 0}, {0, 1}}
    },
                  Fb = {{{1 + 2e-4, 0}, {0, 1}}};
    PetscCall(nhs.Evaluate(Fa, Tensor2::Zero(), EvaluationKind::Trial, &ra));
    PetscCall(nhs.Evaluate(Fb, Tensor2::Zero(), EvaluationKind::Trial, &rb));
    const StrainStress a = GreenLagrangeAndPiola(Fa, ra.sigma), b = GreenLagrangeAndPiola(Fb, rb.sigma);
    const PetscReal    c = SecondOrderWorkCosine(a, b, 1e-12, 1e-6), l2m = p.lambda + 2 * p.mu;
    const PetscReal    closed = l2m / std::sqrt(l2m * l2m + p.lambda * p.lambda);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "second-order work: uniaxial strain cos(dS, dE) = %.6f, closed form %.6f\n", (double)c, (double)closed));
    TG_CHECK(std::fabs(c - closed) < 1e-3, "the second-order work's cosine %g is not the closed form's %g", (double)c, (double)closed);
    /* a rigid rotation of a stressed state leaves E and S as they are: no increment to judge; the
       first Piola pair would call a turning, pressurised point unstable (dP : dF < 0) */
    const Tensor2      R = Tensor2::Rotation(0.3), Fr = R * Fb, sr = R * rb.sigma * R.T();
    const StrainStress br = GreenLagrangeAndPiola(Fr, sr);
    TG_CHECK((br.E - b.E).Norm() < 1e-14 && (br.S - b.S).Norm() < 1e-12 * b.S.Norm(), "E or S changed under a rigid rotation");
    TG_CHECK(SecondOrderWorkCosine(b, br, 1e-12, 1e-6) == 1, "a rigid rotation was judged");
    const Tensor2 pI = -5.0 * Tensor2::Identity(), F0 = Tensor2::Identity(), F1 = Tensor2::Rotation(0.05);
    auto          piola = [](const Tensor2 &F, const Tensor2 &sg) { return F.Det() * (sg * F.Inverse().T()); };
    const Tensor2 dP = piola(F1, pI) - piola(F0, pI), dF = F1 - F0;
    PetscReal     pf = 0;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) pf += dP(i, j) * dF(i, j);
    TG_CHECK(pf < 0 && SecondOrderWorkCosine(GreenLagrangeAndPiola(F0, pI), GreenLagrangeAndPiola(F1, pI), 1e-12, 1e-6) == 1,
             "a pressurised point turning by 0.05 rad: dP:dF = %g (negative expected), and (S, E) must not judge it", (double)pf);
    /* a stress that falls along a stretch (an RVE that gave way): cos near -1 */
    Tensor2 fallen = 0.5 * rb.sigma;
    TG_CHECK(SecondOrderWorkCosine(a, GreenLagrangeAndPiola(Fb, fallen), 1e-12, 1e-6) < -0.5, "a falling stress was not judged softening");
    /* below the floors: no decision */
    TG_CHECK(SecondOrderWorkCosine(a, GreenLagrangeAndPiola(Fa, fallen), 1e-12, 1e-6) == 1, "no strain increment, yet judged");
    TG_CHECK(SecondOrderWorkCosine(a, a, 1e-12, 1e-6) == 1, "no increment at all, yet judged");
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_material: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
