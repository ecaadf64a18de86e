static const char help[] = "Each physics term's forces against an independent check:\n"
                           "central finite differences of its energy (springs, repulsion, SPH pressure, body force),\n"
                           "the cos(alpha) factor of the repulsion beyond a spring's end, the dashpot and repulsion\n"
                           "damping against their formulas, and the viscous power\n"
                           "identity sum_k f_k . v_k = -sum_i V_i tau_i : grad v_i of the corrected SPH viscosity.\n";
#include "test_util.h"
#include "fine_run_util.h"
#include <turgor/physics/repulsion.h>
#include <turgor/physics/sph_fluid.h>
#include <turgor/physics/wall_springs.h>

using namespace turgor;

/* A 2 x 2 cell tissue with every particle displaced at random (up to `amp` µm). */
static PetscErrorCode DisorderedTissue(PetscReal amp, Tissue *T)
{
  PetscFunctionBeginUser;
  PetscCall(turgor_test::SquareGridTissue(2, T));
  turgor_test::Random rnd(7);
  for (PetscReal &x : T->X) x += amp * rnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* max_k |f_k + dE/dx_k| / max_k |f_k| with central differences of step h [µm]. The SPH energy is
   large (sum m c^2 ln rho) compared with its variations, so it needs a larger step against round-off. */
static PetscErrorCode CompareWithEnergy(ForceModel &model, const Tissue &T, const char *name, PetscReal tol, PetscReal h = 1e-6)
{
  const PetscInt         n    = T.particles.n;
  std::vector<PetscReal> x    = T.X, v(2 * n, 0.0), f(2 * n);
  PetscReal              fmax = 0, err = 0, Ep, Em;
  PetscBool              complete;
  PetscFunctionBeginUser;
  PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
  for (PetscReal fk : f) fmax = PetscMax(fmax, std::fabs(fk));
  for (PetscInt k = 0; k < 2 * n; k++) {
    const PetscReal x0 = x[k];
    x[k]               = x0 + h;
    PetscCall(model.PotentialEnergy(x.data(), &Ep, &complete));
    x[k] = x0 - h;
    PetscCall(model.PotentialEnergy(x.data(), &Em, &complete));
    x[k] = x0;
    TG_CHECK(complete, "%s has no energy", name);
    err = PetscMax(err, std::fabs(f[k] + (Ep - Em) / (2 * h)));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-28s max |f + dE/dx| / max |f| = %.3e  (max |f| = %.4g µN)\n", name, (double)(err / fmax), (double)fmax));
  TG_CHECK(fmax > 0, "%s: no force at all, the test would be vacuous", name);
  TG_CHECK(err <= tol * fmax, "%s: forces are not the gradient of the energy (%.3e)", name, (double)(err / fmax));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A model of the named terms, in this order, each configured from its options (the defaults unless
   given on the command line), except the repulsion's angle factor: off, so that its forces are the
   gradient of its energy. */
static PetscErrorCode ModelWith(const std::vector<std::string> &names, const Tissue &T, ForceModel *model)
{
  PhysicsSpec physics;
  LoadSpec    load;
  PetscFunctionBeginUser;
  for (const std::string &name : names) {
    std::unique_ptr<ForceTerm> term;
    PetscCall(ForceTermCreate(PETSC_COMM_SELF, name, "-physics", &term));
    PetscCall(term->SetFromOptions(PETSC_COMM_SELF, TermContext{&load}));
    if (auto *rep = dynamic_cast<Repulsion *>(term.get())) rep->angle_factor = PETSC_FALSE;
    physics.Add(std::move(term));
  }
  PetscCall(model->SetUp(physics, T.particles));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A model of one term built by hand. */
static PetscErrorCode ModelOf(std::unique_ptr<ForceTerm> term, const Tissue &T, ForceModel *model)
{
  PhysicsSpec physics;
  PetscFunctionBeginUser;
  physics.Add(std::move(term));
  PetscCall(model->SetUp(physics, T.particles));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Repulsion of one particle from one spring [(0,0), (10,0)], angle factor on: inside the spring the
   force is the conservative one; beyond its end it is scaled by cos(alpha) = |d x t| / (|d| |t|). */
static PetscErrorCode RepulsionAngleFactor()
{
  PetscFunctionBeginUser;
  for (PetscReal px : {4.0, 12.0}) {
    Tissue T;
    T.AddParticle(0, 0, 0.5, KIND_WALL);
    T.AddParticle(10, 0, 0.5, KIND_WALL);
    T.AddParticle(px, 2.5, 0.4, KIND_FLUID, 0);
    T.AddSpring(0, 1);
    T.Finalize();
    std::vector<PetscReal> f_on(6), f_off(6), v(6, 0.0);
    for (PetscBool angle : {PETSC_TRUE, PETSC_FALSE}) {
      ForceModel model;
      auto       rep    = std::make_unique<Repulsion>();
      rep->angle_factor = angle;
      PetscCall(ModelOf(std::move(rep), T, &model));
      PetscCall(model.ComputeForces(T.X.data(), v.data(), angle ? f_on.data() : f_off.data(), NULL));
    }
    const PetscReal dx = px - std::min<PetscReal>(px, 10), dy = 2.5, cosa = dy / std::hypot(dx, dy);
    for (int k = 0; k < 6; k++) TG_CHECK_CLOSE(f_on[k], cosa * f_off[k], 1e-14, 1e-300, "repulsion angle factor");
    /* force on the particle points away from the closest point, reactions sum to zero */
    TG_CHECK(f_off[4] * dx + f_off[5] * dy > 0, "repulsion must push the particle away");
    TG_CHECK_CLOSE(f_on[0] + f_on[2] + f_on[4], 0.0, 1e-14, std::fabs(f_on[5]), "repulsion x momentum");
    TG_CHECK_CLOSE(f_on[1] + f_on[3] + f_on[5], 0.0, 1e-14, std::fabs(f_on[5]), "repulsion y momentum");
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "repulsion at x = %4.1f: cos(alpha) = %.4f, |F| = %.4g µN\n", (double)px, (double)cosa,
                          (double)std::hypot(f_on[4], f_on[5])));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The velocity-dependent (dissipative) parts have no energy: check them against their formulas,
   evaluated here independently: the spring dashpot gamma (e . v_ij) e with gamma = 2 sqrt(m k)
   (eq 16), and the repulsion's critical damping -2 sqrt(6 lambda m / r^7) ((v - v^) . e) e (eq 17). */
static PetscErrorCode DampingTerms()
{
  PetscFunctionBeginUser;
  {
    Tissue T;
    T.AddParticle(0, 0, 0.5, KIND_WALL);
    T.AddParticle(12.0, 5.0, 0.5, KIND_WALL);
    T.AddSpring(0, 1);
    T.Finalize();
    T.X[2] += 0.3; /* stretched */
    const std::vector<PetscReal> v = {0.2, -0.4, -0.7, 0.9}, v0(4, 0.0);
    std::vector<PetscReal>       f(4), f0(4);
    ForceModel                   model;
    PetscCall(ModelOf(std::make_unique<WallSprings>(), T, &model));
    PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
    PetscCall(model.ComputeForces(T.X.data(), v0.data(), f0.data(), NULL));
    const PetscReal dx = T.X[2] - T.X[0], dy = T.X[3] - T.X[1], r = std::hypot(dx, dy), ex = dx / r, ey = dy / r;
    const PetscReal gamma = 2 * std::sqrt(0.5 * 4000.0), vn = (v[2] - v[0]) * ex + (v[3] - v[1]) * ey;
    TG_CHECK_CLOSE(f[0] - f0[0], gamma * vn * ex, 1e-12, std::fabs(gamma * vn), "dashpot force x");
    TG_CHECK_CLOSE(f[1] - f0[1], gamma * vn * ey, 1e-12, std::fabs(gamma * vn), "dashpot force y");
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "spring dashpot: %.6g µN along the spring, as gamma (e . v_ij) with gamma = %.6g ng/µs\n",
                          (double)((f[0] - f0[0]) * ex + (f[1] - f0[1]) * ey), (double)gamma));
  }
  {
    Tissue T;
    T.AddParticle(0, 0, 0.5, KIND_WALL);
    T.AddParticle(10, 0, 0.5, KIND_WALL);
    T.AddParticle(4, 2.5, 0.4, KIND_FLUID, 0);
    T.AddSpring(0, 1);
    T.Finalize();
    const std::vector<PetscReal> v = {0.1, 0.2, -0.2, 0.5, 0.3, -1.2}, v0(6, 0.0);
    std::vector<PetscReal>       f(6), f0(6);
    ForceModel                   model;
    PetscCall(ModelOf(std::make_unique<Repulsion>(), T, &model));
    PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
    PetscCall(model.ComputeForces(T.X.data(), v0.data(), f0.data(), NULL));
    const PetscReal t = 0.4, r = 2.5, vh = (1 - t) * v[1] + t * v[3]; /* closest point (4, 0), normal e = (0, 1) */
    const PetscReal damp = -2 * std::sqrt(6 * 5e5 * 0.4 / std::pow(r, 7)) * (1 - std::pow(r / 5.0, 6)) * (v[5] - vh); /* tapered */
    TG_CHECK_CLOSE(f[5] - f0[5], damp, 1e-12, std::fabs(damp), "repulsion damping on the particle");
    TG_CHECK_CLOSE(f[1] - f0[1], -(1 - t) * damp, 1e-12, std::fabs(damp), "repulsion damping reaction on x1");
    TG_CHECK_CLOSE(f[3] - f0[3], -t * damp, 1e-12, std::fabs(damp), "repulsion damping reaction on x2");
    TG_CHECK(std::fabs(f[4] - f0[4]) < 1e-12 * std::fabs(damp), "repulsion damping must act along the normal");
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "repulsion damping: %.6g µN, as -2 sqrt(6 lambda m / r^7) (1 - (r/x0)^6) (v - v^).e\n", (double)(f[5] - f0[5])));
  }
  { /* continuity at the cutoff: just inside x0 the damping is ~0 (the literal term is not) */
    for (PetscBool taper : {PETSC_TRUE, PETSC_FALSE}) {
      Tissue T;
      T.AddParticle(0, 0, 0.5, KIND_WALL);
      T.AddParticle(10, 0, 0.5, KIND_WALL);
      T.AddParticle(4, 5.0 * (1 - 1e-6), 0.4, KIND_FLUID, 0);
      T.AddSpring(0, 1);
      T.Finalize();
      const std::vector<PetscReal> v = {0, 0, 0, 0, 0, -1.0}, v0(6, 0.0);
      std::vector<PetscReal>       f(6), f0(6);
      ForceModel                   model;
      auto                         rep = std::make_unique<Repulsion>();
      rep->damping_taper               = taper;
      PetscCall(ModelOf(std::move(rep), T, &model));
      PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
      PetscCall(model.ComputeForces(T.X.data(), v0.data(), f0.data(), NULL));
      const PetscReal literal = 2 * std::sqrt(6 * 5e5 * 0.4 / std::pow(5.0, 7)); /* |v| = 1 */
      const PetscReal ratio   = std::fabs(f[5] - f0[5]) / literal;
      if (taper) TG_CHECK(ratio < 1e-5, "tapered repulsion damping must vanish at the cutoff");
      else TG_CHECK(std::fabs(ratio - 1) < 1e-5, "the literal damping keeps its full value at the cutoff");
      PetscCall(
        PetscPrintf(PETSC_COMM_SELF, "repulsion damping at r = x0 (1 - 1e-6), taper %s: %.3g of the literal value\n", taper ? "on" : "off", (double)ratio));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The corrected viscous forces are the variational counterpart of the velocity gradient:
   sum_k f_k . v_k = -sum_i V_i tau_i : grad v_i exactly (power of the internal forces). */
static PetscErrorCode ViscousPower(const Tissue &T, PetscBool correction)
{
  const PetscInt         n = T.particles.n;
  std::vector<PetscReal> v(2 * n), f(2 * n), rho, gradv;
  turgor_test::Random    rnd(11);
  PetscFunctionBeginUser;
  for (PetscReal &vk : v) vk = rnd();
  ForceModel model;
  auto       own   = std::make_unique<SPHFluid>();
  own->sound_speed = 0; /* viscous stress only */
  own->viscosity   = 0.5;
  own->correction  = correction;
  PetscCall(ModelOf(std::move(own), T, &model));
  auto *sph = dynamic_cast<SPHFluid *>(model.Term("sph")); /* the model's own, set-up copy */
  PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
  const ForceInput in = {&T.particles, T.X.data(), v.data(), &model.Neighbours(), &model.Images()};
  PetscCall(sph->DensityAndVelocityGradient(in, rho, gradv));
  PetscReal pf = 0, ps = 0;
  for (PetscInt k = 0; k < 2 * n; k++) pf += f[k] * v[k];
  for (PetscInt i = 0; i < n; i++) {
    if (T.particles.kind[i] != KIND_FLUID) continue;
    const PetscReal *g = &gradv[4 * i], tr = g[0] + g[3], mu = sph->viscosity;
    const PetscReal  txx = mu * (2 * g[0] - 2.0 / 3.0 * tr), tyy = mu * (2 * g[3] - 2.0 / 3.0 * tr), txy = mu * (g[1] + g[2]);
    ps -= T.particles.mass[i] / rho[i] * (txx * g[0] + txy * (g[1] + g[2]) + tyy * g[3]);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "viscous power (correction %-3s): sum f.v = %.12g, -sum V tau:grad v = %.12g\n", correction ? "on" : "off", (double)pf,
                        (double)ps));
  TG_CHECK(ps < 0, "viscosity must dissipate");
  TG_CHECK_CLOSE(pf, ps, 1e-10, 0, "viscous power identity");
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  Tissue T;
  PetscCall(DisorderedTissue(0.8, &T));
  {
    ForceModel m;
    PetscCall(ModelWith({"springs"}, T, &m));
    PetscCall(CompareWithEnergy(m, T, "springs", 1e-7));
  }
  {
    ForceModel m;
    PetscCall(ModelWith({"repulsion"}, T, &m));
    PetscCall(CompareWithEnergy(m, T, "repulsion (no angle factor)", 1e-7));
  }
  {
    ForceModel m;
    PetscCall(ModelWith({"sph"}, T, &m));
    PetscCall(CompareWithEnergy(m, T, "sph pressure", 1e-6, 1e-4));
  }
  {
    ForceModel m;
    PetscCall(ModelWith({"body_force"}, T, &m));
    PetscCall(CompareWithEnergy(m, T, "body force", 1e-7, 1e-2)); /* linear energy: any step is exact */
  }
  {
    ForceModel m;
    PetscCall(ModelWith({"springs", "repulsion", "sph", "body_force"}, T, &m));
    PetscCall(CompareWithEnergy(m, T, "all terms together", 1e-6, 1e-4));
  }
  PetscCall(RepulsionAngleFactor());
  PetscCall(DampingTerms());
  PetscCall(ViscousPower(T, PETSC_TRUE));
  PetscCall(ViscousPower(T, PETSC_FALSE));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_force_consistency: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
