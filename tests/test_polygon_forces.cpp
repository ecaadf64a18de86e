static const char help[] = "Force terms of polygonal cells (bars, hinges, contact, pressure, viscosity):\n"
                           "hinge plasticity (return mapping, dissipation), forces = -dE/dx by finite differences with zero\n"
                           "total force and torque, a pressurised regular N-gon (gas law) against its closed form, node-bar\n"
                           "contact (lever rule, momenta, corners once, Coulomb stick/slip, history across rebuilds),\n"
                           "velocity Verlet energy error ~ dt^2, no contact lists without contact, and the near list of\n"
                           "contact against lists rebuilt at every step (a compressed tissue of 64 hexagons, 3000 steps), and the\n"
                           "hinges' vectorised forces and the bars' in node order bit for bit against the one-pass kernels', and the contact's\n"
                           "first pass against its scalar formula.\n";
#include "test_util.h"
#include "polygon_util.h"
#include <turgor/physics/bars.h>
#include <turgor/physics/cell_pressure.h>
#include <turgor/physics/contact.h>
#include <turgor/physics/hinges.h>
#include <cstring>
#include <turgor/physics/viscosity.h>

using namespace turgor;
using turgor_test::MakeModel;
using turgor_test::PolygonBuilder;
using Terms = std::vector<std::unique_ptr<ForceTerm>>;

template <class T, class... A>
static Terms List(std::unique_ptr<T> t, A... rest)
{
  Terms v;
  v.push_back(std::move(t));
  if constexpr (sizeof...(rest) > 0)
    for (auto &u : List(std::move(rest)...)) v.push_back(std::move(u));
  return v;
}

