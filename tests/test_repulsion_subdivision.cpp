static const char help[] = "The repulsion of a straight wall does not depend on how many springs it is cut into, and walls\n"
                           "meeting at a corner push independently:\n"
                           "- a particle near a straight wall of 2, 4, 8 and 16 collinear springs (the last shorter than the\n"
                           "  cutoff) feels the same force within 1e-12 relative (the energy within 1e-10: near the cutoff it\n"
                           "  is a difference of terms 1e5 times larger), along the whole wall and beyond its\n"
                           "  free ends, at several distances below the cutoff, right over the joints and next to them, with\n"
                           "  and without the angle factor and the damping; a straight wall does not repel its own particles;\n"
                           "- corners (an L of two springs at 90 and 120 degrees, a T of three, a + of four): forces against\n"
                           "  central differences of the energy, linear and angular momentum, the + as the sum of its two\n"
                           "  straight walls and the L as the sum of its two springs;\n"
                           "- the straight joints found in a square-grid tissue and in a periodic RVE cell.\n";
#include "test_util.h"
#include <turgor/physics/repulsion.h>

using namespace turgor;

static const PetscReal kLambda = 5e5, kX0 = 5.0;

struct Config {
  PetscBool angle, damping;
};

/* A model with one repulsion term (the seed's lambda and x0). */
static PetscErrorCode RepulsionModel(const Tissue &T, Config c, ForceModel *model)
{
  PhysicsSpec physics;
  PetscFunctionBeginUser;
  auto rep          = std::make_unique<Repulsion>();
  rep->strength     = kLambda;
  rep->cutoff       = kX0;
  rep->angle_factor = c.angle;
  rep->damping      = c.damping;
  physics.Add(std::move(rep));
  PetscCall(model->SetUp(physics, T.particles));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A straight wall of n springs from A to B (wall particles 0..n) and one fluid particle (n + 1),
   whose position each sample sets. */
static void StraightWall(PetscInt n, const PetscReal A[2], const PetscReal B[2], Tissue *T)
{
  *T = Tissue();
  for (PetscInt k = 0; k <= n; k++) T->AddParticle(A[0] + (B[0] - A[0]) * k / n, A[1] + (B[1] - A[1]) * k / n, 0.5, KIND_WALL);
  T->AddParticle(0, 0, 0.4, KIND_FLUID, 0);
  for (PetscInt k = 0; k < n; k++) T->AddSpring(k, k + 1);
  T->Finalize();
}

/* Velocities of an affine field v = a + G x (the wall's nodes), so that the interpolated v^ on the
   wall is the field itself whatever the subdivision; the particle has its own velocity. */
static void AffineVelocities(const Tissue &T, PetscInt probe, std::vector<PetscReal> &v)
{
  const PetscReal a[2] =
    {
      0.3, -0.2
  },
                  G[2][2] = {{0.02, -0.05}, {0.04, 0.01}};
  v.assign(T.X.size(), 0.0);
  for (PetscInt i = 0; i < T.particles.n; i++)
    for (int d = 0; d < 2; d++) v[2 * i + d] = a[d] + G[d][0] * T.X[2 * i] + G[d][1] * T.X[2 * i + 1];
  v[2 * probe]     = -0.7;
  v[2 * probe + 1] = 0.45;
}

/* The force on the particle at each sample point, and the repulsion energy there. */
static PetscErrorCode SampleWall(PetscInt n, const PetscReal A[2], const PetscReal B[2], Config c, const std::vector<PetscReal> &points,
                                 std::vector<PetscReal> &F, std::vector<PetscReal> &E)
{
  Tissue     T;
  ForceModel model;
  PetscFunctionBeginUser;
  StraightWall(n, A, B, &T);
  PetscCall(RepulsionModel(T, c, &model));
  const PetscInt         probe = n + 1;
  std::vector<PetscReal> x     = T.X, v, f(x.size());
  if (c.damping) AffineVelocities(T, probe, v);
  else v.assign(x.size(), 0.0);
  F.resize(points.size());
  E.resize(points.size() / 2);
  for (size_t k = 0; 2 * k < points.size(); k++) {
    PetscReal E0;
    PetscBool complete;
    x[2 * probe]     = points[2 * k];
    x[2 * probe + 1] = points[2 * k + 1];
    PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
    PetscCall(model.PotentialEnergy(x.data(), &E0, &complete));
    /* the reaction on the wall is the opposite of the force on the particle, point by point */
    PetscReal rx = 0, ry = 0;
    for (PetscInt i = 0; i <= n; i++) {
      rx += f[2 * i];
      ry += f[2 * i + 1];
    }
    TG_CHECK_CLOSE(rx, -f[2 * probe], 1e-12, std::hypot(f[2 * probe], f[2 * probe + 1]) + 1e-300, "reaction x");
    TG_CHECK_CLOSE(ry, -f[2 * probe + 1], 1e-12, std::hypot(f[2 * probe], f[2 * probe + 1]) + 1e-300, "reaction y");
    F[2 * k]     = f[2 * probe];
    F[2 * k + 1] = f[2 * probe + 1];
    E[k]         = E0;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A straight wall of length 50 µm cut into 2, 4, 8, 16 springs (25, 12.5, 6.25, 3.125 µm): the
   particle's force along the wall, over it and beyond its ends, at distances 0.3 .. 4.99 µm, on
   both sides. Returns the largest relative difference against the 2-spring wall. */
static PetscErrorCode StraightWallSubdivision(const char *label, const PetscReal A[2], const PetscReal B[2], Config c, PetscReal *worst)
{
  const PetscReal        Lw = std::hypot(B[0] - A[0], B[1] - A[1]), e[2] = {(B[0] - A[0]) / Lw, (B[1] - A[1]) / Lw}, nrm[2] = {-e[1], e[0]};
  std::vector<PetscReal> pts, along;
  PetscFunctionBeginUser;
  /* every 1/160 of the wall (all joints of 16 springs), and 1e-7 µm and 0.01 µm beside every joint */
  for (PetscInt k = -24; k <= 160 + 24; k++) along.push_back(Lw * k / 160.0);
  for (PetscInt k = 0; k <= 16; k++)
    for (PetscReal off : {-1e-2, -1e-7, 1e-7, 1e-2}) along.push_back(Lw * k / 16.0 + off);
  for (PetscReal s : along)
    for (PetscReal h : {0.3, 1.0, 2.5, 4.0, 4.99, -0.7, -3.3}) {
      const PetscReal ds = s < 0 ? -s : (s > Lw ? s - Lw : 0); /* beyond a free end */
      if (std::hypot(ds, h) >= 0.999 * kX0) continue;
      pts.push_back(A[0] + s * e[0] + h * nrm[0]);
      pts.push_back(A[1] + s * e[1] + h * nrm[1]);
    }
  std::vector<PetscReal> F2, E2, Fn, En;
  PetscCall(SampleWall(2, A, B, c, pts, F2, E2));
  PetscReal Fmax = 0, Emax = 0;
  for (size_t k = 0; 2 * k < pts.size(); k++) {
    Fmax = PetscMax(Fmax, std::hypot(F2[2 * k], F2[2 * k + 1]));
    Emax = PetscMax(Emax, std::fabs(E2[k]));
  }
  *worst = 0;
  for (PetscInt n : {4, 8, 16}) {
    PetscCall(SampleWall(n, A, B, c, pts, Fn, En));
    PetscReal worst_n = 0, worst_E = 0, at[2] = {0, 0};
    for (size_t k = 0; 2 * k < pts.size(); k++) {
      const PetscReal ref = PetscMax(std::hypot(F2[2 * k], F2[2 * k + 1]), 1e-12 * Fmax);
      const PetscReal rel = std::hypot(Fn[2 * k] - F2[2 * k], Fn[2 * k + 1] - F2[2 * k + 1]) / ref;
      if (rel > worst_n) {
        worst_n = rel;
        at[0]   = (pts[2 * k] - A[0]) * e[0] + (pts[2 * k + 1] - A[1]) * e[1];
        at[1]   = (pts[2 * k] - A[0]) * nrm[0] + (pts[2 * k + 1] - A[1]) * nrm[1];
      }
      worst_E = PetscMax(worst_E, std::fabs(En[k] - E2[k]) / PetscMax(std::fabs(E2[k]), 1e-12 * Emax));
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "  %-7s %2" PetscInt_FMT
                          " springs vs 2, angle factor %-3s damping %-3s: %zu points, max |F - F2|/|F2| = %.2e (at %.4g µm along, %.4g µm off), energy %.2e\n",
                          label, n, c.angle ? "on" : "off", c.damping ? "on" : "off", pts.size() / 2, (double)worst_n, (double)at[0], (double)at[1],
                          (double)worst_E));
    TG_CHECK(worst_n <= 1e-12, "the force near a straight wall of %" PetscInt_FMT " springs differs from 2 springs by %.3e (relative)", n, (double)worst_n);
    TG_CHECK(worst_E <= 1e-10, "the energy near a straight wall of %" PetscInt_FMT " springs differs from 2 springs by %.3e (relative)", n, (double)worst_E);
    *worst = PetscMax(*worst, worst_n);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With nothing else near, a straight wall's particles feel nothing from their own wall, however
   short its springs (here 2 µm, inside the cutoff), with the angle factor off. */
static PetscErrorCode StraightWallAlone()
{
  const PetscReal A[2] = {0, 0}, B[2] = {40, 0};
  Tissue          T;
  ForceModel      model;
  PetscFunctionBeginUser;
  StraightWall(20, A, B, &T);
  PetscCall(RepulsionModel(T, {PETSC_FALSE, PETSC_FALSE}, &model));
  std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f(x.size());
  x[2 * 21]                = 1e3; /* the particle far away */
  PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
  PetscReal fmax = 0;
  for (PetscReal fk : f) fmax = PetscMax(fmax, std::fabs(fk));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "straight wall of 20 springs of 2 µm alone: max |f| on its particles = %.3g µN\n", (double)fmax));
  TG_CHECK(fmax == 0, "a straight wall must not repel its own particles (max |f| = %g)", (double)fmax);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A corner at the origin: arms of 12.5 µm in the given directions [degrees], one spring each,
   and `probes` fluid particles at random positions within the cutoff of the corner (at least 0.5 µm
   from every arm). Wall particles are displaced by up to `jitter` µm (bent joints). */
static PetscErrorCode Corner(const std::vector<PetscReal> &degrees, PetscInt probes, PetscReal jitter, unsigned long long seed, Tissue *T)
{
  turgor_test::Random rnd(seed);
  const PetscReal     Larm = 12.5;
  PetscFunctionBeginUser;
  *T = Tissue();
  T->AddParticle(0, 0, 0.5, KIND_WALL);
  for (PetscReal a : degrees) {
    const PetscReal r = a * PETSC_PI / 180;
    T->AddParticle(Larm * std::cos(r), Larm * std::sin(r), 0.5, KIND_WALL);
  }
  for (PetscInt k = 0; k < probes;) {
    const PetscReal px = 0.9 * kX0 * rnd(), py = 0.9 * kX0 * rnd();
    bool            ok = true;
    for (PetscReal a : degrees) {
      const PetscReal r = a * PETSC_PI / 180, c = std::cos(r), s = std::sin(r), along = px * c + py * s;
      const PetscReal dist = along <= 0 ? std::hypot(px, py) : std::fabs(-px * s + py * c);
      ok                   = ok && dist > 0.5 + 2 * jitter;
    }
    if (!ok) continue;
    T->AddParticle(px, py, 0.4, KIND_FLUID, 0);
    k++;
  }
  /* alternate the spring orientation (corner first or arm first) */
  for (size_t k = 0; k < degrees.size(); k++) {
    if (k % 2) T->AddSpring((PetscInt)k + 1, 0);
    else T->AddSpring(0, (PetscInt)k + 1);
  }
  T->Finalize();
  for (size_t k = 0; k <= degrees.size(); k++)
    for (int d = 0; d < 2; d++) T->X[2 * k + d] += jitter * rnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscInt PairedEnds(const ParticleSet &P)
{
  PetscInt n = 0;
  for (const Spring &s : P.springs) n += (s.joint[0] >= 0) + (s.joint[1] >= 0);
  return n;
}

/* Forces against central differences of the energy (angle factor off), and momenta (angle factor
   and damping on, random velocities). */
static PetscErrorCode CornerChecks(const char *name, const Tissue &T)
{
  const PetscInt n = T.particles.n;
  PetscFunctionBeginUser;
  {
    ForceModel model;
    PetscCall(RepulsionModel(T, {PETSC_FALSE, PETSC_FALSE}, &model));
    std::vector<PetscReal> x = T.X, v(2 * n, 0.0), f(2 * n);
    PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
    PetscReal fmax = 0, err = 0, h = 1e-6;
    for (PetscReal fk : f) fmax = PetscMax(fmax, std::fabs(fk));
    for (PetscInt k = 0; k < 2 * n; k++) {
      PetscReal Ep, Em, x0 = x[k];
      PetscBool complete;
      x[k] = x0 + h;
      PetscCall(model.PotentialEnergy(x.data(), &Ep, &complete));
      x[k] = x0 - h;
      PetscCall(model.PotentialEnergy(x.data(), &Em, &complete));
      x[k] = x0;
      err  = PetscMax(err, std::fabs(f[k] + (Ep - Em) / (2 * h)));
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-34s max |f + dE/dx| / max |f| = %.2e (max |f| = %.4g µN)", name, (double)(err / fmax), (double)fmax));
    TG_CHECK(fmax > 0, "%s: no force at all", name);
    TG_CHECK(err <= 1e-6 * fmax, "%s: forces are not the gradient of the energy (%.3e)", name, (double)(err / fmax));
  }
  {
    ForceModel model;
    PetscCall(RepulsionModel(T, {PETSC_TRUE, PETSC_TRUE}, &model));
    std::vector<PetscReal> v(2 * n), f(2 * n);
    turgor_test::Random    rnd(5);
    for (PetscReal &vk : v) vk = rnd();
    PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
    PetscReal P[2] = {0, 0}, L = 0, Ps = 0, Ls = 0;
    for (PetscInt i = 0; i < n; i++) {
      const PetscReal *xi = &T.X[2 * i], *fi = &f[2 * i];
      P[0] += fi[0];
      P[1] += fi[1];
      L += xi[0] * fi[1] - xi[1] * fi[0];
      Ps += std::hypot(fi[0], fi[1]);
      Ls += std::hypot(xi[0], xi[1]) * std::hypot(fi[0], fi[1]);
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF, ", |sum f|/sum|f| = %.1e, |sum x x f|/sum |x||f| = %.1e\n", (double)(std::hypot(P[0], P[1]) / Ps),
                          (double)(std::fabs(L) / Ls)));
    TG_CHECK(std::hypot(P[0], P[1]) <= 1e-14 * Ps, "%s: linear momentum not conserved", name);
    TG_CHECK(std::fabs(L) <= 1e-14 * Ls, "%s: angular momentum not conserved", name);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The probes' forces in T equal the sums of their forces in the parts (same particles, the springs
   split between the parts), to round-off. */
static PetscErrorCode SumOfParts(const char *name, const Tissue &T, const std::vector<std::vector<PetscInt>> &parts)
{
  const PetscInt         n = T.particles.n;
  std::vector<PetscReal> v(2 * n), f(2 * n), fsum(2 * n, 0.0), fp(2 * n);
  turgor_test::Random    rnd(9);
  PetscFunctionBeginUser;
  for (PetscReal &vk : v) vk = rnd();
  {
    ForceModel model;
    PetscCall(RepulsionModel(T, {PETSC_TRUE, PETSC_TRUE}, &model));
    PetscCall(model.ComputeForces(T.X.data(), v.data(), f.data(), NULL));
  }
  for (const auto &springs : parts) {
    Tissue Tp = T;
    Tp.particles.springs.clear();
    for (PetscInt s : springs) Tp.particles.springs.push_back(T.particles.springs[s]);
    Tp.Finalize(); /* the joints of the part alone */
    ForceModel model;
    PetscCall(RepulsionModel(Tp, {PETSC_TRUE, PETSC_TRUE}, &model));
    PetscCall(model.ComputeForces(T.X.data(), v.data(), fp.data(), NULL));
    for (PetscInt k = 0; k < 2 * n; k++) fsum[k] += fp[k];
  }
  PetscReal err = 0, fmax = 0;
  for (PetscInt k = 0; k < 2 * n; k++) {
    err  = PetscMax(err, std::fabs(f[k] - fsum[k]));
    fmax = PetscMax(fmax, std::fabs(f[k]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-34s max |f - sum of parts| / max |f| = %.1e\n", name, (double)(err / fmax)));
  TG_CHECK(err <= 1e-13 * fmax, "%s: the walls do not push independently (%.3e)", name, (double)(err / fmax));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A particle at (a, b) in a quadrant of an unperturbed +: the force of two straight walls,
   lambda (r^-6 - x0^-6) from each, exactly. */
static PetscErrorCode PlusAnalytic()
{
  Tissue T;
  PetscFunctionBeginUser;
  PetscCall(Corner({0, 90, 180, 270}, 0, 0, 1, &T));
  T.AddParticle(0, 0, 0.4, KIND_FLUID, 0);
  T.Finalize();
  const PetscInt probe = T.particles.n - 1;
  ForceModel     model;
  PetscCall(RepulsionModel(T, {PETSC_TRUE, PETSC_FALSE}, &model));
  std::vector<PetscReal> x     = T.X, v(x.size(), 0.0), f(x.size());
  PetscReal              worst = 0;
  for (PetscReal a : {-4.0, -2.2, -0.6, 0.6, 1.3, 3.1, 4.5})
    for (PetscReal b : {-4.7, -1.9, -0.4, 0.8, 2.6, 4.2}) {
      x[2 * probe]     = a;
      x[2 * probe + 1] = b;
      PetscCall(model.ComputeForces(x.data(), v.data(), f.data(), NULL));
      const PetscReal fx = std::copysign(kLambda * (std::pow(std::fabs(a), -6) - std::pow(kX0, -6)), a);
      const PetscReal fy = std::copysign(kLambda * (std::pow(std::fabs(b), -6) - std::pow(kX0, -6)), b);
      worst              = PetscMax(worst, std::hypot(f[2 * probe] - fx, f[2 * probe + 1] - fy) / std::hypot(fx, fy));
    }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "+ corner, particle in a quadrant: max |F - F(two straight walls)|/|F| = %.1e\n", (double)worst));
  TG_CHECK(worst <= 1e-12, "a particle near a + must feel exactly its two straight walls (%.3e)", (double)worst);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());

  PetscCall(PetscPrintf(PETSC_COMM_SELF, "Straight wall of 50 µm, 2 vs 4, 8, 16 springs (x0 = %g µm):\n", (double)kX0));
  PetscReal worst = 0;
  {
    const PetscReal A[2] = {0, 0}, B[2] = {50, 0};                                                      /* along x: the joints' bisectors are hit exactly */
    const PetscReal C[2] = {3.7, -1.2}, D[2] = {3.7 + 50 * std::cos(0.37), -1.2 + 50 * std::sin(0.37)}; /* oblique */
    for (Config c : {
           Config{PETSC_TRUE,  PETSC_FALSE},
           Config{PETSC_FALSE, PETSC_FALSE},
           Config{PETSC_TRUE,  PETSC_TRUE },
           Config{PETSC_FALSE, PETSC_TRUE }
    }) {
      PetscReal w;
      PetscCall(StraightWallSubdivision("along x", A, B, c, &w));
      worst = PetscMax(worst, w);
      PetscCall(StraightWallSubdivision("oblique", C, D, c, &w));
      worst = PetscMax(worst, w);
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "straight wall: largest relative force difference %.2e\n", (double)worst));
  PetscCall(StraightWallAlone());

  {
    Tissue L90, L120, Tj, Plus, PlusBent;
    PetscCall(Corner({0, 90}, 24, 0, 21, &L90));
    PetscCall(Corner({0, 120}, 24, 0.3, 22, &L120));
    PetscCall(Corner({0, 90, 180}, 24, 0.3, 23, &Tj));
    PetscCall(Corner({0, 90, 180, 270}, 24, 0, 24, &Plus));
    PetscCall(Corner({0, 90, 180, 270}, 24, 0.4, 25, &PlusBent));
    TG_CHECK(PairedEnds(L90.particles) == 0 && PairedEnds(L120.particles) == 0, "an L has no straight joint");
    TG_CHECK(PairedEnds(Tj.particles) == 2, "a T has one straight joint");
    TG_CHECK(PairedEnds(Plus.particles) == 4, "a + has two straight joints");
    TG_CHECK(Plus.particles.springs[0].joint[0] == 2 * 2 + 0 && Plus.particles.springs[1].joint[1] == 2 * 3 + 1, "+: 0 deg joins 180 deg, 90 joins 270");
    PetscCall(CornerChecks("L corner, 90 degrees", L90));
    PetscCall(CornerChecks("L corner, 120 degrees, bent", L120));
    PetscCall(CornerChecks("T junction, bent", Tj));
    PetscCall(CornerChecks("+ corner", Plus));
    PetscCall(CornerChecks("+ corner, bent", PlusBent));
    PetscCall(SumOfParts("L corner = its two springs", L90, {{0}, {1}}));
    PetscCall(SumOfParts("+ corner = its two walls", Plus,
                         {
                           {0, 2},
                           {1, 3}
    }));
    PetscCall(SumOfParts("+ corner, bent = its two walls", PlusBent,
                         {
                           {0, 2},
                           {1, 3}
    }));
    PetscCall(SumOfParts("T junction, bent = its two walls", Tj,
                         {
                           {0, 2},
                           {1}
    }));
    PetscCall(PlusAnalytic());
  }

  { /* the joints of the generated tissues */
    SquareGridSpec spec;
    Tissue         T, R;
    spec.cells_x = spec.cells_y = 2;
    PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, &T));
    /* 12 cell sides with a midpoint joint, the centre's 2 joints, 4 boundary T's with 1: 18 joints */
    TG_CHECK(PairedEnds(T.particles) == 36, "2 x 2 cells: %" PetscInt_FMT " paired spring ends, expected 36", PairedEnds(T.particles));
    spec.cells_x = spec.cells_y = 1;
    PetscCall(GeneratePeriodicSquareGridTissue(PETSC_COMM_SELF, spec, &R));
    TG_CHECK(PairedEnds(R.particles) == 8, "periodic cell: %" PetscInt_FMT " paired spring ends, expected all 8", PairedEnds(R.particles));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "joints: 2 x 2 cells %" PetscInt_FMT " paired spring ends of %zu, periodic cell %" PetscInt_FMT " of %zu\n",
                          PairedEnds(T.particles), 2 * T.particles.springs.size(), PairedEnds(R.particles), 2 * R.particles.springs.size()));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_repulsion_subdivision: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
