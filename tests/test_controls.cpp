static const char help[] = "Load controls of the fine run against closed forms, with DOPRI (rk 5dp) and velocity Verlet:\n"
                           "1. free particles under a constant imposed velocity move as x0 + v t (to round-off), a free component falls\n"
                           "   freely under the body force (-g t^2 / 2);\n"
                           "2. a ramp reaches v T / 2 + v (t - T); a cyclic profile is back at the start after a full period;\n"
                           "   a delayed group starts at its delay; a group with a duration stops after it and holds;\n"
                           "3. a force-controlled node with no other force moves as F t^2 / (2 m), and groups.csv reports F;\n"
                           "4. the reaction of a node pulling a spring chain equals the last spring's tension k (l - l0);\n"
                           "5. groups.csv has the columns time, <name>_ux, _uy, _fx, _fy, _mz and one row per sample;\n"
                           "6. TS verlet holds the controlled components in its own state (TSVerletSetConstraints): the state's\n"
                           "   velocities are the imposed ones exactly at the end.\n";
#include "test_util.h"
#include "fine_run_util.h"
#include <string>
#include <turgor/physics/body_force.h>
#include <turgor/physics/wall_springs.h>
#include <turgor/ts/velocity_verlet.h>
#include <fstream>
#include <sstream>

using namespace turgor;

struct Result {
  std::vector<PetscReal>              x;      /* final state positions [2n] */
  std::vector<PetscReal>              v;      /* final state velocities [2n] (the integrator's, as it holds them) */
  std::vector<std::string>            header; /* groups.csv */
  std::vector<std::vector<PetscReal>> rows;
};

