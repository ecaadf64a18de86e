static const char help[] = "RVE benchmark: wall time of a cold RVE solve, a warm-started solve after a 1e-3 strain\n"
                           "increment, a full tangent by forward differences (6 perturbed solves), with Psi-tc iterations,\n"
                           "and the exact tangent (implicit differentiation: no RVE solve; its force evaluations and\n"
                           "Krylov iterations), for RVEs of -cells 1,4 cells per side (the seed's parameters; other\n"
                           "options as for turgor).\n\n"
                           "  bench_rve [-cells 1,4] [-repeats 5]\n";

#include <turgor/app/register_all.h>
#include <turgor/rve/rve.h>

using namespace turgor;

int main(int argc, char **argv)
{
  PetscInt  cells[4] = {1, 4}, ncells = 2, repeats = 5;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscOptionsBegin(PETSC_COMM_SELF, "", "RVE benchmark options", "bench");
  PetscCall(PetscOptionsIntArray("-cells", "RVE sizes (cells per side)", "", cells, &ncells, &set));
  if (!set) ncells = 2;
  PetscCall(PetscOptionsInt("-repeats", "Repetitions (best time is reported)", "", repeats, &repeats, NULL));
  PetscOptionsEnd();
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%6s %9s %10s %7s %10s %7s %12s %12s %9s %11s %12s %7s %7s %11s\n", "cells", "unknowns", "cold [ms]", "its",
                        "warm [ms]", "its", "warm/cold", "tangent[ms]", "its", "tan/cold", "exact [ms]", "fevals", "krylov", "exact/tan"));
  for (PetscInt c = 0; c < ncells; c++) {
    /* one material per RVE size (its options, e.g. -rve_psi_atol, still apply; -rve_cells would
       override -cells, so the size printed is the material's), a fresh point per repetition */
    RVEMaterial material;
    material.spec.cells = cells[c];
    PetscCall(material.SetFromOptions(PETSC_COMM_SELF, nullptr));
    PetscReal     best[4] = {1e30, 1e30, 1e30, 1e30};
    PetscInt      its[3] = {0, 0, 0}, unknowns = 0, exact_evals = 0, exact_its = 0;
    const Tensor2 F0 =
                    {
                      {{1.01, 0}, {0, 1}}
    },
                  F1 = {{{1.011, 0}, {0, 1}}}, Fd = {{{1e-3, 0}, {0, 0}}};
    for (PetscInt r = 0; r < repeats; r++) {
      std::unique_ptr<MaterialPoint> point;
      MaterialResponse               a, b, s;
      Tangents                       D;
      MaterialCounters               before, after;
      TangentOptions                 implicit;
      PetscLogDouble                 t0, t1, t2, t3, t4;
      PetscCall(material.CreatePoint(PETSC_COMM_SELF, &point));
      const RVE *rve = dynamic_cast<const RVE *>(point.get());
      PetscCheck(rve, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the rve material must create RVE points");
      unknowns = rve->NumUnknowns();
      PetscCall(PetscTime(&t0));
      PetscCall(point->Evaluate(F0, Fd, EvaluationKind::Trial, &a));
      PetscCall(PetscTime(&t1));
      PetscCall(point->Evaluate(F1, Fd, EvaluationKind::Trial, &b));
      PetscCall(PetscTime(&t2));
      /* the exact tangent first: it differentiates the last evaluated state (forward differences
         leave the last perturbed one) */
      implicit.method = TangentMethod::Implicit;
      PetscCall(ComputeTangents(*point, F1, Fd, b, implicit, &D, &s));
      PetscCheck(s.ok, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "exact tangent failed: %s", s.reason.c_str());
      PetscCall(PetscTime(&t3));
      point->AddCounters(before);
      PetscCall(ComputeTangents(*point, F1, Fd, b, TangentOptions(), &D, &s));
      PetscCall(PetscTime(&t4));
      point->AddCounters(after);
      PetscCheck(a.ok && b.ok && s.ok, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "RVE evaluation failed");
      best[0]     = PetscMin(best[0], t1 - t0);
      best[1]     = PetscMin(best[1], t2 - t1);
      best[2]     = PetscMin(best[2], t4 - t3);
      best[3]     = PetscMin(best[3], t3 - t2);
      exact_evals = before.tangent_force_evals;
      exact_its   = before.tangent_linear_its;
      its[0]      = a.iterations;
      its[1]      = b.iterations;
      its[2]      = after.iterations - before.iterations;
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "%6" PetscInt_FMT " %9" PetscInt_FMT " %10.3f %7" PetscInt_FMT " %10.3f %7" PetscInt_FMT " %12.3f %12.3f %9" PetscInt_FMT
                          " %11.2f %12.3f %7" PetscInt_FMT " %7" PetscInt_FMT " %11.2f\n",
                          material.spec.cells, unknowns, 1e3 * best[0], its[0], 1e3 * best[1], its[1], best[1] / best[0], 1e3 * best[2], its[2],
                          best[2] / best[0], 1e3 * best[3], exact_evals, exact_its, best[3] / best[2]));
  }
  PetscCall(PetscFinalize());
  return 0;
}
