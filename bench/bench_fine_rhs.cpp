static const char help[] = "Fine-scale force evaluation benchmark: RHS evaluations per second and particle updates per\n"
                           "second on one core for square tissues of -sizes cells per side, memory per particle, and the\n"
                           "cost of each physics subset on the seed's 16 x 16 tissue.\n\n"
                           "  bench_fine_rhs [-sizes 16,64,256] [-min_time 2] [-repeats 3]\n";

#include <turgor/turgor.hpp>
#include <algorithm>
#include <cmath>

using namespace turgor;

struct Timing {
  PetscInt  n = 0, evals = 0, pairs_fluid = 0, pairs_spring = 0;
  PetscReal seconds_per_eval = 0, bytes_per_particle = 0;
};

/* A perturbed tissue in motion, so that every pass does real work. */
static PetscErrorCode MakeTissue(PetscInt cells, Tissue *T)
{
  SquareGridSpec spec;
  PetscFunctionBeginUser;
  spec.cells_x = spec.cells_y = cells;
  PetscCall(GenerateSquareGridTissue(PETSC_COMM_SELF, spec, T));
  unsigned long long s   = 12345;
  auto               rnd = [&]() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((s >> 11) * (1.0 / 9007199254740992.0)) * 2.0 - 1.0;
  };
  for (PetscReal &x : T->X) x += 0.2 * rnd();
  T->V.resize(T->X.size());
  for (PetscReal &v : T->V) v = 0.1 * rnd();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The terms of a comma-separated list, each with its options (-wall_*, -sph_*, ...). */
static PetscErrorCode ListedPhysics(const std::string &list, const LoadSpec &load, PhysicsSpec *physics)
{
  PetscFunctionBeginUser;
  physics->names.clear();
  for (size_t begin = 0, end; begin <= list.size(); begin = end + 1) {
    end = std::min(list.find(',', begin), list.size());
    physics->names.push_back(list.substr(begin, end - begin));
  }
  PetscCall(physics->SetFromOptions(PETSC_COMM_SELF, TermContext{&load}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode TimeModel(const Tissue &T, const PhysicsSpec &physics, PetscReal min_time, PetscInt repeats, PetscLogDouble mem_before, Timing *t)
{
  ForceModel             model;
  std::vector<PetscReal> a(T.X.size());
  PetscLogDouble         mem_after, t0, t1;
  PetscFunctionBeginUser;
  PetscCall(model.SetUp(physics, T.particles));
  PetscCall(model.ComputeAcceleration(T.X.data(), T.V.data(), a.data())); /* builds the lists */
  PetscCall(PetscMemoryGetCurrentUsage(&mem_after));
  t->n                  = T.particles.n;
  t->bytes_per_particle = (mem_after - mem_before) / t->n;
  t->pairs_fluid        = (PetscInt)model.Neighbours().FluidPairs().size();
  t->pairs_spring       = (PetscInt)model.Neighbours().ParticleSpringPairs().size();
  t->seconds_per_eval   = PETSC_MAX_REAL;
  for (PetscInt r = 0; r < repeats; r++) { /* best of `repeats` batches of >= min_time seconds */
    PetscInt k = 0;
    PetscCall(PetscTime(&t0));
    do {
      PetscCall(model.ComputeAcceleration(T.X.data(), T.V.data(), a.data()));
      k++;
      PetscCall(PetscTime(&t1));
    } while (t1 - t0 < min_time);
    t->seconds_per_eval = PetscMin(t->seconds_per_eval, (t1 - t0) / k);
    t->evals += k;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt  sizes[8] = {16, 64, 256}, nsizes = 3, repeats = 3;
  PetscReal min_time = 1.0;
  PetscBool set, physics_set;
  LoadSpec  load;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscOptionsBegin(PETSC_COMM_SELF, "", "Benchmark options", "bench");
  PetscCall(PetscOptionsIntArray("-sizes", "Cells per side of the square tissues (default 16,64,256)", "", sizes, &nsizes, &set));
  if (!set) nsizes = 3;
  PetscCall(PetscOptionsReal("-min_time", "Seconds per timing batch", "", min_time, &min_time, NULL));
  PetscCall(PetscOptionsInt("-repeats", "Timing batches (best is reported)", "", repeats, &repeats, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasName(NULL, NULL, "-physics", &physics_set));
  PetscCheck(!physics_set, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Option -physics: the benchmark chooses the terms of each row itself");
  PetscCall(load.SetFromOptions(PETSC_COMM_SELF));

  PetscCall(PetscPrintf(PETSC_COMM_SELF, "All terms (springs, repulsion, sph, body_force), one core; best of %" PetscInt_FMT " batches of >= %g s\n", repeats,
                        (double)min_time));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%8s %10s %10s %12s %12s %14s %14s %12s\n", "cells", "particles", "ms/RHS", "RHS/s", "ns/particle", "updates/s",
                        "bytes/particle", "fluid pairs"));
  std::vector<PetscReal> per_particle;
  for (PetscInt k = 0; k < nsizes; k++) {
    PetscLogDouble mem0;
    Tissue         T;
    PhysicsSpec    spec;
    Timing         t;
    PetscCall(PetscMemoryGetCurrentUsage(&mem0));
    PetscCall(MakeTissue(sizes[k], &T));
    PetscCall(ListedPhysics("springs,repulsion,sph,body_force", load, &spec));
    PetscCall(TimeModel(T, spec, min_time, repeats, mem0, &t));
    per_particle.push_back(1e9 * t.seconds_per_eval / t.n);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%5" PetscInt_FMT "^2 %10" PetscInt_FMT " %10.4f %12.1f %12.1f %14.4g %14.0f %12" PetscInt_FMT "\n", sizes[k], t.n,
                          1e3 * t.seconds_per_eval, 1.0 / t.seconds_per_eval, per_particle.back(), t.n / t.seconds_per_eval, t.bytes_per_particle,
                          t.pairs_fluid));
  }
  if (per_particle.size() > 1) {
    PetscReal lo = per_particle[0], hi = per_particle[0];
    for (PetscReal c : per_particle) lo = PetscMin(lo, c), hi = PetscMax(hi, c);
    PetscReal mean = 0.5 * (lo + hi);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "cost per particle: %.1f .. %.1f ns, i.e. within +-%.0f%% of %.1f ns\n", (double)lo, (double)hi,
                          100.0 * (hi - mean) / mean, (double)mean));
  }

  PetscCall(PetscPrintf(PETSC_COMM_SELF, "\nPhysics subsets on the 16 x 16 tissue (a term that is off costs nothing):\n"));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-36s %10s %12s %14s %14s\n", "-physics", "ms/RHS", "RHS/s", "fluid pairs", "spring pairs"));
  for (const char *physics : {"springs", "springs,repulsion", "springs,repulsion,sph", "springs,repulsion,sph,body_force"}) {
    PetscLogDouble mem0;
    Tissue         T;
    PhysicsSpec    spec;
    Timing         t;
    PetscCall(PetscMemoryGetCurrentUsage(&mem0));
    PetscCall(MakeTissue(16, &T));
    PetscCall(ListedPhysics(physics, load, &spec));
    PetscCall(TimeModel(T, spec, min_time, repeats, mem0, &t));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-36s %10.4f %12.1f %14" PetscInt_FMT " %14" PetscInt_FMT "\n", physics, 1e3 * t.seconds_per_eval,
                          1.0 / t.seconds_per_eval, t.pairs_fluid, t.pairs_spring));
  }
  PetscCall(PetscFinalize());
  return 0;
}
