static const char help[] = "Polygonal-cell forces benchmark: node-steps per second of a velocity-Verlet loop (one force-model\n"
                           "evaluation per step, plus AcceptStep when a term has state) on a jittered hexagonal tissue of\n"
                           "-cells_x x -cells_y hexagons (neighbours 2 r apart) with bars, hinges and contact.\n\n"
                           "-edge_speed s sets the compression by the speed of the tissue's edge (strain rate s / half-width) instead of\n"
                           "the strain rate 1e-3 /µs, so that tissues of every size see the same motion at their nodes (node_cost_flatness.py).\n\n"
                           "  bench_polygon_forces [-cells_x 20] [-cells_y 19] [-steps 20000] [-friction 0.3] [-physics_set bars,hinges,contact]\n"
                           "                       [-edge_speed s]\n";
#include "../tests/test_util.h"
#include "../tests/polygon_util.h"
#include <turgor/physics/bars.h>
#include <turgor/physics/contact.h>
#include <turgor/physics/hinges.h>
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>

using namespace turgor;

int main(int argc, char **argv)
{
  PetscInt  nx = 20, ny = 19, steps = 20000;
  PetscReal mu = 0.3, edge_speed = 0;
  char      set[256] = "bars,hinges,contact";
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-cells_x", &nx, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-cells_y", &ny, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-steps", &steps, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-friction", &mu, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-edge_speed", &edge_speed, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-physics_set", set, sizeof set, NULL));
  const std::string physics = set;
  /* hexagons on a triangular lattice of spacing D, neighbours 2 r apart; the jitter (nodes pulled
     towards their centre by up to 0.1 µm) is part of the reference geometry (rest lengths and
     angles), so the tissue starts at rest with no overlap; a uniform compression velocity (strain
     rate 1e-3 /µs) then closes the gaps and brings cells into contact */
  const PetscReal             D = 10, r = 0.25, m = 1;
  turgor_test::PolygonBuilder B;
  turgor_test::Random         rnd(2024);
  Tissue                     &T  = turgor_test::HexagonTissue(B, nx, ny, D, r, m, rnd);
  std::vector<PetscReal>      x  = T.X, v(x.size()), a(x.size());
  const PetscReal             xc = 0.5 * (T.lo[0] + T.hi[0]), yc = 0.5 * (T.lo[1] + T.hi[1]);
  const PetscReal             rate = edge_speed > 0 ? edge_speed / (0.5 * std::max(T.hi[0] - T.lo[0], T.hi[1] - T.lo[1])) : 1e-3;
  for (PetscInt i = 0; i < T.particles.n; i++) {
    v[2 * i]     = -rate * (x[2 * i] - xc) + 0.01 * rnd();
    v[2 * i + 1] = -rate * (x[2 * i + 1] - yc) + 0.01 * rnd();
  }
  std::vector<std::unique_ptr<ForceTerm>> terms;
  if (physics.find("bars") != std::string::npos) {
    auto b       = std::make_unique<Bars>();
    b->stiffness = 1e4;
    terms.push_back(std::move(b));
  }
  if (physics.find("hinges") != std::string::npos) {
    auto h        = std::make_unique<Hinges>();
    h->stiffness  = 1e3;
    h->max_moment = 50;
    terms.push_back(std::move(h));
  }
  if (physics.find("contact") != std::string::npos) {
    auto c                  = std::make_unique<Contact>();
    c->stiffness            = 1e4;
    c->friction             = mu;
    c->tangential_stiffness = 5e3;
    terms.push_back(std::move(c));
  }
  ForceModel M;
  PetscCall(turgor_test::MakeModel(T.particles, std::move(terms), M, 0.2));
  std::vector<TimeStepLimit> lim;
  PetscCall(M.TimeStepLimits(x.data(), v.data(), lim));
  PetscReal dt = PETSC_MAX_REAL;
  for (auto &l : lim) dt = std::min(dt, l.dt);
  dt *= 0.5;
  const bool state = M.HasInternalState();
  PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
  const Contact *C        = dynamic_cast<const Contact *>(M.Term("contact"));
  double         cand_sum = 0, near_sum = 0, contact_sum = 0;
  auto           run = [&](PetscInt n) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (PetscInt s = 0; s < n; s++) {
      for (size_t q = 0; q < x.size(); q++) {
        v[q] += 0.5 * dt * a[q];
        x[q] += dt * v[q];
      }
      PetscCall(M.ComputeAcceleration(x.data(), v.data(), a.data()));
      for (size_t q = 0; q < x.size(); q++) v[q] += 0.5 * dt * a[q];
      if (state) PetscCall(M.AcceptStep(x.data(), v.data()));
      if (C) cand_sum += C->Candidates(), near_sum += C->NearCandidates(), contact_sum += C->ActiveContacts();
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  };
  PetscCall(run(steps / 10)); /* warm-up */
  cand_sum = near_sum = contact_sum = 0;
  const PetscInt rebuild0 = M.Neighbours().Rebuilds(), near0 = C ? C->NearListBuilds() : 0;
  const auto     t0 = std::chrono::steady_clock::now();
  const auto     c0 = std::clock(); /* CPU time as well: on a shared machine the wall time includes waiting */
  PetscCall(run(steps));
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), cpu = (double)(std::clock() - c0) / CLOCKS_PER_SEC;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "polygon forces [%s]: %" PetscInt_FMT " cells, %" PetscInt_FMT " nodes, %zu bars, dt %.3g µs\n", physics.c_str(),
                        nx * ny, T.particles.n, T.particles.springs.size(), dt));
  if (C)
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "  contact: %.0f candidates, %.0f near and %.0f contacts per step on average, %" PetscInt_FMT " rebuilds and %" PetscInt_FMT
                          " near-list builds in %" PetscInt_FMT " steps\n",
                          cand_sum / steps, near_sum / steps, contact_sum / steps, M.Neighbours().Rebuilds() - rebuild0, C->NearListBuilds() - near0, steps));
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "  %" PetscInt_FMT " steps in %.3f s wall, %.3f s CPU: %.3g node-steps/s (wall), %.3g node-steps/s (CPU), %.1f ns CPU per node-step\n",
                        steps, sec, cpu, steps * (double)T.particles.n / sec, steps * (double)T.particles.n / cpu,
                        1e9 * cpu / (steps * (double)T.particles.n)));
  PetscCall(PetscFinalize());
  return 0;
}