static PetscErrorCode Forces(ForceModel &M, const std::vector<PetscReal> &x, const std::vector<PetscReal> &v, std::vector<PetscReal> &f)
{
  PetscFunctionBeginUser;
  f.assign(x.size(), 0.0);
  PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Total force and torque about the origin, relative to the largest force. */
static PetscErrorCode CheckMomenta(const std::vector<PetscReal> &x, const std::vector<PetscReal> &f, PetscReal tol, const char *what)
{
  PetscReal fx = 0, fy = 0, tq = 0, fmax = 0, xmax = 0;
  PetscFunctionBeginUser;
  for (size_t i = 0; 2 * i < x.size(); i++) {
    fx += f[2 * i];
    fy += f[2 * i + 1];
    tq += x[2 * i] * f[2 * i + 1] - x[2 * i + 1] * f[2 * i];
    fmax = std::max(fmax, std::hypot(f[2 * i], f[2 * i + 1]));
    xmax = std::max(xmax, std::hypot(x[2 * i], x[2 * i + 1]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %s: sum f = (%.2e, %.2e), torque %.2e (max |f| %.3g)\n", what, fx, fy, tq, fmax));
  TG_CHECK(fmax > 0, "%s: no force at all", what);
  TG_CHECK(std::hypot(fx, fy) <= tol * fmax && std::fabs(tq) <= tol * fmax * xmax, "%s: momentum or angular momentum not conserved", what);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Forces against -dE/dx by central differences. */
static PetscErrorCode CheckGradient(ForceModel &M, std::vector<PetscReal> x, PetscReal h, PetscReal tol, const char *what)
{
  std::vector<PetscReal> v(x.size(), 0.0), f;
  PetscReal              err = 0, fmax = 0;
  PetscFunctionBeginUser;
  PetscCall(Forces(M, x, v, f));
  for (size_t k = 0; k < x.size(); k++) {
    PetscReal       Ep, Em;
    PetscBool       c;
    const PetscReal x0 = x[k];
    x[k]               = x0 + h;
    PetscCall(M.PotentialEnergy(x.data(), &Ep, &c));
    x[k] = x0 - h;
    PetscCall(M.PotentialEnergy(x.data(), &Em, &c));
    x[k] = x0;
    err  = std::max(err, std::fabs(f[k] + (Ep - Em) / (2 * h)));
    fmax = std::max(fmax, std::fabs(f[k]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %s: max |f + dE/dx| = %.3e (max |f| %.3g)\n", what, err, fmax));
  TG_CHECK(fmax > 0 && err <= tol * fmax, "%s: forces are not -dE/dx", what);
  PetscCall(CheckMomenta(x, f, 1e-12, what));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 1. A hinge turned past M_max: moment held at M_max, theta_p = excess rotation, work M_max dtheta_p,
   stage evaluations change nothing, elastic unloading. */
static PetscErrorCode TestHingePlasticity()
{
  PolygonBuilder  B;
  const PetscReal kr = 100, Mmax = 1, l = 2;
  PetscFunctionBeginUser;
  B.AddCell(
    {
      {-l, 0},
      {0,  0},
      {l,  0}
  },
    true, 1.0);
  Tissue    &T = B.Finish(0.1);
  auto       h = std::make_unique<Hinges>();
  ForceModel M;
  h->stiffness  = kr;
  h->max_moment = Mmax;
  PetscCall(MakeModel(T.particles, List(std::move(h)), M));
  Hinges *H = dynamic_cast<Hinges *>(M.Term("hinges"));
  TG_CHECK(H && H->NumHinges() == 1 && M.HasInternalState(), "one plastic hinge expected");
  std::vector<PetscReal> x     = T.X, v(x.size(), 0.0), f;
  auto                   place = [&](PetscReal phi) { x[4] = l * std::cos(phi), x[5] = l * std::sin(phi); };
  PetscCall(Forces(M, x, v, f)); /* reference */
  const PetscReal phi_max = 0.05, phi_y = Mmax / kr;
  for (int s = 1; s <= 50; s++) { /* quasi-static loading, one accepted step per increment */
    place(phi_max * s / 50);
    PetscCall(Forces(M, x, v, f));
    PetscCall(M.AcceptStep(x.data(), v.data()));
  }
  PetscCall(Forces(M, x, v, f));
  const PetscReal Mnow = std::hypot(f[4], f[5]) * l;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "hinge: M = %.12g (M_max %g), theta_p = %.12g (excess %.12g), dissipated %.12g\n", Mnow, Mmax, H->PlasticAngle(0),
                        phi_max - phi_y, H->PlasticDissipation()));
  TG_CHECK_CLOSE(Mnow, Mmax, 1e-12, 1, "moment held at M_max");
  TG_CHECK_CLOSE(H->PlasticAngle(0), phi_max - phi_y, 1e-10, 1e-3, "plastic angle = excess rotation");
  TG_CHECK_CLOSE(H->PlasticDissipation(), Mmax * (phi_max - phi_y), 1e-10, 1e-3, "dissipated work = M_max dtheta_p");
  /* a stage far beyond, not accepted: the state does not move */
  place(0.3);
  PetscCall(Forces(M, x, v, f));
  TG_CHECK_CLOSE(H->PlasticAngle(0), phi_max - phi_y, 1e-12, 1e-3, "stage evaluations leave theta_p");
  /* elastic unloading by 0.005 rad */
  place(phi_max - 0.005);
  PetscCall(Forces(M, x, v, f));
  PetscCall(M.AcceptStep(x.data(), v.data()));
  PetscCall(Forces(M, x, v, f));
  TG_CHECK_CLOSE(std::hypot(f[4], f[5]) * l, Mmax - kr * 0.005, 1e-9, 1, "elastic unloading");
  TG_CHECK_CLOSE(H->PlasticDissipation(), Mmax * (phi_max - phi_y), 1e-10, 1e-3, "no dissipation while unloading");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 2. Every conservative term against finite differences of its energy, with zero total force and
   torque, on a perturbed closed heptagon next to a second cell (contact across). */
static PetscErrorCode TestGradients()
{
  PetscFunctionBeginUser;
  for (int which = 0; which < 6; which++) {
    PolygonBuilder      B;
    turgor_test::Random rnd(7);
    B.AddRegular(7, 5, 0, 0, 1.0);
    B.AddRegular(5, 4, 9.2, 0.3, 1.0, 0.2); /* overlaps the first cell's right side slightly */
    Tissue &T = B.Finish(0.5);
    for (auto &q : T.X) q += 0.05 * rnd();
    Terms       terms;
    const char *what = "";
    if (which == 0) {
      auto t       = std::make_unique<Bars>();
      t->stiffness = 300;
      terms        = List(std::move(t));
      what         = "bars";
    } else if (which == 1) {
      auto t       = std::make_unique<Hinges>();
      t->stiffness = 70;
      terms        = List(std::move(t));
      what         = "hinges";
    } else if (which <= 4) {
      auto t          = std::make_unique<CellPressure>();
      t->law          = (CellPressure::Law)(which - 2);
      t->p0           = 0.7;
      t->bulk_modulus = 3;
      terms           = List(std::move(t));
      what            = which == 2 ? "pressure constant" : which == 3 ? "pressure gas" : "pressure elastic";
    } else {
      auto t       = std::make_unique<Contact>();
      t->stiffness = 1000;
      terms        = List(std::move(t));
      what         = "contact (frictionless)";
    }
    ForceModel M;
    PetscCall(MakeModel(T.particles, std::move(terms), M));
    std::vector<PetscReal> x0 = T.X, v(x0.size(), 0.0), f;
    PetscCall(Forces(M, x0, v, f)); /* reference state (A0, theta0) */
    std::vector<PetscReal> x = x0;
    for (auto &q : x) q += 0.2 * rnd();
    if (which == 5) {
      Contact *C = dynamic_cast<Contact *>(M.Term("contact"));
      PetscCall(Forces(M, x, v, f));
      TG_CHECK(C->ActiveContacts() > 0, "the gradient test of contact needs contacts (%" PetscInt_FMT ")", C->ActiveContacts());
    }
    PetscCall(CheckGradient(M, x, 1e-6, 1e-6, what));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 3. Regular N-gon, gas law, bars: at equilibrium the polygon stays regular with side l solving
   k (l - l0) = T = p l / (2 tan(pi/N)) (virtual work: N dE_bar/dl = p dA/dl, A = N l^2 / (4 tan(pi/N))),
   p = p0 A0 / A; T = p a with a = R cos(pi/N) the apothem (-> Laplace T = p R as N grows). */
static PetscErrorCode TestPressurisedNgon()
{
  const PetscInt  N  = 12;
  const PetscReal R0 = 10, k = 100, p0 = 1, m = 1, nu = 2, dt = 0.01;
  PolygonBuilder  B;
  PetscFunctionBeginUser;
  B.AddRegular(N, R0, 0, 0, m);
  Tissue &T       = B.Finish(0.1);
  auto    b       = std::make_unique<Bars>();
  auto    p       = std::make_unique<CellPressure>();
  auto    vi      = std::make_unique<Viscosity>();
  b->stiffness    = k;
  p->law          = CellPressure::GAS;
  p->p0           = p0;
  vi->coefficient = nu;
  ForceModel M;
  PetscCall(MakeModel(T.particles, List(std::move(b), std::move(p), std::move(vi)), M));
  const PetscReal tn = std::tan(PETSC_PI / N), l0 = 2 * R0 * std::sin(PETSC_PI / N), A0 = N * l0 * l0 / (4 * tn);
  PetscReal       l = l0; /* Newton on g(l) = k (l - l0) - p0 A0 2 / (N l) */
  for (int it = 0; it < 50; it++) l -= (k * (l - l0) - 2 * p0 * A0 / (N * l)) / (k + 2 * p0 * A0 / (N * l * l));
  const PetscReal A = N * l * l / (4 * tn), pe = p0 * A0 / A, Texp = pe * l / (2 * tn);
  /* damped velocity Verlet to rest */
  std::vector<PetscReal> x = T.X, v(x.size(), 0.0), a(x.size());
  PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
  for (int s = 0; s < 40000; s++) {
    for (size_t q = 0; q < x.size(); q++) {
      v[q] += 0.5 * dt * a[q];
      x[q] += dt * v[q];
    }
    PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data())); /* viscosity with the half-step velocity */
    for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q];
  }
  const PetscReal Asim = PolygonArea(T.particles.polygons[0].nodes, x.data());
  PetscReal       lmin = PETSC_MAX_REAL, lmax = 0;
  for (PetscInt q = 0; q < N; q++) {
    const PetscInt  i = q, j = (q + 1) % N;
    const PetscReal lq = std::hypot(x[2 * j] - x[2 * i], x[2 * j + 1] - x[2 * i + 1]);
    lmin = std::min(lmin, lq), lmax = std::max(lmax, lq);
  }
  const PetscReal Tsim = k * (0.5 * (lmin + lmax) - l0), psim = p0 * A0 / Asim;
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "N-gon (gas): A = %.12g (closed form %.12g), bar tension %.12g (p l/(2 tan(pi/N)) = %.12g; p R = %.6g), sides %.3e apart\n", Asim, A,
                        Tsim, Texp, psim * l / (2 * std::sin(PETSC_PI / N)), lmax - lmin));
  TG_CHECK_CLOSE(Asim, A, 1e-9, 1, "equilibrium area");
  TG_CHECK_CLOSE(Tsim, Texp, 1e-7, 1, "bar tension");
  TG_CHECK_CLOSE(Tsim, psim * l / (2 * tn), 1e-7, 1, "discrete Laplace law with the simulated pressure");
  TG_CHECK(lmax - lmin < 1e-9 * l, "the polygon stays regular");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The forces of contact alone (normal stiffness kn) on the builder's cells (bar radius r) at rest:
   the model M, the positions x and the forces f. */
static PetscErrorCode ContactAtRest(PolygonBuilder &B, PetscReal r, PetscReal kn, ForceModel &M, std::vector<PetscReal> &x, std::vector<PetscReal> &f)
{
  PetscFunctionBeginUser;
  Tissue &T    = B.Finish(r);
  auto    c    = std::make_unique<Contact>();
  c->stiffness = kn;
  PetscCall(MakeModel(T.particles, List(std::move(c)), M));
  x = T.X;
  PetscCall(Forces(M, x, std::vector<PetscReal>(x.size(), 0.0), f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4a. A node pressed on a bar: k_n delta split by the lever rule; momenta; a corner counted once. */
static PetscErrorCode TestContactNormal()
{
  const PetscReal kn = 1000, r = 0.5, delta = 0.01;
  PetscFunctionBeginUser;
  {
    PolygonBuilder B;
    B.AddCell(
      {
        {0,  0},
        {10, 0}
    },
      true, 1.0);
    B.AddCell(
      {
        {3, 2 * r - delta}
    },
      true, 1.0);
    ForceModel             M;
    std::vector<PetscReal> x, f;
    PetscCall(ContactAtRest(B, r, kn, M, x, f));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "contact: node %.12g, bar ends %.12g %.12g (k_n delta = %g, lever 0.7/0.3)\n", f[5], f[1], f[3], kn * delta));
    TG_CHECK_CLOSE(f[5], kn * delta, 1e-9, 1, "normal force k_n delta");
    TG_CHECK_CLOSE(f[1], -0.7 * kn * delta, 1e-9, 1, "lever rule, near end");
    TG_CHECK_CLOSE(f[3], -0.3 * kn * delta, 1e-9, 1, "lever rule, far end");
    PetscCall(CheckMomenta(x, f, 1e-12, "node on bar"));
  }
  /* a node off the corner of a closed square: both bars at the corner are closest there */
  for (int pass = 0; pass < 2; pass++) {
    PolygonBuilder B;
    B.AddCell(
      {
        {0,  0 },
        {10, 0 },
        {10, 10},
        {0,  10}
    },
      false, 1.0);
    const PetscReal px = pass == 0 ? -0.4 : -0.3, py = pass == 0 ? -0.4 : 4.0;
    B.AddCell(
      {
        {px, py}
    },
      true, 1.0);
    ForceModel             M;
    std::vector<PetscReal> x, f;
    PetscCall(ContactAtRest(B, r, kn, M, x, f));
    Contact        *C   = dynamic_cast<Contact *>(M.Term("contact"));
    const PetscReal dst = pass == 0 ? std::hypot(px, py) : -px;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "contact %s: %" PetscInt_FMT " contact(s), |f| = %.12g (k_n delta = %.12g)\n",
                          pass == 0 ? "at a corner" : "beside a side", C->ActiveContacts(), std::hypot(f[8], f[9]), kn * (2 * r - dst)));
    TG_CHECK(C->ActiveContacts() == 1, "the node touches the cell once, not from both bars at the corner");
    TG_CHECK_CLOSE(std::hypot(f[8], f[9]), kn * (2 * r - dst), 1e-9, 1, "a corner pushes once");
    PetscCall(CheckMomenta(x, f, 1e-12, "corner"));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4a'. A node slid past the inner side of a bent joint (a wall bent by 11 degrees towards it, where
   it lies in front of both bars): it touches the wall through the nearer bar only, so the contact
   energy is continuous (the seed counts it from both bars there, and the count jumps by a whole
   contact's energy where the node leaves one bar's span) and the force is the energy's gradient on
   either side of the bisector. */
static PetscErrorCode TestContactJoint()
{
  const PetscReal kn = 1000, r = 0.5, y = 0.8, h = 1e-6;
  PetscFunctionBeginUser;
  PolygonBuilder B;
  B.AddCell(
    {
      {0,  0},
      {10, 0},
      {20, 2}
  },
    true, 1.0);
  B.AddCell(
    {
      {9, y}
  },
    true, 1.0);
  ForceModel             M;
  std::vector<PetscReal> x, f, E;
  std::vector<bool>      has;
  PetscCall(ContactAtRest(B, r, kn, M, x, f));
  PetscReal worst = 0, fmax = 0, Eprev = -1, worst_grad = 0;
  for (PetscInt k = 0; k <= 2000; k++) { /* x from 9 to 11 in steps of 1e-3, each with a step of h */
    for (PetscReal dx : {0.0, h}) {
      x[6] = 9 + 1e-3 * (PetscReal)k + dx;
      PetscCall(M.TermEnergies(x.data(), E, has));
      if (dx == 0) {
        PetscCall(Forces(M, x, std::vector<PetscReal>(x.size(), 0.0), f));
        fmax  = std::max(fmax, std::hypot(f[6], f[7]));
        Eprev = E[0];
      } else {
        const PetscReal jump = std::fabs(E[0] - Eprev);
        worst                = std::max(worst, jump);
        worst_grad           = std::max(worst_grad, std::fabs((E[0] - Eprev) / h + f[6]));
      }
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "contact across a bent joint: largest energy change over %g µm %.3g (force up to %.4g, so a jump shows as >> %.3g); "
                        "|dE/dx + f_x| <= %.3g\n",
                        (double)h, (double)worst, (double)fmax, (double)(fmax * h), (double)worst_grad));
  TG_CHECK(worst < 2 * fmax * h, "the contact energy jumps by %g over %g µm at the joint", (double)worst, (double)h);
  TG_CHECK(worst_grad < 1e-2 * fmax, "the contact force is not the energy's gradient at the joint: |dE/dx + f_x| = %g", (double)worst_grad);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4b. Coulomb friction: nodes on a fixed bar, normal load N each, tangential load F each:
   stick for F < mu N (spring oscillation bounded by 2 F / k_t), slide with (F - mu N)/m above;
   the history is the same after a forced neighbour rebuild. */
static PetscErrorCode RunBlock(PetscReal F, PetscReal *accel, PetscReal *maxdisp, bool rebuild_check)
{
  const PetscReal kn = 1000, kt = 1000, mu = 0.5, Nl = 1, r = 0.5, m = 1, dt = 0.002;
  PolygonBuilder  B;
  PetscFunctionBeginUser;
  B.AddCell(
    {
      {-50, 0},
      {50,  0}
  },
    true, 1.0);
  for (int q = 0; q < 3; q++)
    B.AddCell(
      {
        {2.0 + 3 * q, 2 * r - Nl / kn}
    },
      true, m); /* at normal equilibrium */
  Tissue &T            = B.Finish(r);
  T.particles.fixed[0] = T.particles.fixed[1] = 1;
  auto c                                      = std::make_unique<Contact>();
  c->stiffness                                = kn;
  c->friction                                 = mu;
  c->tangential_stiffness                     = kt;
  ForceModel M;
  PetscCall(MakeModel(T.particles, List(std::move(c)), M, 0.2));
  TG_CHECK(M.HasInternalState(), "friction has history");
  Contact               *C          = dynamic_cast<Contact *>(M.Term("contact"));
  std::vector<PetscReal> x          = T.X, v(x.size(), 0.0), a(x.size());
  auto                   accelerate = [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
    for (PetscInt i = 2; i < T.particles.n; i++) a[2 * i] += F / m, a[2 * i + 1] -= Nl / m;
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCall(accelerate());
  PetscCall(M.AcceptStep(x.data(), v.data()));
  const PetscInt steps = 2000;
  PetscReal      v1 = 0, t1 = 0;
  *maxdisp = 0;
  for (PetscInt s = 1; s <= steps; s++) {
    for (size_t q = 0; q < x.size(); q++) {
      v[q] += 0.5 * dt * a[q];
      x[q] += dt * v[q];
    }
    PetscCall(accelerate());
    for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q];
    PetscCall(M.AcceptStep(x.data(), v.data()));
    *maxdisp = std::max(*maxdisp, std::fabs(x[4] - T.X[4]));
    if (s == steps / 2) v1 = v[4], t1 = s * dt;
    if (rebuild_check && s == steps / 2) { /* forced rebuild: same forces, same history */
      std::vector<PetscReal> f1, f2;
      const size_t           n1 = C->HistoryEntries();
      PetscCall(Forces(M, x, v, f1));
      const PetscInt builds = C->CandidateListBuilds();
      M.Neighbours().Reset();
      PetscCall(Forces(M, x, v, f2));
      TG_CHECK(C->CandidateListBuilds() == builds + 1, "Reset() must rebuild the candidate list");
      PetscReal dmax = 0, fmax = 0;
      for (size_t q = 0; q < f1.size(); q++) dmax = std::max(dmax, std::fabs(f1[q] - f2[q])), fmax = std::max(fmax, std::fabs(f1[q]));
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  forced rebuild: %zu -> %zu history entries, forces differ by %.3g (tangential %.6g)\n", n1, C->HistoryEntries(),
                            dmax, f1[4]));
      TG_CHECK(n1 == 3 && C->HistoryEntries() == n1 && dmax == 0 && std::fabs(f1[4]) > 0, "history must survive a neighbour rebuild");
      PetscCall(CheckMomenta(x, f1, 1e-12, "contact with friction")); /* the couple balances the tangential torque */
    }
  }
  *accel = (v[4] - v1) / (steps * dt - t1);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestFriction()
{
  const PetscReal mu = 0.5, Nl = 1, kt = 1000;
  PetscReal       a, d;
  PetscFunctionBeginUser;
  PetscCall(RunBlock(0.2, &a, &d, true));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "friction F = 0.2 < mu N = 0.5: acceleration %.3g, max displacement %.4g (2F/k_t = %.4g)\n", a, d, 0.4 / kt));
  TG_CHECK(d <= 2 * 0.2 / kt * (1 + 1e-6), "sticks: the node stays on its tangential spring");
  PetscCall(RunBlock(0.8, &a, &d, false));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "friction F = 0.8 > mu N: acceleration %.12g ((F - mu N)/m = %.12g)\n", a, 0.8 - mu * Nl));
  TG_CHECK_CLOSE(a, 0.8 - mu * Nl, 1e-9, 1, "slides with (F - mu N)/m");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 5. Bars + elastic hinges under velocity Verlet: the energy error is O(dt^2). */
static PetscErrorCode EnergyError(PetscReal dt, PetscInt steps, PetscReal *err)
{
  PolygonBuilder      B;
  turgor_test::Random rnd(3);
  PetscFunctionBeginUser;
  B.AddRegular(6, 3, 0, 0, 1.0);
  Tissue &T    = B.Finish(0.1);
  auto    b    = std::make_unique<Bars>();
  auto    h    = std::make_unique<Hinges>();
  b->stiffness = 100;
  h->stiffness = 50;
  ForceModel M;
  PetscCall(MakeModel(T.particles, List(std::move(b), std::move(h)), M));
  std::vector<PetscReal> x = T.X, v(x.size()), a(x.size()), f;
  PetscCall(Forces(M, x, v, f)); /* reference */
  for (auto &q : x) q += 0.1 * rnd();
  for (auto &q : v) q = 0.5 * rnd();
  auto energy = [&](PetscReal *E) -> PetscErrorCode {
    PetscBool c;
    PetscFunctionBeginUser;
    PetscCall(M.PotentialEnergy(x.data(), E, &c));
    for (auto q : v) *E += 0.5 * q * q;
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscReal E0, E;
  PetscCall(energy(&E0));
  PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
  *err = 0;
  for (PetscInt s = 0; s < steps; s++) {
    for (size_t q = 0; q < x.size(); q++) {
      v[q] += 0.5 * dt * a[q];
      x[q] += dt * v[q];
    }
    PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
    for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q];
    if (s % 10 == 0) {
      PetscCall(energy(&E));
      *err = std::max(*err, std::fabs(E - E0));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TestEnergy()
{
  PetscReal e1, e2;
  PetscFunctionBeginUser;
  PetscCall(EnergyError(0.02, 100000, &e1));
  PetscCall(EnergyError(0.01, 100000, &e2));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "energy (bars + hinges, velocity Verlet, 1e5 steps): max error %.4g (dt 0.02), %.4g (dt 0.01), ratio %.3f\n", e1, e2,
                        e1 / e2));
  TG_CHECK(e1 / e2 > 3.5 && e1 / e2 < 4.5, "energy error must shrink as dt^2");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 6. Physics off costs nothing: a bars-only model asks for no node-bar lists and builds none. */
static PetscErrorCode TestNoContactNoLists()
{
  PolygonBuilder B;
  PetscFunctionBeginUser;
  B.AddRegular(6, 3, 0, 0, 1.0);
  B.AddRegular(6, 3, 6.1, 0, 1.0);
  Tissue    &T = B.Finish(0.5);
  ForceModel M, Mc;
  PetscCall(MakeModel(T.particles, List(std::make_unique<Bars>()), M));
  PetscCall(MakeModel(T.particles, List(std::make_unique<Bars>(), std::make_unique<Contact>()), Mc));
  std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f;
  for (int s = 0; s < 3; s++) {
    PetscCall(Forces(M, x, v, f));
    PetscCall(Forces(Mc, x, v, f));
  }
  const Contact *C = dynamic_cast<const Contact *>(Mc.Term("contact"));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "bars only: particle-spring lists %s, rebuilds %" PetscInt_FMT "; with contact: %" PetscInt_FMT " rebuild(s), %" PetscInt_FMT
                        " candidate list build(s), %zu candidates\n",
                        M.Neighbours().WantsParticleSpringPairs() ? "requested" : "not requested", M.Neighbours().Rebuilds(), Mc.Neighbours().Rebuilds(),
                        C->CandidateListBuilds(), C->Candidates()));
  TG_CHECK(!M.Neighbours().WantsParticleSpringPairs() && M.Neighbours().Rebuilds() == 0, "a bars-only model must build no contact lists");
  TG_CHECK(Mc.Neighbours().Rebuilds() == 1 && C->CandidateListBuilds() == 1 && C->Candidates() > 0, "the contact model builds its list once");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The near list never misses a pair: a tissue of 8 x 8 hexagons compressed (strain rate 5e-3 /µs,
   cells closing their gaps and sliding with friction) is integrated by velocity Verlet with one
   model (skin 0.2 µm: neighbour lists and near lists kept over many steps) while a second model
   (skin 0: both lists rebuilt from scratch at every step) is evaluated and accepted at the same
   states; their forces must agree to round-off at every step, with contacts made and broken. */
static PetscErrorCode TestNearList()
{
  PetscFunctionBeginUser;
  PolygonBuilder      B;
  turgor_test::Random rnd(7);
  Tissue             &T = turgor_test::HexagonTissue(B, 8, 8, 10, 0.25, 1, rnd);
  ForceModel          A, Z;
  auto                contact = []() {
    auto c                  = std::make_unique<Contact>();
    c->stiffness            = 1e4;
    c->friction             = 0.3;
    c->tangential_stiffness = 5e3;
    return c;
  };
  auto bars = []() {
    auto b       = std::make_unique<Bars>();
    b->stiffness = 1e4;
    return b;
  };
  PetscCall(MakeModel(T.particles, List(bars(), contact()), A, 0.2));
  PetscCall(MakeModel(T.particles, List(bars(), contact()), Z, 0.0));
  std::vector<PetscReal> x  = T.X, v(x.size()), a(x.size()), fz(x.size());
  const PetscReal        xc = 0.5 * (T.lo[0] + T.hi[0]), yc = 0.5 * (T.lo[1] + T.hi[1]), rate = 5e-3, dt = 2e-3;
  for (PetscInt i = 0; i < T.particles.n; i++) v[2 * i] = -rate * (x[2 * i] - xc), v[2 * i + 1] = -rate * (x[2 * i + 1] - yc);
  const Contact *CA = dynamic_cast<const Contact *>(A.Term("contact")), *CZ = dynamic_cast<const Contact *>(Z.Term("contact"));
  PetscReal      worst = 0;
  PetscInt       most = 0, made = 0, prev = 0;
  PetscCall(A.ComputeAcceleration(x.data(), v.data(), a.data()));
  for (PetscInt s = 0; s < 3000; s++) {
    for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q], x[q] += dt * v[q];
    PetscCall(A.ComputeForces(x.data(), v.data(), a.data(), NULL));
    PetscCall(Z.ComputeForces(x.data(), v.data(), fz.data(), NULL));
    PetscReal d = 0, fmax = 0;
    for (size_t q = 0; q < x.size(); q++) d = std::max(d, std::fabs(a[q] - fz[q])), fmax = std::max(fmax, std::fabs(fz[q]));
    worst = std::max(worst, d / fmax);
    TG_CHECK(CA->ActiveContacts() == CZ->ActiveContacts(), "step %" PetscInt_FMT ": %" PetscInt_FMT " contacts with the near list, %" PetscInt_FMT " without",
             s, CA->ActiveContacts(), CZ->ActiveContacts());
    most = std::max(most, CZ->ActiveContacts());
    made += std::max<PetscInt>(0, CZ->ActiveContacts() - prev);
    prev = CZ->ActiveContacts();
    for (PetscInt i = 0; i < T.particles.n; i++) a[2 * i] /= T.particles.mass[i], a[2 * i + 1] /= T.particles.mass[i];
    for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q];
    PetscCall(A.AcceptStep(x.data(), v.data()));
    PetscCall(Z.AcceptStep(x.data(), v.data()));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "near list: %" PetscInt_FMT " neighbour rebuilds and %" PetscInt_FMT " near-list builds (skin 0: %" PetscInt_FMT
                        " rebuilds) in 3000 steps, up to %" PetscInt_FMT " contacts, %" PetscInt_FMT " made; forces differ by %.2e of the largest\n",
                        A.Neighbours().Rebuilds(), CA->NearListBuilds(), Z.Neighbours().Rebuilds(), most, made, (double)worst));
  TG_CHECK(most > 50 && made > 50 && CA->NearListBuilds() > 10 && A.Neighbours().Rebuilds() > 2 && A.Neighbours().Rebuilds() < 1000,
           "the test must make contacts and rebuild both lists");
  TG_CHECK(worst < 1e-12, "forces with and without the near list differ by %g", (double)worst);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Tissues for the bit checks of the vectorised loops: twelve closed cells (triangles to nonagons) and
   a nine-node open chain, in the order asked (node numbers follow the order of adding). */
static void AddCellsAndChain(PolygonBuilder &B, bool cells, bool chain, bool chain_first)
{
  auto add_chain = [&] {
    B.AddCell(
      {
        {0, 5  },
        {1, 5.2},
        {2, 4.9},
        {3, 5.1},
        {4, 5  },
        {5, 5.3},
        {6, 5.1},
        {7, 5.2},
        {8, 5  }
    },
      true, 1.0);
  };
  if (chain && chain_first) add_chain();
  for (PetscInt c = 0; cells && c < 12; c++) B.AddRegular(3 + c % 7, 1.0 + 0.1 * c, 3.0 * c, 0, 1.0);
  if (chain && !chain_first) add_chain();
}

/* 9. The hinges' vectorised loops (forces without the virial) give the bits of the one-pass kernel
   (forces with it), bent so that some hinges leave the series (|tan(theta - theta0)| > 0.1, one past
   a right angle), elastic and plastic: closed cells and an open chain (the hinges' nodes not
   consecutive: bars gathered), closed cells alone and the chain alone (bars read in order). */
static PetscErrorCode HingeVectorBits(bool cells, bool chain)
{
  PolygonBuilder      B;
  turgor_test::Random rnd(11);
  PetscFunctionBeginUser;
  AddCellsAndChain(B, cells, chain, false);
  Tissue &T = B.Finish(0.1);
  for (PetscReal Mmax : {0.0, 0.3})
    for (size_t block : {(size_t)512, (size_t)10}) { /* one block, and blocks of a few polygons */
      auto h        = std::make_unique<Hinges>();
      h->stiffness  = 2.5;
      h->max_moment = Mmax;
      h->SetBlockHinges(block);
      ForceModel M;
      PetscCall(MakeModel(T.particles, List(std::move(h)), M));
      std::vector<PetscReal> x = T.X, v(x.size(), 0.0), f, fv(x.size(), 0.0);
      PetscCall(Forces(M, x, v, f)); /* the reference angles */
      for (auto &q : x) q += (cells ? 0.1 : 0.03) * rnd();
      if (chain) { /* the chain's third node pushed up past its neighbours: a bend of about 100 degrees */
        const size_t fold = x.size() / 2 - 7;
        x[2 * fold] = 2.0, x[2 * fold + 1] = 6.5;
      }
      PetscCall(Forces(M, x, v, f));
      PetscReal virial[4] = {0, 0, 0, 0};
      PetscCall(M.ComputeForces(x.data(), v.data(), fv.data(), virial));
      const Hinges *H       = dynamic_cast<const Hinges *>(M.Term("hinges"));
      size_t        outside = 0, obtuse = 0;
      for (size_t k = 0; k < H->NumHinges(); k++) {
        const PetscReal d = std::fabs(H->Angle(k, x.data()));
        outside += d > std::atan(0.1);
        obtuse += d > 0.5 * PETSC_PI;
      }
      const bool same = std::memcmp(f.data(), fv.data(), f.size() * sizeof(PetscReal)) == 0;
      PetscCall(
        PetscPrintf(PETSC_COMM_SELF,
                    "hinges (%s, M_max %g, blocks of %zu): %zu hinges, %zu outside the series (%zu past a right angle), bars %s: vectorised forces %s\n",
                    cells && chain ? "cells and a chain"
                    : cells        ? "cells"
                                   : "a chain",
                    (double)Mmax, block, H->NumHinges(), outside, obtuse, H->BarsInOrder() ? "in order" : "gathered", same ? "the same bits" : "DIFFER"));
      TG_CHECK(outside > 1 && (obtuse > 0 || !chain) && outside + 2 < H->NumHinges(), "the test must take both paths");
      TG_CHECK(H->BarsInOrder() == !(cells && chain), "the hinges' nodes are consecutive unless a chain follows the cells");
      TG_CHECK(same, "the hinges' vectorised forces differ from the one-pass kernel's");
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 10. The bars' loops in node order (forces without the virial) give the bits of the one-pass spring
   kernel (forces with it), their dashpot part (the energy balance's) too: a chain before closed cells
   (the chain's bars in node order, the cells' after them one by one: the cells' first node is not the
   chain's last bar's next), cells and a chain after them, cells alone, a chain alone (all in node
   order: rings' closing bars, a chain's ends). The cells' pressure likewise: each cell's nodes
   numbered consecutively, its forces node by node (without the virial) against edge by edge. */
static PetscErrorCode SpringOrderBits(int layout)
{
  PolygonBuilder      B;
  turgor_test::Random rnd(5);
  const bool          cells = layout != 3, chain = layout != 2;
  const char         *name[4] = {"a chain, then cells", "cells, then a chain", "cells", "a chain"};
  PetscFunctionBeginUser;
  AddCellsAndChain(B, cells, chain, layout == 0);
  Tissue &T = B.Finish(0.1);
  for (PetscReal damping : {0.0, 0.7}) {
    auto b       = std::make_unique<Bars>();
    auto h       = std::make_unique<Hinges>();
    auto p       = std::make_unique<CellPressure>();
    b->stiffness = 30;
    b->damping   = damping;
    h->stiffness = 2.5;
    p->law       = CellPressure::GAS;
    p->p0        = 0.7;
    p->SetReference(T.X.data());
    ForceModel M;
    PetscCall(
      MakeModel(T.particles, List(std::move(h), std::move(b), std::move(p)), M)); /* hinges first: the bars and the pressure add to forces already there */
    M.KeepTermForces(true);
    std::vector<PetscReal> x = T.X, v(x.size()), f(x.size(), 0.0), fv(x.size(), 0.0);
    for (auto &q : x) q += 0.1 * rnd();
    for (auto &q : v) q = rnd();
    std::vector<std::vector<PetscReal>> F, Fd, Fv, Fdv;
    PetscCall(M.ComputeForces(x.data(), v.data(), f.data(), NULL));
    M.TakeTermForces(F, Fd);
    PetscReal virial[4] = {0, 0, 0, 0};
    PetscCall(M.ComputeForces(x.data(), v.data(), fv.data(), virial));
    M.TakeTermForces(Fv, Fdv);
    const Bars *Bt      = dynamic_cast<const Bars *>(M.Term("bars"));
    const bool  same    = std::memcmp(f.data(), fv.data(), f.size() * sizeof(PetscReal)) == 0;
    const bool  dashpot = damping > 0 && Fd.size() == 3 && Fdv.size() == 3 && Fd[1].size() == f.size() && Fdv[1].size() == f.size();
    const bool  same_d  = dashpot && std::memcmp(Fd[1].data(), Fdv[1].data(), f.size() * sizeof(PetscReal)) == 0;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "bars and pressure (%s, damping %g): %zu of %zu bars in node order: forces %s%s\n", name[layout], (double)damping,
                          Bt->BarsInNodeOrder(), T.particles.springs.size(), same ? "the same bits" : "DIFFER",
                          damping > 0 ? (same_d ? ", dashpot part the same bits" : ", dashpot part DIFFERS or missing") : ""));
    const size_t ordered = Bt->BarsInNodeOrder(), bars = T.particles.springs.size();
    TG_CHECK(layout == 0 ? ordered == 8 && ordered < bars : ordered == bars,
             "%zu of %zu bars in node order: all of them, or the chain's 8 when the chain comes first", ordered, bars);
    TG_CHECK(damping == 0 || dashpot, "the dashpot part must be kept");
    TG_CHECK(same && (damping == 0 || same_d), "the bars' or the pressure's forces in node order differ from the one-pass kernels'");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The contact's first pass (two pairs at a time with AVX where the CPU has it, else one by one) against
   the scalar formula, pair by pair: the same list. Nodes sit at 2 r from their bar's line to round-off
   (either side of the test), beyond its ends, on its ends, at its middle; an odd count (the AVX pass's
   last pair alone); a bar of zero length. */
static PetscErrorCode ContactFirstPassAgrees()
{
  PetscFunctionBeginUser;
  turgor_test::Random          rnd(11);
  const PetscReal              R = 0.93, R2 = R * R;
  const size_t                 n = 2001;
  std::vector<PetscReal>       x;
  std::vector<ContactNearPair> near;
  for (size_t k = 0; k < n; k++) {
    const PetscReal     ax = 10 * rnd(), ay = 10 * rnd(), len = k % 97 == 0 ? 0 : 0.5 + 3 * std::fabs(rnd()), th = 3.2 * rnd();
    const PetscReal     ex = len * std::cos(th), ey = len * std::sin(th);
    const PetscReal     ts[6] = {-0.1, 0, 0.5 + 0.4 * rnd(), 1, 1.05, 0.01}, t = ts[k % 6];
    const PetscReal     dist = R * (1 + (k % 3 == 0 ? 4e-16 * rnd() : 0.2 * rnd())), nl = len > 0 ? len : 1;
    const PetscReal     px = ax + t * ex - dist * ey / nl, py = ay + t * ey + dist * ex / nl;
    const std::uint32_t base = (std::uint32_t)x.size();
    x.insert(x.end(), {ax, ay, ax + ex, ay + ey, px, py});
    near.push_back({base + 4, base, base + 2});
  }
  std::vector<PetscInt> want;
  for (size_t j = 0; j < n; j++) {
    const ContactNearPair &C  = near[j];
    const PetscReal        ex = x[C.b2] - x[C.a2], ey = x[C.b2 + 1] - x[C.a2 + 1];
    const PetscReal        px = x[C.p2] - x[C.a2], py = x[C.p2 + 1] - x[C.a2 + 1];
    const PetscReal        L2 = ex * ex + ey * ey, t = std::min(std::max(px * ex + py * ey, (PetscReal)0), L2);
    const PetscReal        dx = px * L2 - t * ex, dy = py * L2 - t * ey;
    if (dx * dx + dy * dy < R2 * L2 * L2) want.push_back((PetscInt)j);
  }
  std::vector<PetscInt> got(n), one(n);
  got.resize(ContactTouchingPairs(near.data(), n, x.data(), R2, got.data()));
  one.resize(ContactTouchingPairsOneByOne(near.data(), n, x.data(), R2, one.data()));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "contact's first pass: %zu of %zu pairs touch by the scalar formula; the pass %s, one by one %s\n", want.size(), n,
                        got == want ? "the same list" : "ANOTHER list", one == want ? "the same list" : "ANOTHER list"));
  TG_CHECK(want.size() > n / 5 && want.size() < 4 * n / 5, "the test's pairs do not sample both sides of 2 r (%zu of %zu touch)", want.size(), n);
  TG_CHECK(got == want && one == want, "the contact's first pass lists other pairs than the scalar formula");
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(TestHingePlasticity());
  PetscCall(TestGradients());
  PetscCall(TestPressurisedNgon());
  PetscCall(TestContactNormal());
  PetscCall(TestContactJoint());
  PetscCall(TestFriction());
  PetscCall(TestNoContactNoLists());
  PetscCall(TestNearList());
  PetscCall(TestEnergy());
  PetscCall(HingeVectorBits(true, true));
  PetscCall(HingeVectorBits(true, false));
  PetscCall(HingeVectorBits(false, true));
  for (int layout = 0; layout < 4; layout++) PetscCall(SpringOrderBits(layout));
  PetscCall(ContactFirstPassAgrees());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "all polygon force checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
