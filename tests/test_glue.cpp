static const char help[] = "Glue bonds between polygonal cells, driven kinematically (positions prescribed, no integrator):\n"
                           "1. two squares 2 r apart with 1, 3 and 7 bars per side: every node of the shared faces is bonded, the length\n"
                           "   shares sum to the face length (1e-12) and none is zero; so too where the two nodes of a bar 100 times shorter\n"
                           "   bond to the same end of the other cell's bar (coincident bond points);\n"
                           "2. forces = -dE/dx by central differences, zero total force and torque, on a sheared and opened pair;\n"
                           "3. energy law: a bond pulled open in steps of 1e-4 delta_c breaks within one step of delta_c = sqrt(2 G_c / k_n)\n"
                           "   and releases (1/2) k_n delta^2 L;\n"
                           "4. strength law: a bond slid along its bar breaks at k_t delta_t = tau_c, one pulled at 45 degrees on the\n"
                           "   quadratic interaction (within one step);\n"
                           "5. softening law: the work of pulling two squares apart is G_c x the face length (2%) for 2, 4 and 8 bonds per\n"
                           "   face, and the fracture dissipation counted by the term is the same;\n"
                           "6. created = intact + broken at every step, with the neighbour lists rebuilt at every step;\n"
                           "7. the accepted step's commits from the force evaluation's record (the bonds past their peak) are those of an\n"
                           "   evaluation at the accepted state: the same breaks, dissipation and work, bit for bit;\n"
                           "8. the vectorised loop of the undamaged bonds' forces (whichever clone the CPU runs) gives the bits of the same\n"
                           "   arithmetic written out bond by bond here, on 1 001 random bonds, opening and closing.\n";
#include "test_util.h"
#include "polygon_util.h"
#include <turgor/physics/bars.h>
#include <turgor/physics/contact.h>
#include <turgor/physics/glue.h>
#include <turgor/physics/glue_bond_forces.h>
#include <cstring>
#include <random>

using namespace turgor;
using turgor_test::MakeModel;
using turgor_test::PolygonBuilder;

/* A square cell [x0, x0 + W] x [0, W] with n bars per side, counter-clockwise from (x0, 0). */
static void AddSquare(PolygonBuilder &B, PetscReal x0, PetscReal W, PetscInt n)
{
  std::vector<std::array<PetscReal, 2>> pts;
  const PetscReal                       c[5][2] = {
                          {x0,     0},
                          {x0 + W, 0},
                          {x0 + W, W},
                          {x0,     W},
                          {x0,     0}
  };
  for (int side = 0; side < 4; side++)
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal s = (PetscReal)k / n;
      pts.push_back({c[side][0] + s * (c[side + 1][0] - c[side][0]), c[side][1] + s * (c[side + 1][1] - c[side][1])});
    }
  B.AddCell(pts, false, 1.0);
}

static std::unique_ptr<Glue> MakeGlue(Glue::Law law, PetscReal kn, PetscReal kt, PetscReal Gc, PetscReal sigma = -1, PetscReal tau = -1)
{
  auto g                  = std::make_unique<Glue>();
  g->law                  = law;
  g->normal_stiffness     = kn;
  g->tangential_stiffness = kt;
  g->fracture_energy      = Gc;
  g->strength             = sigma;
  g->shear_strength       = tau;
  g->distance             = 0.05;
  g->open_cells           = true;
  return g;
}

