static const char help[] = "Tangent machinery (TW 562 eqs 46-53) on the closed-form neo-Hookean material:\n"
                           "forward- and central-difference D^e and D^v against the analytic tangents (1e-6), and the exact\n"
                           "ones of -material_tangent implicit (1e-13),\n"
                           "for several deformations including shear and rotation; inverted F is a failed evaluation.\n";
#include "test_util.h"
#include <turgor/material/neo_hookean.h>

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
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_material: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
