static const char help[] = "The repulsion is smooth across the joints of bent walls:\n"
                           "- continuity: a particle moved across the bisector of a bent joint in 1e-6 µm steps, on its\n"
                           "  concave and convex sides, sees its force change by less than 1e-6 of its size per step\n"
                           "  (and the bisector rule without a wedge, -repulsion_joint_blend 0, does jump there);\n"
                           "- the force on every particle is minus the gradient of the energy (central differences) at\n"
                           "  and across joints bent by 0 to 60 degrees, with and without the angle factor, around\n"
                           "  walls of long and of short springs (both wedges of a spring at once, the extension's tip);\n"
                           "- linear and angular momentum are conserved there, with damping and the angle factor, and the\n"
                           "  virial is that of the forces.\n";
#include "test_util.h"
#include <turgor/physics/repulsion.h>

using namespace turgor;

static const PetscReal kLambda = 5e5, kX0 = 5.0;

struct Config {
  PetscBool angle, damping;
  PetscReal blend; /* degrees; < 0: the default */
};

static PetscErrorCode RepulsionModel(const Tissue &T, Config c, ForceModel *model)
{
  PhysicsSpec physics;
  PetscFunctionBeginUser;
  auto rep          = std::make_unique<Repulsion>();
  rep->strength     = kLambda;
  rep->cutoff       = kX0;
  rep->angle_factor = c.angle;
  rep->damping      = c.damping;
  if (c.blend >= 0) rep->joint_blend = c.blend;
  physics.Add(std::move(rep));
  PetscCall(model->SetUp(physics, T.particles));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A wall of n springs of length l through the origin, bent at each joint by `bend` degrees towards
   +y (its bisector at the middle joint is the y axis when n is even), joints found straight and the
   bend applied afterwards (the joints are the topology, fixed). Wall particles 0..n, then `probes`
   fluid particles at the origin. */
static void BentWall(PetscInt n, PetscReal l, PetscReal bend, PetscInt probes, Tissue *T)
{
  *T = Tissue();
  for (PetscInt k = 0; k <= n; k++) T->AddParticle((k - n / 2) * l, 0, 0.5, KIND_WALL);
  for (PetscInt k = 0; k < probes; k++) T->AddParticle(0, 0, 0.4, KIND_FLUID, 0);
  for (PetscInt k = 0; k < n; k++) {
    if (k % 2) T->AddSpring(k + 1, k);
    else T->AddSpring(k, k + 1);
  }
  T->Finalize();
  /* walk out from the middle point, turning by `bend` at every joint, symmetric about the y axis */
  const PetscReal b = bend * PETSC_PI / 180, m = (PetscReal)(n / 2);
  for (int side = -1; side <= 1; side += 2) {
    PetscReal px = 0, py = 0, angle = side > 0 ? 0.5 * b : PETSC_PI - 0.5 * b;
    for (PetscInt k = 1; k <= (side > 0 ? n - n / 2 : n / 2); k++) {
      px += l * std::cos(angle);
      py += l * std::sin(angle);
      const PetscInt i = (PetscInt)m + side * k;
      T->X[2 * i]      = px;
      T->X[2 * i + 1]  = py;
      angle += side > 0 ? b : -b;
    }
  }
}

/* Move the probe along x at height y0 from -X to X in steps h; the largest change of the force
   between steps, and of that change from one step to the next, relative to the largest force on
   the way, and where they are. */
static PetscErrorCode Scan(const Tissue &T, Config c, PetscReal y0, PetscReal X, PetscReal h, PetscReal *jump, PetscReal *second, PetscReal *fmax,
                           PetscReal *at, PetscReal *at2)
{
  ForceModel     model;
  const PetscInt probe = T.particles.n - 1;
  PetscFunctionBeginUser;
  PetscCall(RepulsionModel(T, c, &model));
  std::vector<PetscReal> x       = T.X, v(x.size(), 0.0), f(x.size());
  PetscReal              prev[2] = {0, 0}, step[2] = {0, 0}, worst = 0, worst2 = 0, big = 0;
  const PetscInt         steps = (PetscInt)std::llround(2 * X / h);
  for (PetscInt k = 0; k <= steps; k++) {
    x[2 * probe]     = -X + k * h;
    x[2 * probe + 1] = y0;
    PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
    const PetscReal fx = f[2 * probe], fy = f[2 * probe + 1];
    big = PetscMax(big, std::hypot(fx, fy));
    if (k > 0 && std::hypot(fx - prev[0], fy - prev[1]) > worst) {
      worst = std::hypot(fx - prev[0], fy - prev[1]);
      *at   = x[2 * probe];
    }
    /* the change of the change: a jump J shows as J, a kink of the slope as 1e-6 times it */
    if (k > 1 && std::hypot(fx - prev[0] - step[0], fy - prev[1] - step[1]) > worst2) {
      worst2 = std::hypot(fx - prev[0] - step[0], fy - prev[1] - step[1]);
      *at2   = x[2 * probe];
    }
    step[0] = fx - prev[0];
    step[1] = fy - prev[1];
    prev[0] = fx;
    prev[1] = fy;
  }
  *jump   = worst / big;
  *second = worst2 / big;
  *fmax   = big;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Continuity()
{
  Tissue    T;
  PetscReal jump, second, fmax, at, at2;
  PetscFunctionBeginUser;
  BentWall(2, 12.5, 12.0, 1, &T); /* two springs, bent by 12 degrees at the origin */
  const PetscReal beta = Repulsion().joint_blend * PETSC_PI / 180;
  for (PetscReal y0 : {3.5, -3.5}) {
    /* through the whole wedge (the default 10 degrees: 0.62 µm on either side of the bisector at 3.5 µm) */
    const PetscReal X = 1.2 * std::fabs(y0) * std::tan(beta);
    for (Config c : {
           Config{PETSC_TRUE,  PETSC_FALSE, -1},
           Config{PETSC_FALSE, PETSC_TRUE,  -1}
    }) {
      PetscCall(Scan(T, c, y0, X, 1e-6, &jump, &second, &fmax, &at, &at2));
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "joint bent 12 deg, %s side (y = %g µm), angle factor %s damping %s: across x = ±%.3f µm in 1e-6 µm steps, largest change %.2e of "
                            "max |F| = %.4g µN (at x = %.6f), of that change from step to step %.1e (at x = %.6f)\n",
                            y0 > 0 ? "concave" : "convex", (double)y0, c.angle ? "on" : "off", c.damping ? "on" : "off", (double)X, (double)jump, (double)fmax,
                            (double)at, (double)second, (double)at2));
      TG_CHECK(jump < 1e-6, "the force jumps by %.3e of its size across a bent joint", (double)jump);
      /* the slope's changes: ~3e-12 where the wedge ends (the weight's third derivative jumps), ~1e-9
         on the convex side where the closest point reaches the tip of the spring's extension (the
         distance turns from a line's to a point's, as at a free end) */
      TG_CHECK(second < 1e-8, "the force's slope jumps by %.3e of its size (per 1e-6 µm) across a bent joint", (double)second);
    }
  }
  /* without the wedge (the bisector rule) the force turns by the bend angle at the bisector */
  PetscCall(Scan(T, Config{PETSC_TRUE, PETSC_FALSE, 0}, 3.5, 1e-3, 1e-6, &jump, &second, &fmax, &at, &at2));
  PetscCall(
    PetscPrintf(PETSC_COMM_SELF,
                "the same, concave side, -repulsion_joint_blend 0: largest change %.2e of max |F| (at x = %.2e; 2 sin 6 deg = %.3f), of that change %.1e\n",
                (double)jump, (double)at, 2 * std::sin(6 * PETSC_PI / 180), (double)second));
  TG_CHECK(jump > 0.1, "the bisector rule should jump at a bent joint (%.3e)", (double)jump);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Forces against central differences of the energy, for every particle, with the probes placed
   around the middle joint, mostly inside or near its wedge, on both sides. */
static PetscErrorCode GradientAndMomenta(const char *name, PetscInt n, PetscReal l, PetscReal bend, unsigned long long seed)
{
  const PetscInt      probes = 24;
  Tissue              T;
  turgor_test::Random rnd(seed);
  PetscFunctionBeginUser;
  BentWall(n, l, bend, probes, &T);
  const PetscInt first = n + 1, np = T.particles.n;
  for (PetscInt k = 0; k < probes;) {
    /* an angle from the bisector (the y axis), mostly within 10 degrees, and a distance from the joint */
    const PetscReal psi = (k % 3 ? 10.0 : 60.0) * rnd() * PETSC_PI / 180, rho = 2.6 + 2.8 * std::fabs(rnd()), side = k % 2 ? 1.0 : -1.0;
    const PetscReal px = rho * std::sin(psi), py = side * rho * std::cos(psi);
    /* at least 0.8 µm from every spring */
    bool ok = true;
    for (PetscInt s = 0; s < n; s++) {
      const PetscReal *a = &T.X[2 * s], *b = &T.X[2 * s + 2];
      const PetscReal  tx = b[0] - a[0], ty = b[1] - a[1], t = std::min(1.0, std::max(0.0, ((px - a[0]) * tx + (py - a[1]) * ty) / (tx * tx + ty * ty)));
      ok = ok && std::hypot(px - a[0] - t * tx, py - a[1] - t * ty) > 0.8;
    }
    if (!ok) continue;
    T.X[2 * (first + k)]     = px;
    T.X[2 * (first + k) + 1] = py;
    k++;
  }
  PetscReal worst = 0;
  for (PetscBool angle : {PETSC_FALSE, PETSC_TRUE}) {
    ForceModel model;
    PetscCall(RepulsionModel(T, {angle, PETSC_FALSE, -1}, &model));
    std::vector<PetscReal> x = T.X, v(2 * np, 0.0), f(2 * np);
    PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
    PetscReal fmax = 0, err = 0, h = 1e-6;
    for (PetscReal fk : f) fmax = PetscMax(fmax, std::fabs(fk));
    for (PetscInt k = 0; k < 2 * np; k++) {
      PetscReal Ep, Em, x0 = x[k];
      PetscBool complete;
      x[k] = x0 + h;
      PetscCall(model.PotentialEnergy(x.data(), &Ep, &complete));
      x[k] = x0 - h;
      PetscCall(model.PotentialEnergy(x.data(), &Em, &complete));
      x[k] = x0;
      err  = PetscMax(err, std::fabs(f[k] + (Ep - Em) / (2 * h)));
    }
    worst = PetscMax(worst, err / fmax);
    TG_CHECK(fmax > 0, "%s: no force at all", name);
    TG_CHECK(err <= 1e-7 * fmax, "%s, angle factor %s: forces are not the gradient of the energy (%.3e)", name, angle ? "on" : "off", (double)(err / fmax));
  }
  PetscReal Pr = 0, Lr = 0, Vr = 0;
  {
    ForceModel model;
    PetscCall(RepulsionModel(T, {PETSC_TRUE, PETSC_TRUE, -1}, &model));
    std::vector<PetscReal> v(2 * np), f(2 * np);
    for (PetscReal &vk : v) vk = rnd();
    PetscReal W[4] = {0, 0, 0, 0}, Wf[4] = {0, 0, 0, 0}, Ws = 0;
    PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), W));
    PetscReal P[2] = {0, 0}, L = 0, Ps = 0, Ls = 0;
    for (PetscInt i = 0; i < np; i++) {
      const PetscReal *xi = &T.X[2 * i], *fi = &f[2 * i];
      P[0] += fi[0];
      P[1] += fi[1];
      L += xi[0] * fi[1] - xi[1] * fi[0];
      Ps += std::hypot(fi[0], fi[1]);
      Ls += std::hypot(xi[0], xi[1]) * std::hypot(fi[0], fi[1]);
      for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) Wf[2 * a + b] -= fi[a] * xi[b];
    }
    /* the virial the term reports (its interactions' -sum f (x) x, built from relative positions) is
       that of the forces it applied: the weight's gradient and the extensions' tips included */
    for (int k = 0; k < 4; k++) Ws = PetscMax(Ws, std::fabs(W[k] - Wf[k]));
    Vr = Ws / Ls;
    TG_CHECK(Vr <= 1e-13, "%s: the virial is not -sum f (x) x of the forces (%.3e)", name, (double)Vr);
    Pr = std::hypot(P[0], P[1]) / Ps;
    Lr = std::fabs(L) / Ls;
    TG_CHECK(Pr <= 1e-14, "%s: linear momentum not conserved (%.3e)", name, (double)Pr);
    TG_CHECK(Lr <= 1e-14, "%s: angular momentum not conserved (%.3e)", name, (double)Lr);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-44s max |f + dE/dx| / max |f| = %.2e, |sum f|/sum|f| = %.1e, |sum x x f|/sum |x||f| = %.1e, virial %.1e\n", name,
                        (double)worst, (double)Pr, (double)Lr, (double)Vr));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(Continuity());
  /* long springs: one wedge at a time; short ones (2.5 µm): a particle in both wedges of a spring */
  PetscCall(GradientAndMomenta("2 springs of 12.5 µm, straight", 2, 12.5, 0, 31));
  PetscCall(GradientAndMomenta("2 springs of 12.5 µm, bent 3 deg", 2, 12.5, 3, 32));
  PetscCall(GradientAndMomenta("2 springs of 12.5 µm, bent 20 deg", 2, 12.5, 20, 33));
  PetscCall(GradientAndMomenta("2 springs of 12.5 µm, bent 60 deg", 2, 12.5, 60, 34));
  PetscCall(GradientAndMomenta("6 springs of 2.5 µm, bent 8 deg at each joint", 6, 2.5, 8, 35));
  PetscCall(GradientAndMomenta("6 springs of 2.5 µm, bent 35 deg at each joint", 6, 2.5, 35, 36));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_repulsion_joints: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