/* SetFromOptions' derived values (sigma_c, tau_c, the softening openings) for a term made in code. */
static PetscErrorCode Configure(Glue &g)
{
  PetscFunctionBeginUser;
  PetscCall(g.SetFromOptions(PETSC_COMM_SELF, TermContext{}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestShares()
{
  PetscFunctionBeginUser;
  const PetscReal W = 10, r = 0.25;
  for (PetscInt n : {1, 3, 7}) {
    PolygonBuilder B;
    AddSquare(B, 0, W, n);
    AddSquare(B, W + 2 * r, W, n);
    Tissue &T = B.Finish(r);
    Glue    g = *MakeGlue(Glue::ENERGY, 1e3, 1e3, 1);
    PetscCall(Configure(g));
    NeighbourSearch nb;
    PetscCall(g.SetUp(T.particles, nb));
    PetscCall(g.CreateBonds(T.particles, T.X.data()));
    PetscReal sum = 0, smallest = PETSC_MAX_REAL;
    for (PetscInt b = 0; b < g.Created(); b++) sum += g.LengthShare(b), smallest = std::min(smallest, g.LengthShare(b));
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "shares: %" PetscInt_FMT " bars per side: %" PetscInt_FMT " bonds (%" PetscInt_FMT
                          " per face), sum of shares %.15g (face %g), smallest %g\n",
                          n, g.Created(), g.Created() / 2, (double)sum, (double)W, (double)smallest));
    TG_CHECK(g.Created() == 2 * (n + 1), "expected %" PetscInt_FMT " bonds (every node of both faces), got %" PetscInt_FMT, 2 * (n + 1), g.Created());
    TG_CHECK_CLOSE(sum, W, 1e-12, 0, "the length shares of an interface sum to its length");
    TG_CHECK(smallest > 0, "a bond without a length share");
  }
  { /* a bar 100 times shorter: cell B's nodes (W + 2r, W + 0.1) and (W + 2r, W) both bond to A's
       corner (W, W), the end of A's bars: their bond points coincide and share their part of the face */
    PolygonBuilder B;
    AddSquare(B, 0, W, 1);
    const PetscReal x0 = W + 2 * r;
    B.AddCell(
      {
        {x0,     0      },
        {x0 + W, 0      },
        {x0 + W, W + 0.1},
        {x0,     W + 0.1},
        {x0,     W      }
    },
      false, 1.0);
    Tissue &T = B.Finish(r);
    Glue    g = *MakeGlue(Glue::ENERGY, 1e3, 1e3, 1);
    PetscCall(Configure(g));
    NeighbourSearch nb;
    PetscCall(g.SetUp(T.particles, nb));
    PetscCall(g.CreateBonds(T.particles, T.X.data()));
    PetscReal sum = 0, smallest = PETSC_MAX_REAL;
    for (PetscInt b = 0; b < g.Created(); b++) sum += g.LengthShare(b), smallest = std::min(smallest, g.LengthShare(b));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "a bar 100 times shorter: %" PetscInt_FMT " bonds, sum of shares %.15g (face %g), smallest %g\n", g.Created(),
                          (double)sum, (double)W, (double)smallest));
    TG_CHECK(g.Created() == 5, "expected 5 bonds (2 of A's nodes, 3 of B's), got %" PetscInt_FMT, g.Created());
    TG_CHECK_CLOSE(sum, W, 1e-12, 0, "the length shares of an interface with coincident bond points sum to its length");
    TG_CHECK(smallest > 0, "a bond without a length share");
  }
  { /* -glue_unbonded_box: a pre-crack over the lower half of the interface (7 bars per side: nodes at
       y = 10 k/7; those at k = 0..3, y <= 4.29, lie in the box) */
    PolygonBuilder B;
    AddSquare(B, 0, W, 7);
    AddSquare(B, W + 2 * r, W, 7);
    Tissue &T = B.Finish(r);
    Glue    g = *MakeGlue(Glue::ENERGY, 1e3, 1e3, 1);
    PetscCall(PetscOptionsSetValue(NULL, "-glue_unbonded_box", "-1,-1,25,5"));
    PetscCall(Configure(g));
    PetscCall(PetscOptionsClearValue(NULL, "-glue_unbonded_box"));
    NeighbourSearch nb;
    PetscCall(g.SetUp(T.particles, nb));
    PetscCall(g.CreateBonds(T.particles, T.X.data()));
    PetscReal sum = 0;
    for (PetscInt b = 0; b < g.Created(); b++) sum += g.LengthShare(b);
    std::vector<TermStatistic> stats;
    g.Statistics(stats);
    PetscReal unbonded = -1;
    for (auto &s : stats)
      if (s.name == "bonds_unbonded_box") unbonded = s.value;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "unbonded box over y <= 5: %" PetscInt_FMT " bonds (8 outside the box), %g left out, sum of shares %g\n",
                          g.Created(), (double)unbonded, (double)sum));
    TG_CHECK(g.Created() == 8 && unbonded == 8, "expected 8 bonds made and 8 left out by the box, got %" PetscInt_FMT " and %g", g.Created(), (double)unbonded);
    TG_CHECK(sum > 0 && sum < W, "the bonded part of the interface is shorter than the face: sum of shares %g", (double)sum);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Forces are -dE/dx (central differences) with no net force or torque: the right cell opened, slid
   and bent; with -glue_compression closed instead (the bonds then push). */