static PetscErrorCode ReadCsv(const std::string &path, Result *r)
{
  std::ifstream in(path);
  std::string   line;
  PetscFunctionBeginUser;
  TG_CHECK(std::getline(in, line), "cannot read %s", path.c_str());
  {
    std::stringstream ss(line);
    std::string       c;
    while (std::getline(ss, c, ',')) r->header.push_back(c);
  }
  while (std::getline(in, line)) {
    std::stringstream      ss(line);
    std::string            c;
    std::vector<PetscReal> row;
    while (std::getline(ss, c, ',')) row.push_back(std::stod(c));
    r->rows.push_back(row);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Run `tissue` with the given terms and groups to t_final; Verlet with a fixed step dt. */
static PetscErrorCode Run(const Tissue &tissue, std::vector<std::unique_ptr<ForceTerm>> terms, const std::vector<ControlGroup> &groups, TSType type,
                          PetscReal t_final, PetscReal dt, PetscInt samples, const std::vector<std::string> &clamp, Result *r)
{
  FineRun run(PETSC_COMM_SELF);
  PetscFunctionBeginUser;
  run.Physics().names = {};
  for (auto &t : terms) run.Physics().Add(std::move(t));
  for (const ControlGroup &g : groups) run.GetControls().Add(g);
  run.Spec().clamp = clamp;
  run.Spec().dt    = dt;
  turgor_test::QuietOutput(run, "test_controls_out", samples);
  PetscCall(run.SetFromOptions());
  run.SetTissue(tissue);
  PetscCall(TSSetType(run.GetTS(), type));
  PetscCall(TSSetMaxTime(run.GetTS(), t_final));
  if (std::string(type) == TSRK) PetscCall(TSSetTolerances(run.GetTS(), 1e-10, NULL, 1e-10, NULL));
  PetscCall(run.SetUp());
  PetscCall(run.Solve());
  PetscCall(run.WriteSummary());
  const PetscScalar *u;
  const PetscInt     n = tissue.particles.n;
  PetscCall(VecGetArrayRead(run.GetState(), &u));
  r->x.assign(u, u + 2 * n);
  r->v.assign(u + 2 * n, u + 4 * n);
  PetscCall(VecRestoreArrayRead(run.GetState(), &u));
  r->header.clear();
  r->rows.clear();
  PetscCall(ReadCsv("test_controls_out/groups.csv", r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static ControlGroup Group(const char *name, std::vector<PetscInt> nodes, bool velocity, PetscReal a, PetscReal b, ControlProfile profile = CONTROL_STEP)
{
  ControlGroup g;
  g.name     = name;
  g.node_ids = nodes;
  g.velocity = velocity;
  g.value[0] = a;
  g.value[1] = b;
  g.profile  = profile;
  return g;
}

int main(int argc, char **argv)
{
  const PetscReal m = 0.5;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  Tissue free3; /* three free particles, no springs */
  for (int i = 0; i < 3; i++) free3.AddParticle(10.0 * i, 1.0 * i, m, KIND_WALL);
  free3.Finalize();

  for (TSType type : {TSRK, TSBASICSYMPLECTIC, TSVERLET}) {
    const bool      held = std::string(type) == TSVERLET; /* the integrator's state holds the controls */
    const PetscReal T = 7.0, dt = 0.01;
    Result          r;
    { /* 1. constant velocity on particles 0, 2; particle 1: vx imposed, y free under gravity */
      const PetscReal                         g  = 0.3;
      auto                                    bf = std::make_unique<BodyForce>();
      std::vector<std::unique_ptr<ForceTerm>> terms;
      bf->load.body_acceleration[0] = 0, bf->load.body_acceleration[1] = -g;
      terms.push_back(std::move(bf));
      ControlGroup a = Group("a", {0, 2}, true, 0.25, -0.125), b = Group("b", {1}, true, 0.5, 0);
      b.free[1] = true;
      PetscCall(Run(free3, std::move(terms), {a, b}, type, T, dt, 10, {"none"}, &r));
      for (PetscInt i : {0, 2}) {
        TG_CHECK_CLOSE(r.x[2 * i], free3.X[2 * i] + 0.25 * T, 1e-12, 1, "x of a velocity-controlled particle");
        TG_CHECK_CLOSE(r.x[2 * i + 1], free3.X[2 * i + 1] - 0.125 * T, 1e-12, 1, "y of a velocity-controlled particle");
      }
      TG_CHECK_CLOSE(r.x[2], free3.X[2] + 0.5 * T, 1e-12, 1, "controlled x of the half-free particle");
      TG_CHECK_CLOSE(r.x[3], free3.X[3] - 0.5 * g * T * T, 1e-9, 1, "free y of the half-free particle (free fall)");
      TG_CHECK(!held || (r.v[0] == 0.25 && r.v[1] == -0.125 && r.v[4] == 0.25 && r.v[5] == -0.125 && r.v[2] == 0.5),
               "TS verlet's state does not hold the imposed velocities: (%g, %g), (%g, %g), %g", (double)r.v[0], (double)r.v[1], (double)r.v[4], (double)r.v[5],
               (double)r.v[2]);
      TG_CHECK_CLOSE(r.rows.back()[1], 0.25 * T, 1e-13, 1, "groups.csv a_ux");
      TG_CHECK_CLOSE(r.rows.back()[7], -0.5 * g * T * T, 1e-9, 1, "groups.csv b_uy (free)");
      /* the gravity the controlled components resist: reaction = -(m g) per node, in y only for a */
      TG_CHECK_CLOSE(r.rows.back()[4], 2 * m * g, 1e-12, 1, "groups.csv a_fy: the reaction holds the weight");
      TG_CHECK(r.rows.back()[9] == 0, "a free component has no reaction");
      TG_CHECK(r.header.size() == 11 && r.header[0] == "time" && r.header[1] == "a_ux" && r.header[4] == "a_fy" && r.header[5] == "a_mz" &&
                 r.header[9] == "b_fy",
               "groups.csv columns");
      TG_CHECK(r.rows.size() == 11, "groups.csv has %zu rows, expected 11", r.rows.size());
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s constant velocity: x - (x0 + v t) = %.2e µm, free fall error %.2e µm\n", type,
                            (double)(r.x[0] - free3.X[0] - 0.25 * T), (double)(r.x[3] - free3.X[3] + 0.5 * g * T * T)));
    }
    { /* 2. ramp and cyclic */
      ControlGroup a = Group("ramp", {0}, true, 0.4, 0, CONTROL_RAMP), c = Group("cyc", {2}, true, 0, 0.3, CONTROL_CYCLIC);
      a.ramp_time   = 2.5;
      c.half_period = 1.75; /* T = 2 full periods */
      PetscCall(Run(free3, {}, {a, c}, type, T, dt, 28, {"none"}, &r));
      const PetscReal ramp = 0.4 * 2.5 / 2 + 0.4 * (T - 2.5);
      TG_CHECK_CLOSE(r.rows.back()[1], ramp, 1e-13, 1, "ramp displacement (groups.csv)");
      TG_CHECK_CLOSE(r.x[0] - free3.X[0], ramp, std::string(type) == TSRK ? 1e-7 : 1e-12, 1, "ramp displacement (state)");
      TG_CHECK_CLOSE(r.rows[4][1], 0.4 * 1.0 / (2 * 2.5), 1e-13, 1, "ramp displacement at t = 1 < T (v t^2 / 2T)");
      TG_CHECK(!held || r.v[0] == 0.4, "TS verlet's state: the ramp's velocity %g, not 0.4", (double)r.v[0]);
      TG_CHECK_CLOSE(r.rows[7][7], 0.3 * 1.75, 1e-13, 1, "cyclic displacement after a half period");
      TG_CHECK(std::fabs(r.rows[14][7]) < 1e-13 && std::fabs(r.rows.back()[7]) < 1e-13, "cyclic: not back at the start after full periods");
      TG_CHECK(std::fabs(r.x[5] - free3.X[5]) < (std::string(type) == TSRK ? 1e-7 : 1e-12), "cyclic (state): %g", (double)(r.x[5] - free3.X[5]));
      TG_CHECK_CLOSE(r.rows[4][3], m * 0.4 / 2.5, 1e-12, 1, "ramp reaction: m a_c");
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s ramp: state error %.2e µm; cyclic after 2 periods: state %.2e µm\n", type,
                            (double)(r.x[0] - free3.X[0] - ramp), (double)(r.x[5] - free3.X[5])));
    }
    { /* 2b. delayed: a velocity group holds still until its delay, then moves; a delayed force
         group pushes from its delay on: x = F (t - d)^2 / 2m */
      ControlGroup a = Group("late", {0}, true, 0.5, 0), f = Group("push", {1}, false, 0.02, 0), b = Group("brief", {2}, true, 0, 0.3, CONTROL_RAMP);
      a.delay = 2.0, f.delay = 3.0;
      b.delay = 0.5, b.ramp_time = 1.0, b.duration = 1.5; /* ramp to 0.3 over 1 µs, then 0.5 µs at 0.3, then still */
      PetscCall(Run(free3, {}, {a, f, b}, type, T, dt, 7, {"none"}, &r));
      const PetscReal brief = 0.3 * 1.0 / 2 + 0.3 * 0.5;
      TG_CHECK_CLOSE(r.rows.back()[12], brief, 1e-13, 1, "a control with a duration: v T / 2 + v (D - T), then still (groups.csv)");
      TG_CHECK_CLOSE(r.x[5] - free3.X[5], brief, std::string(type) == TSRK ? 1e-7 : 1e-12, 1, "a control with a duration (state)");
      TG_CHECK(r.rows[2][1] == 0, "a delayed velocity control moved before its delay: %g", (double)r.rows[2][1]);
      TG_CHECK_CLOSE(r.x[0] - free3.X[0], 0.5 * (T - 2.0), std::string(type) == TSRK ? 1e-7 : 1e-12, 1, "delayed velocity control: v (t - delay)");
      TG_CHECK_CLOSE(r.x[2] - free3.X[2], 0.02 * (T - 3.0) * (T - 3.0) / (2 * m), std::string(type) == TSRK ? 1e-6 : 1e-3, 1,
                     "delayed force control: F (t - d)^2 / 2m");
      TG_CHECK(r.rows[2][8] == 0 && r.rows[4][8] == 0.02, "groups.csv: the delayed force is 0 before the delay, F after");
    }
    { /* 3. force control on one node, no other force */
      const PetscReal F = 0.02;
      PetscCall(Run(free3, {}, {Group("f", {1}, false, F, -2 * F)}, type, T, dt, 10, {"none"}, &r));
      TG_CHECK_CLOSE(r.x[2] - free3.X[2], F * T * T / (2 * m), 1e-10, 1, "force control: x = F t^2 / 2m");
      TG_CHECK_CLOSE(r.x[3] - free3.X[3], -2 * F * T * T / (2 * m), 1e-10, 1, "force control: y");
      TG_CHECK(r.rows.back()[3] == F && r.rows.back()[4] == -2 * F, "groups.csv: the applied force");
      TG_CHECK(r.x[0] == free3.X[0] && r.x[4] == free3.X[4], "particles outside the group moved");
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s force control: x - F t^2/2m = %.2e µm\n", type, (double)(r.x[2] - free3.X[2] - F * T * T / (2 * m))));
    }
    { /* 4. a chain of 4 springs, left end clamped, right end pulled at constant velocity */
      const PetscReal k = 40, l0 = 5;
      Tissue          chain;
      for (int i = 0; i < 5; i++) chain.AddParticle(l0 * i, 0, m, KIND_WALL);
      for (int i = 0; i < 4; i++) chain.AddSpring(i, i + 1);
      chain.Finalize();
      auto springs           = std::make_unique<WallSprings>();
      springs->stiffness     = k;
      springs->damping_ratio = 0;
      std::vector<std::unique_ptr<ForceTerm>> terms;
      terms.push_back(std::move(springs));
      PetscCall(Run(chain, std::move(terms), {Group("pull", {4}, true, 0.2, 0)}, type, T, 1e-3, 10, {"left"}, &r));
      const PetscReal l = std::hypot(r.x[8] - r.x[6], r.x[9] - r.x[7]), tension = k * (l - l0);
      TG_CHECK(tension > 0.1, "the chain is not stretched");
      TG_CHECK_CLOSE(r.rows.back()[3], tension, 1e-9, 1, "reaction of the pulling node vs the last spring's tension k (l - l0)");
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s chain: reaction %.10g µN, tension k (l - l0) %.10g µN\n", type, (double)r.rows.back()[3], (double)tension));
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "test_controls: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