static PetscErrorCode TestGradient(bool compression)
{
  PetscFunctionBeginUser;
  const PetscReal W = 10, r = 0.25;
  PolygonBuilder  B;
  AddSquare(B, 0, W, 3);
  AddSquare(B, W + 2 * r, W, 3);
  Tissue                                 &T = B.Finish(r);
  ForceModel                              M;
  std::vector<std::unique_ptr<ForceTerm>> terms;
  auto                                    g = MakeGlue(Glue::ENERGY, 1e3, 400, 1e6); /* never breaks here */
  PetscCall(Configure(*g));
  g->compression = compression;
  terms.push_back(std::move(g));
  PetscCall(MakeModel(T.particles, std::move(terms), M, 0.2));
  std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f(x.size());
  PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL)); /* the bonds, at the reference */
  turgor_test::Random rnd(5);
  for (PetscInt i = 0; i < T.particles.n; i++) { /* open, slide and bend the right cell */
    if (x[2 * i] > W) x[2 * i] += (compression ? -1 : 1) * (0.02 + 0.01 * x[2 * i + 1] / W), x[2 * i + 1] += 0.015;
    x[2 * i] += 0.003 * rnd(), x[2 * i + 1] += 0.003 * rnd();
  }
  PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
  PetscReal       err = 0, fmax = 0, sx = 0, sy = 0, tq = 0;
  const PetscReal h = 1e-6;
  for (size_t q = 0; q < x.size(); q++) {
    std::vector<PetscReal> xp = x, xm = x;
    PetscReal              Ep, Em;
    PetscBool              c;
    xp[q] += h, xm[q] -= h;
    PetscCall(M.PotentialEnergy(xp.data(), &Ep, &c));
    PetscCall(M.PotentialEnergy(xm.data(), &Em, &c));
    err  = std::max(err, std::fabs(f[q] + (Ep - Em) / (2 * h)));
    fmax = std::max(fmax, std::fabs(f[q]));
  }
  for (PetscInt i = 0; i < T.particles.n; i++) sx += f[2 * i], sy += f[2 * i + 1], tq += x[2 * i] * f[2 * i + 1] - x[2 * i + 1] * f[2 * i];
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "gradient (%s): max |f + dE/dx| = %.3e (max |f| %.4g), sum f = (%.2e, %.2e), torque %.2e\n",
                        compression ? "closed, -glue_compression" : "opened", (double)err, (double)fmax, (double)sx, (double)sy, (double)tq));
  TG_CHECK(fmax > 1 && err < 1e-6 * fmax, "glue forces differ from -dE/dx");
  TG_CHECK(std::fabs(sx) < 1e-12 * fmax && std::fabs(sy) < 1e-12 * fmax && std::fabs(tq) < 1e-10 * fmax * W, "glue forces carry a net force or torque");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One bond: an open one-bar cell along y = 0 and a triangle whose lowest node sits 2 r above the
   bar's middle; the triangle is moved rigidly by (ux, uy) per step, AcceptStep after each step,
   until the bond breaks. Returns the opening (delta_n, delta_t) at the break and its record. */
static PetscErrorCode PullOne(std::unique_ptr<Glue> proto, PetscReal ux, PetscReal uy, PetscReal *dn, PetscReal *dt, Glue::Break *brk, bool here = false)
{
  PetscFunctionBeginUser;
  const PetscReal r = 0.25;
  PolygonBuilder  B;
  B.AddCell({{{0, 0}}, {{10, 0}}}, true, 1.0);
  B.AddCell({{{5, 2 * r}}, {{6, 2 * r + 1.5}}, {{4, 2 * r + 1.5}}}, false, 1.0);
  Tissue &T = B.Finish(r);
  PetscCall(Configure(*proto));
  std::vector<std::unique_ptr<ForceTerm>> terms;
  terms.push_back(std::move(proto));
  ForceModel M;
  PetscCall(MakeModel(T.particles, std::move(terms), M, 0.2));
  Glue                  *g = dynamic_cast<Glue *>(M.Term("glue"));
  std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f(x.size());
  PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
  TG_CHECK(g->Created() == 1, "expected one bond, got %" PetscInt_FMT, g->Created());
  for (PetscInt step = 1; step < 1000000 && g->Intact(); step++) {
    for (PetscInt i = 2; i < 5; i++) x[2 * i] += ux, x[2 * i + 1] += uy;
    g->Opening(0, x.data(), dn, dt);
    PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
    PetscCall(M.AcceptStep(x.data(), v.data(), (PetscReal)step, &here)); /* here: commit from the force evaluation's record */
  }
  std::vector<Glue::Break> b = g->TakeBreaks();
  TG_CHECK(b.size() == 1 && g->Broken() == 1, "the bond did not break (once)");
  *brk = b[0];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestBreaks()
{
  PetscFunctionBeginUser;
  const PetscReal kn = 2e3, kt = 1e3, Gc = 0.5, dc = std::sqrt(2 * Gc / kn), step = 1e-4 * dc;
  PetscReal       dn, dt;
  Glue::Break     b;
  PetscCall(PullOne(MakeGlue(Glue::ENERGY, kn, kt, Gc), 0, step, &dn, &dt, &b));
  {
    /* committed from the force evaluation's record of the bonds that break (the brittle laws record
       only those): the same break, bit for bit, as an evaluation at the accepted state */
    PetscReal   dn2, dt2;
    Glue::Break b2;
    PetscCall(PullOne(MakeGlue(Glue::ENERGY, kn, kt, Gc), 0, step, &dn2, &dt2, &b2, true));
    TG_CHECK(dn2 == dn && dt2 == dt && b2.energy == b.energy && b2.time == b.time, "energy law: the break from the record differs (t %g / %g)", (double)b2.time,
             (double)b.time);
    const PetscReal sigma = 30, tau = 20, u = 1e-4 * sigma / kn / std::sqrt(2.0);
    PetscReal       dn3, dt3, dn4, dt4;
    Glue::Break     b3, b4;
    PetscCall(PullOne(MakeGlue(Glue::STRENGTH, kn, kt, Gc, sigma, tau), u, u, &dn3, &dt3, &b3));
    PetscCall(PullOne(MakeGlue(Glue::STRENGTH, kn, kt, Gc, sigma, tau), u, u, &dn4, &dt4, &b4, true));
    TG_CHECK(dn3 == dn4 && dt3 == dt4 && b3.energy == b4.energy && b3.time == b4.time, "strength law: the break from the record differs (t %g / %g)",
             (double)b4.time, (double)b3.time);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "energy law: broke at delta_n = %.10g, delta_c = %.10g (%.2f steps beyond), mode %s, released %.6g = (1/2) k_n delta^2 L %.6g\n",
                        (double)dn, (double)dc, (double)((dn - dc) / step), b.mode, (double)b.energy, (double)(0.5 * kn * dn * dn * b.length)));
  TG_CHECK_CLOSE(b.energy, 0.5 * kn * dn * dn * b.length, 1e-12, 0, "energy released at the break");
  TG_CHECK(dn >= dc * (1 - 1e-12) && dn - dc <= step * (1 + 1e-9), "the energy law broke at %g, not within one step of %g", (double)dn, (double)dc);
  TG_CHECK(std::string(b.mode) == "tension", "pure opening is not reported as tension");
  {
    const PetscReal sigma = 30, tau = 20, st = 1e-4 * tau / kt;
    PetscCall(PullOne(MakeGlue(Glue::STRENGTH, kn, kt, Gc, sigma, tau), st, 0, &dn, &dt, &b));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "strength law, shear: broke at k_t delta_t = %.8g (tau_c %g), delta_n %.2e, mode %s\n", (double)(kt * dt),
                          (double)tau, (double)dn, b.mode));
    TG_CHECK(kt * std::fabs(dt) >= tau * (1 - 1e-9) && kt * std::fabs(dt) <= tau + kt * st * (1 + 1e-6), "the shear criterion did not break at tau_c");
    TG_CHECK(std::string(b.mode) == "shear", "a sliding break is not reported as shear");
    const PetscReal u = 1e-4 * sigma / kn / std::sqrt(2.0);
    PetscCall(PullOne(MakeGlue(Glue::STRENGTH, kn, kt, Gc, sigma, tau), u, u, &dn, &dt, &b));
    const PetscReal q = (kn * dn / sigma) * (kn * dn / sigma) + (kt * dt / tau) * (kt * dt / tau);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "strength law, 45 degrees: broke at (k_n dn/sigma)^2 + (k_t dt/tau)^2 = %.8g, mode %s\n", (double)q, b.mode));
    TG_CHECK(q >= 1 - 1e-9 && q <= 1 + 4e-4, "the quadratic interaction did not break at 1 (%g)", (double)q);
    TG_CHECK(std::string(b.mode) == "mixed", "a 45-degree break is not reported as mixed");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Softening: pull the right square away rigidly, sum the work of the force that holds it (trapezoid)
   until every bond has broken. Twice: the accepted step committing what the force evaluation at its
   state recorded, and (recompute) told that no evaluation was there, so that the glue evaluates the
   openings again: the same pull, bit for bit; and a third time with the force evaluation in blocks of
   3 bonds (the passes' block boundaries, and damaged bonds redone inside a block): the same bits. */
static PetscErrorCode TestWorkOfSeparation()
{
  PetscFunctionBeginUser;
  const PetscReal W = 10, r = 0.25, kn = 1e3, Gc = 0.2, sigma = 10; /* l0 = 0.01, lf = 0.04 */
  for (PetscInt n : {1, 3, 7}) {
    PetscReal work_of[3] = {0, 0, 0}, dissipation_of[3] = {0, 0, 0};
    PetscInt  steps_of[3] = {0, 0, 0};
    for (int variant = 0; variant < 3; variant++) {
      const bool     recompute = variant == 1; /* variant 2: the force evaluation in blocks of 3 bonds */
      PolygonBuilder B;
      AddSquare(B, 0, W, n);
      AddSquare(B, W + 2 * r, W, n);
      Tissue                                 &T = B.Finish(r);
      std::vector<std::unique_ptr<ForceTerm>> terms;
      auto                                    gl = MakeGlue(Glue::SOFTENING, kn, kn, Gc, sigma);
      auto                                    ct = std::make_unique<Contact>(); /* it asks for neighbour lists, rebuilt at every step with skin 0 */
      PetscCall(Configure(*gl));
      terms.push_back(std::move(gl));
      terms.push_back(std::move(ct));
      ForceModel M;
      PetscCall(MakeModel(T.particles, std::move(terms), M, 0.0)); /* skin 0: lists rebuilt at every step */
      Glue                  *g = dynamic_cast<Glue *>(M.Term("glue"));
      std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f(x.size());
      if (variant == 2) g->SetBlockBonds(3);
      PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
      const PetscInt created = g->Created();
      PetscReal      work = 0, Fprev = 0, L = 0;
      PetscInt       step = 0;
      for (PetscInt b = 0; b < created; b++) L += g->LengthShare(b);
      const PetscReal du = 1e-5;
      for (; step < 100000 && g->Intact(); step++) {
        for (PetscInt i = 0; i < T.particles.n; i++)
          if (T.X[2 * i] > W + r) x[2 * i] += du;
        PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
        PetscReal F = 0; /* the glue's pull on the right cell; the hand that holds it pulls back */
        for (PetscInt i = 0; i < T.particles.n; i++)
          if (T.X[2 * i] > W + r) F -= f[2 * i];
        work += 0.5 * (F + Fprev) * du;
        Fprev           = F;
        const bool here = !recompute;
        PetscCall(M.AcceptStep(x.data(), v.data(), (PetscReal)step, &here));
        TG_CHECK(g->Intact() + g->Broken() == created, "bonds lost: %" PetscInt_FMT " intact + %" PetscInt_FMT " broken != %" PetscInt_FMT " created",
                 g->Intact(), g->Broken(), created);
      }
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "softening, %" PetscInt_FMT " bonds per face%s: work of separation %.8g, G_c L = %.8g (relative difference %.2e), fracture "
                            "dissipation %.8g, %" PetscInt_FMT " neighbour rebuilds\n",
                            n + 1,
                            recompute      ? " (openings evaluated again at each accepted state)"
                            : variant == 2 ? " (in blocks of 3 bonds)"
                                           : "",
                            (double)work, (double)(Gc * L), (double)(work / (Gc * L) - 1), (double)g->Dissipation(), M.Neighbours().Rebuilds()));
      TG_CHECK(g->Intact() == 0, "not every bond broke");
      TG_CHECK(M.Neighbours().Rebuilds() > 1000, "the neighbour lists were not rebuilt at every step");
      TG_CHECK_CLOSE(L, W, 1e-12, 0, "interface length");
      TG_CHECK_CLOSE(work, Gc * L, 0.02, 0, "work of separation vs G_c L");
      TG_CHECK_CLOSE(g->Dissipation(), Gc * L, 1e-6, 0, "fracture dissipation vs G_c L");
      work_of[variant] = work, dissipation_of[variant] = g->Dissipation(), steps_of[variant] = step;
    }
    for (int variant = 1; variant < 3; variant++)
      TG_CHECK(work_of[0] == work_of[variant] && dissipation_of[0] == dissipation_of[variant] && steps_of[0] == steps_of[variant],
               "%s: work %.17g / %.17g, dissipation %.17g / %.17g, steps %" PetscInt_FMT " / %" PetscInt_FMT,
               variant == 1 ? "the commits from the force loop's record differ from an evaluation at the accepted state"
                            : "the force evaluation in blocks of 3 bonds differs from the one in a single block",
               (double)work_of[0], (double)work_of[variant], (double)dissipation_of[0], (double)dissipation_of[variant], steps_of[0], steps_of[variant]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* GlueUndamagedForces against the same formula, bond by bond, in this file's scalar code: the same
   bits (a fused multiply-add or a reordered sum in the vectorised loop would show here), and its marks
   of the bonds to commit against the laws' scalar tests, for every law, with broken bonds among them. */
static PetscErrorCode TestUndamagedForcesBits()
{
  PetscFunctionBeginUser;
  const size_t                     n = 1001, nodes = 300;
  std::mt19937                     gen(7);
  std::uniform_real_distribution<> U(-1.0, 1.0);
  std::vector<PetscReal>           x(2 * nodes);
  for (PetscReal &v : x) v = 20 * U(gen);
  GlueBondGeometry G;
  G.Resize(n);
  for (size_t k = 0; k < n; k++) {
    G.p[k] = (PetscInt)(gen() % nodes), G.a[k] = (PetscInt)(gen() % nodes), G.b[k] = (PetscInt)((G.a[k] + 1 + gen() % (nodes - 1)) % nodes);
    G.lam[k] = 0.5 + 0.5 * U(gen), G.sign[k] = U(gen) > 0 ? 1 : -1, G.gn0[k] = U(gen), G.gt0[k] = U(gen), G.L[k] = 1 + U(gen);
    G.intact[k] = U(gen) > -0.8 ? 1 : 0, G.lmax[k] = U(gen) > 0.6 ? 11 + U(gen) : 0; /* a tenth broken, a fifth past the peak once */
  }
  GlueLawParameters law{};
  law.kn = 1.3e4, law.kt = 0.7e4, law.beta2 = law.kt / law.kn, law.l0 = 10, law.l02 = law.l0 * law.l0, law.Gc = 6e5, law.sigma = 1.3e5, law.tau = 7e4;
  for (int which : {0, 1, 2})
    for (bool closing : {false, true}) {
      law.law = which, law.closing = closing;
      std::vector<PetscReal> force(4 * n), opening(3 * n);
      for (size_t lo : {(size_t)0, (size_t)400}) { /* in two ranges, as the glue's blocks call it */
        const size_t hi = lo ? n : 400;
        GlueUndamagedForces(G, lo, hi, x.data(), law, force.data() + 4 * lo, opening.data() + lo, opening.data() + n + lo, opening.data() + 2 * n + lo);
      }
      size_t differ = 0, marked = 0, mismarked = 0;
      for (size_t k = 0; k < n; k++) {
        const PetscReal ex = x[2 * G.b[k]] - x[2 * G.a[k]], ey = x[2 * G.b[k] + 1] - x[2 * G.a[k] + 1];
        const PetscReal il = 1 / std::sqrt(ex * ex + ey * ey), tx = ex * il, ty = ey * il, nx = -G.sign[k] * ty, ny = G.sign[k] * tx;
        const PetscReal l1 = 1 - G.lam[k];
        const PetscReal gx = x[2 * G.p[k]] - l1 * x[2 * G.a[k]] - G.lam[k] * x[2 * G.b[k]];
        const PetscReal gy = x[2 * G.p[k] + 1] - l1 * x[2 * G.a[k] + 1] - G.lam[k] * x[2 * G.b[k] + 1];
        const PetscReal gt = gx * tx + gy * ty, gn = gx * nx + gy * ny;
        const PetscReal dn = gn - G.gn0[k], dt = gt - G.gt0[k], dnp = std::max(dn, (PetscReal)0), dnf = closing ? dn : dnp;
        const PetscReal s = G.L[k], Fn = s * law.kn * dnf, Ft = s * law.kt * dt;
        const PetscReal Fx = Fn * nx + Ft * tx, Fy = Fn * ny + Ft * ty, q = (Ft * gn - Fn * gt) * il;
        const PetscReal want[6] = {Fx, Fy, l1 * Fx + q * nx, l1 * Fy + q * ny, dnp, dt};
        const PetscReal got[6]  = {force[4 * k], force[4 * k + 1], force[4 * k + 2], force[4 * k + 3], opening[k], opening[n + k]};
        differ += std::memcmp(want, got, sizeof want) != 0;
        /* the laws' tests written out: past the peak, or breaking */
        const PetscReal l2      = dnp * dnp + law.beta2 * dt * dt;
        const bool      changes = which == 2 ? !(G.lmax[k] <= law.l0 && l2 <= law.l02)
                                : which == 0 ? 0.5 * law.kn * l2 >= law.Gc
                                             : (law.kn * dnp / law.sigma) * (law.kn * dnp / law.sigma) + (law.kt * dt / law.tau) * (law.kt * dt / law.tau) >= 1;
        const bool      mark    = G.intact[k] != 0 && changes;
        marked += mark;
        mismarked += (opening[2 * n + k] == 1) != mark || (opening[2 * n + k] != 0 && opening[2 * n + k] != 1);
      }
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "vectorised undamaged forces (law %d, %s): %zu of %zu bonds differ from the scalar formula in some bit; %zu marked, %zu wrongly\n",
                            which, closing ? "closing too" : "opening only", differ, n, marked, mismarked));
      TG_CHECK(marked > 10 && marked < n - 100, "law %d: %zu of %zu bonds marked: the test's openings do not sample both sides of the law's threshold", which,
               marked, n);
      TG_CHECK(mismarked == 0, "law %d: %zu bonds marked otherwise than the law's test", which, mismarked);
      TG_CHECK(differ == 0, "the vectorised glue loop gave other bits than the scalar formula for %zu bonds", differ);
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(TestShares());
  PetscCall(TestGradient(false));
  PetscCall(TestGradient(true));
  PetscCall(TestBreaks());
  PetscCall(TestWorkOfSeparation());
  PetscCall(TestUndamagedForcesBits());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "all glue checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
