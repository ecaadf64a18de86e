static const char help[] = "Eigen analysis of the coarse model (src/analysis/), each against a second method:\n"
                           " 1. the acoustic tensor's smallest determinant (Voigt D^e + stress, golden-section search) against\n"
                           "    the full fourth-order neo-Hookean moduli sampled in 100000 directions, closed form at F = I, and a\n"
                           "    loss of ellipticity;\n"
                           " 2. DOPRI's stability boundary: |R| = 1 on it and < 1 inside, the real interval 3.3066;\n"
                           " 3. CoarseModel::AssembleTangentAt against IJacobian's K and C blocks, leaving the model as it was\n"
                           "    (its residual bit for bit, its counters), for the closed-form material and the RVE;\n"
                           " 4. the lowest and largest eigenvalues of (K, M) (SLEPc EPS) and the damped ones (PEP) against dense\n"
                           "    LAPACK (sygv; geev on the first-order companion form) on a deformed cantilever;\n"
                           " 5. a coarse snapshot written and read back (ReadCoarseSnapshot) gives the state written; one with NaN\n"
                           "    displacements is refused.\n";
#include "test_util.h"
#include <turgor/analysis/coarse_operators.h>
#include <turgor/analysis/damped_modes.h>
#include <turgor/analysis/explicit_stability.h>
#include <turgor/analysis/pencil_eigensolver.h>
#include <turgor/coarse/coarse_fields.h>
#include <turgor/coarse/coarse_snapshot_reader.h>
#include <turgor/material/acoustic_tensor.h>
#include <turgor/material/neo_hookean.h>
#include <petscblaslapack.h>
#include <algorithm>
#include <complex>
#include <cstring>
#include <filesystem>

using namespace turgor;

/* 1. Acoustic tensor. The reference builds A_ijkl = c_ijkl + delta_ik sigma_jl from the
   neo-Hookean spatial moduli c_ijkl = (lambda/J) d_ij d_kl + ((mu - lambda ln J)/J)(d_ik d_jl +
   d_il d_jk) directly (no Voigt mapping) and samples det Q(n) in 100000 directions. */
static PetscReal BruteForceMinDet(const NeoHookeanSpec &p, const Tensor2 &F, const Tensor2 &sigma)
{
  const PetscReal J = F.Det(), m = (p.mu - p.lambda * std::log(J)) / J;
  auto            d    = [](int i, int j) { return i == j ? 1.0 : 0.0; };
  PetscReal       best = PETSC_MAX_REAL;
  for (int s = 0; s < 100000; s++) {
    const PetscReal th = PETSC_PI * s / 100000, n[2] = {std::cos(th), std::sin(th)};
    PetscReal       Q[2][2] = {
            {0, 0},
            {0, 0}
    };
    for (int i = 0; i < 2; i++)
      for (int k = 0; k < 2; k++)
        for (int j = 0; j < 2; j++)
          for (int l = 0; l < 2; l++) {
            const PetscReal c = p.lambda / J * d(i, j) * d(k, l) + m * (d(i, k) * d(j, l) + d(i, l) * d(j, k));
            Q[i][k] += n[j] * (c + d(i, k) * sigma(j, l)) * n[l];
          }
    best = PetscMin(best, Q[0][0] * Q[1][1] - Q[0][1] * Q[1][0]);
  }
  return best;
}

static PetscErrorCode AcousticTensorCheck()
{
  NeoHookeanSpec   spec;
  NeoHookean       nh(spec);
  MaterialResponse r;
  Tangents         D;
  PetscFunctionBeginUser;
  spec.viscosity = 0;
  nh.p           = spec;
  /* F = I: Q = mu I + (lambda + mu) n n for every n, det = mu (lambda + 2 mu) */
  nh.AnalyticTangents(Tensor2::Identity(), &D);
  {
    const AcousticMinimum a = MinAcousticDeterminant(D.De, Tensor2::Zero());
    TG_CHECK_CLOSE(a.det, spec.mu * (spec.lambda + 2 * spec.mu), 1e-13, 0, "min det Q at F = I");
  }
  /* a stretched and sheared state, with its stress */
  const Tensor2 F = {
    {{1.3, 0.2}, {-0.1, 0.8}}
  };
  PetscCall(nh.Evaluate(F, Tensor2::Zero(), EvaluationKind::Trial, &r));
  nh.AnalyticTangents(F, &D);
  {
    const AcousticMinimum a = MinAcousticDeterminant(D.De, r.sigma);
    const PetscReal       b = BruteForceMinDet(spec, F, r.sigma);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "1. acoustic tensor, F = [1.3 0.2; -0.1 0.8]: min det Q = %.12g at %.6f rad; sampled %.12g\n", (double)a.det,
                          (double)a.angle, (double)b));
    TG_CHECK(a.det <= b * (1 + 1e-12), "the search's minimum %g is above a sampled value %g", (double)a.det, (double)b);
    TG_CHECK_CLOSE(a.det, b, 1e-8, 0, "min det Q against 100000 sampled directions");
  }
  /* loss of ellipticity: an initial compression beyond mu makes Q(n) indefinite across n */
  {
    Tensor2 s = Tensor2::Identity();
    s(0, 0)   = -3 * spec.mu;
    s(1, 1)   = -0.5 * spec.mu;
    nh.AnalyticTangents(Tensor2::Identity(), &D);
    const AcousticMinimum a = MinAcousticDeterminant(D.De, s);
    const PetscReal       b = BruteForceMinDet(spec, Tensor2::Identity(), s);
    PetscCall(
      PetscPrintf(PETSC_COMM_WORLD, "   under sigma = diag(-3 mu, -mu / 2): min det Q = %.12g (sampled %.12g): not elliptic\n", (double)a.det, (double)b));
    TG_CHECK(a.det < 0, "loss of ellipticity not seen");
    TG_CHECK_CLOSE(a.det, b, 1e-8, 0, "min det Q under compression");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 2. DP5 boundary: on it |R| = 1, just inside |R| < 1. */
static PetscErrorCode DopriBoundaryCheck()
{
  const double c[7] = {1, 1, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 600};
  auto         R    = [&](std::complex<double> z) {
    std::complex<double> r = 0, zk = 1;
    for (double ck : c) {
      r += ck * zk;
      zk *= z;
    }
    return std::abs(r);
  };
  PetscFunctionBeginUser;
  for (PetscReal th : {0.55 * PETSC_PI, 0.7 * PETSC_PI, 0.85 * PETSC_PI, PETSC_PI}) {
    const PetscReal r = DormandPrinceBoundary(th);
    TG_CHECK_CLOSE(R(std::polar((double)r, (double)th)), 1.0, 1e-9, 0, "|R| on DP5's boundary");
    for (double f : {0.25, 0.5, 0.75, 0.99}) TG_CHECK(R(std::polar(f * r, (double)th)) < 1, "|R| >= 1 inside DP5's boundary at theta %g", (double)th);
  }
  TG_CHECK_CLOSE(DormandPrinceBoundary(PETSC_PI), 3.3066, 1e-4, 0, "DP5's real stability interval");
  TG_CHECK_CLOSE(DormandPrinceStepLimit(2.0, 3.0), DormandPrinceBoundary(PETSC_PI) / (2.0 * (3.0 + std::sqrt(8.0))), 1e-14, 0, "overdamped limit");
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "2. DP5 stability boundary: real interval %.6f; at zeta 0.15: dt omega <= %.6f\n",
                        (double)DormandPrinceBoundary(PETSC_PI), (double)DormandPrinceStepLimit(1.0, 0.15)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MakeModel(CoarseModel &model, const char *material, PetscInt nx, PetscInt ny, PetscReal Lx, PetscReal Ly, PetscReal gy)
{
  std::unique_ptr<MaterialModel> m;
  DM                             dm;
  const PetscInt                 faces[2] = {nx, ny};
  const PetscReal                lo[2] = {0, 0}, hi[2] = {Lx, Ly};
  LoadSpec                       load;
  PetscFunctionBeginUser;
  PetscCall(MaterialModelCreate(PETSC_COMM_WORLD, material, &m));
  PetscCall(m->SetFromOptions(PETSC_COMM_WORLD, nullptr));
  model.Pool().SetMaterial(std::move(m));
  model.Pool().SetDefaultTolerance(1e-12);
  PetscCall(DMPlexCreateBoxMesh(PETSC_COMM_WORLD, 2, PETSC_FALSE, faces, lo, hi, NULL, PETSC_TRUE, &dm));
  PetscCall(model.SetMesh(dm));
  PetscCall(DMDestroy(&dm));
  load.body_acceleration[0] = 0;
  load.body_acceleration[1] = gy;
  model.SetLoad(load);
  PetscCall(model.SetFromOptions());
  PetscCall(model.SetUp());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a deformed state: u = a (x^2 / L^2 e_y - 0.02 x / L e_x), v = b sin(x) e_y */
static PetscErrorCode DeformedState(CoarseModel &model, Vec U, PetscReal a, PetscReal b)
{
  std::string missing;
  PetscFunctionBeginUser;
  PetscCall(model.NodeState(
    U,
    [&](const PetscReal X[2], PetscReal state[4]) {
      const PetscReal x = X[0] / 400, y = X[1] / 400;
      state[0] = -0.02 * a * x * 400;
      state[1] = a * x * x * 400 + 0.01 * a * x * y * 400;
      state[3] = b * std::sin(3 * x);
      return true;
    },
    &missing));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 3. AssembleTangentAt = IJacobian's K, C (shift 0) and leaves the model as it was. */
static PetscErrorCode TangentAtCheck(const char *material, PetscReal tol)
{
  CoarseModel model(PETSC_COMM_WORLD);
  Vec         U, Z, F0, F1;
  Mat         J, A;
  PetscBool   ok;
  std::string why;
  PetscReal   nJ, nd, df;
  PetscFunctionBeginUser;
  PetscCall(MakeModel(model, material, 3, 2, 400, 400, -0.2));
  PetscCall(model.CreateGlobalVector(&U));
  PetscCall(VecDuplicate(U, &Z));
  PetscCall(VecDuplicate(U, &F0));
  PetscCall(VecDuplicate(U, &F1));
  PetscCall(VecZeroEntries(Z));
  PetscCall(DeformedState(model, U, 0.05, 0.01));
  PetscCall(MatDuplicate(model.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &J));
  PetscCall(MatDuplicate(model.MassMatrix(), MAT_DO_NOT_COPY_VALUES, &A));
  PetscCall(model.IJacobian(U, 0.0, J, &ok));
  TG_CHECK(ok, "IJacobian failed");
  PetscCall(model.IFunction(U, Z, F0, &ok));
  const CoarseCounters before = model.Counters();
  MaterialCounters     mc0, mc1;
  PetscCall(model.Pool().GlobalCounters(&mc0));
  PetscCall(model.AssembleTangentAt(U, true, A, &ok, &why));
  TG_CHECK(ok, "AssembleTangentAt failed: %s", why.c_str());
  PetscCall(model.Pool().GlobalCounters(&mc1));
  PetscCall(MatNorm(J, NORM_FROBENIUS, &nJ));
  PetscCall(MatAXPY(A, -1.0, J, SAME_NONZERO_PATTERN));
  PetscCall(MatNorm(A, NORM_FROBENIUS, &nd));
  PetscCall(model.IFunction(U, Z, F1, &ok));
  PetscCall(VecAXPY(F1, -1.0, F0));
  PetscCall(VecNorm(F1, NORM_INFINITY, &df));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "3. %s: AssembleTangentAt vs IJacobian: |difference| / |J| = %.2e; the residual after it differs by %g; output solves %" PetscInt_FMT
                        ", run solves %" PetscInt_FMT " -> %" PetscInt_FMT "\n",
                        material, (double)(nd / nJ), (double)df, mc1.output_solves - mc0.output_solves, mc0.solves, mc1.solves));
  TG_CHECK(nd <= tol * nJ, "AssembleTangentAt differs from IJacobian by %g of |J|", (double)(nd / nJ));
  TG_CHECK(df == 0, "the residual changed after AssembleTangentAt (by %g)", (double)df);
  TG_CHECK(model.Counters().residuals == before.residuals + 1 && model.Counters().tangent_evals == before.tangent_evals &&
             model.Counters().material_evals == before.material_evals,
           "AssembleTangentAt changed the model's counters");
  TG_CHECK(mc1.solves == mc0.solves && mc1.tangent_solves == mc0.tangent_solves, "AssembleTangentAt counted as the run's work");
  for (Vec *v : {&U, &Z, &F0, &F1}) PetscCall(VecDestroy(v));
  PetscCall(MatDestroy(&J));
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Dense(Mat A, std::vector<PetscScalar> &a, PetscBLASInt *n)
{
  Mat                D;
  PetscInt           m;
  const PetscScalar *v;
  PetscFunctionBeginUser;
  PetscCall(MatConvert(A, MATSEQDENSE, MAT_INITIAL_MATRIX, &D));
  PetscCall(MatGetSize(D, &m, NULL));
  PetscCall(MatDenseGetArrayRead(D, &v));
  a.assign(v, v + m * m); /* column-major */
  PetscCall(MatDenseRestoreArrayRead(D, &v));
  PetscCall(MatDestroy(&D));
  PetscCall(PetscBLASIntCast(m, n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 4. SLEPc against dense LAPACK, on a 8 x 2 cantilever (neo-Hookean, eta = 1) bent by its weight. */
static PetscErrorCode SpectrumCheck()
{
  CoarseModel       model(PETSC_COMM_WORLD);
  CoarseOperators   ops(model);
  PencilEigensolver low(PETSC_COMM_WORLD), high(PETSC_COMM_WORLD);
  DampedModes       damped(PETSC_COMM_WORLD);
  Vec               U;
  PetscBool         ok;
  std::string       why;
  PetscFunctionBeginUser;
  PetscCall(MakeModel(model, "neo_hookean", 8, 2, 400, 100, 0));
  PetscCall(ops.SetUp());
  PetscCall(model.CreateGlobalVector(&U));
  PetscCall(DeformedState(model, U, 0.3, 0.0));
  PetscCall(ops.Assemble(U, true, &ok, &why));
  TG_CHECK(ok, "%s", why.c_str());
  PetscCall(ops.Symmetrize());
  PetscCall(low.SetFromOptions("test_low_", PencilEnd::Lowest, 4, 1e-12));
  PetscCall(high.SetFromOptions("test_high_", PencilEnd::Largest, 1, 1e-12));
  PetscCall(damped.SetFromOptions("test_damped_", 3, 1e-12));
  PetscCall(low.Solve(ops));
  PetscCall(high.Solve(ops));
  PetscCall(damped.Solve(ops));
  /* dense generalized symmetric: K x = lambda M x */
  std::vector<PetscScalar> K, M, C, Kc, Mc;
  PetscBLASInt             n, info, lwork;
  PetscCall(Dense(ops.K(), K, &n));
  PetscCall(Dense(ops.M(), M, &n));
  PetscCall(Dense(ops.C(), C, &n));
  Kc = K;
  Mc = M;
  std::vector<PetscReal>   w(n);
  std::vector<PetscScalar> work(64 * n);
  const PetscBLASInt       one = 1;
  lwork                        = 64 * n;
  LAPACKsygv_(&one, "N", "U", &n, Kc.data(), &n, Mc.data(), &n, w.data(), work.data(), &lwork, &info);
  TG_CHECK(info == 0, "LAPACK sygv failed (%d)", (int)info);
  TG_CHECK((PetscInt)low.Pairs().size() == 4 && high.Pairs().size() == 1, "EPS converged %zu and %zu pairs", low.Pairs().size(), high.Pairs().size());
  for (int k = 0; k < 4; k++) TG_CHECK_CLOSE(low.Pairs()[k].lambda, w[k], 1e-9, 0, "lowest eigenvalue against LAPACK");
  TG_CHECK_CLOSE(high.Pairs()[0].lambda, w[n - 1], 1e-9, 0, "largest eigenvalue against LAPACK");
  for (const Eigenpair &p : low.Pairs()) TG_CHECK(p.residual < 1e-12, "backward error %g", (double)p.residual);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "4. (K, M) on %d dofs: lowest %.10g %.10g, largest %.10g /µs^2 (LAPACK %.10g %.10g, %.10g)\n", (int)n,
                        (double)low.Pairs()[0].lambda, (double)low.Pairs()[1].lambda, (double)high.Pairs()[0].lambda, (double)w[0], (double)w[1],
                        (double)w[n - 1]));
  /* dense quadratic: the companion form [[0, I], [-M^-1 K, -M^-1 C]] */
  {
    const PetscBLASInt        N = 2 * n;
    std::vector<PetscScalar>  Minv(M), B((size_t)N * N, 0), wr(N), wi(N), gwork(8 * N);
    std::vector<PetscBLASInt> piv(n);
    const PetscBLASInt        lw = 8 * N;
    LAPACKgetrf_(&n, &n, Minv.data(), &n, piv.data(), &info);
    TG_CHECK(info == 0, "getrf");
    LAPACKgetri_(&n, Minv.data(), &n, piv.data(), work.data(), &lwork, &info);
    TG_CHECK(info == 0, "getri");
    for (PetscBLASInt i = 0; i < n; i++) {
      B[(size_t)(n + i) * N + i] = 1; /* column n + i, row i */
      for (PetscBLASInt j = 0; j < n; j++) {
        PetscScalar mk = 0, mc = 0;
        for (PetscBLASInt l = 0; l < n; l++) {
          mk += Minv[(size_t)l * n + i] * K[(size_t)j * n + l];
          mc += Minv[(size_t)l * n + i] * C[(size_t)j * n + l];
        }
        B[(size_t)j * N + n + i]       = -mk;
        B[(size_t)(n + j) * N + n + i] = -mc;
      }
    }
    LAPACKgeev_("N", "N", &N, B.data(), &N, wr.data(), wi.data(), NULL, &one, NULL, &one, gwork.data(), &lw, &info);
    TG_CHECK(info == 0, "geev failed (%d)", (int)info);
    std::vector<std::complex<double>> s;
    for (PetscBLASInt k = 0; k < N; k++)
      if (wi[k] >= 0) s.emplace_back(wr[k], wi[k]);
    std::sort(s.begin(), s.end(), [](std::complex<double> a, std::complex<double> b) { return std::abs(a) < std::abs(b); });
    TG_CHECK(damped.Values().size() >= 3, "PEP converged %zu modes", damped.Values().size());
    for (int k = 0; k < 3; k++) {
      const DampedEigenvalue &v = damped.Values()[k];
      TG_CHECK(std::abs(std::complex<double>(v.re, v.im) - s[k]) <= 1e-8 * std::abs(s[k]), "damped eigenvalue %d: %g%+gi vs %g%+gi", k, (double)v.re,
               (double)v.im, s[k].real(), s[k].imag());
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "   damped: s1 = %.10g%+.10gi /µs (companion form %.10g%+.10gi), damping ratio %.4g\n",
                          (double)damped.Values()[0].re, (double)damped.Values()[0].im, s[0].real(), s[0].imag(), (double)damped.Values()[0].Ratio()));
  }
  PetscCall(VecDestroy(&U));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* 5. Write two snapshots, read the second back. */
static PetscErrorCode SnapshotRoundTrip()
{
  CoarseModel           model(PETSC_COMM_WORLD);
  CoarseSnapshotRequest req;
  Vec                   U, V;
  PetscBool             ok;
  PetscReal             t, diff;
  PetscFunctionBeginUser;
  PetscCall(MakeModel(model, "neo_hookean", 3, 2, 300, 200, -0.2));
  PetscCall(model.CreateGlobalVector(&U));
  PetscCall(VecDuplicate(U, &V));
  std::filesystem::create_directories("test_eigen_out");
  {
    CoarseFieldsWriter w;
    PetscCall(w.Open(model, "test_eigen_out", "coarse"));
    PetscCall(DeformedState(model, U, 0.01, 0.0));
    PetscCall(model.EvaluateCellStress(U, &ok));
    PetscCall(w.Write(model, U, 0.0));
    PetscCall(DeformedState(model, U, 0.03, 0.0));
    PetscCall(model.EvaluateCellStress(U, &ok));
    PetscCall(w.Write(model, U, 7.5));
  }
  req.path     = "test_eigen_out/coarse.h5";
  req.has_time = true;
  req.time     = 7.5;
  PetscCall(ReadCoarseSnapshot(model, req, V, &t));
  PetscCall(VecAXPY(V, -1.0, U));
  PetscCall(VecNorm(V, NORM_INFINITY, &diff));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "5. snapshot at t = %g read back: |difference| = %g\n", (double)t, (double)diff));
  TG_CHECK(t == 7.5 && diff == 0, "the snapshot read back differs by %g (t = %g)", (double)diff, (double)t);
  /* a snapshot with a non-finite displacement is refused, naming the option */
  {
    PetscErrorCode ierr;
    const char    *text     = NULL;
    char          *specific = NULL;
    { /* written and closed before it is read (an open writer's file may not hold its snapshot yet) */
      CoarseFieldsWriter w;
      PetscCall(w.Open(model, "test_eigen_out", "nan"));
      PetscCall(VecSet(U, NAN));
      PetscCall(model.EvaluateCellStress(U, &ok));
      PetscCall(w.Write(model, U, 1.0));
    }
    req.path     = "test_eigen_out/nan.h5";
    req.has_time = false;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = ReadCoarseSnapshot(model, req, V, &t);
    PetscCall(PetscPopErrorHandler());
    TG_CHECK(ierr != 0, "a snapshot with NaN displacements was read");
    PetscCall(PetscErrorMessage(ierr, &text, &specific));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "   a NaN snapshot is refused: %s\n", specific));
    TG_CHECK(specific && std::strstr(specific, "-snapshot_file = test_eigen_out/nan.h5") && std::strstr(specific, "not finite"), "message: %s",
             specific ? specific : "");
  }
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&V));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(TurgorRegisterAll());
  PetscCall(AcousticTensorCheck());
  PetscCall(DopriBoundaryCheck());
  PetscCall(TangentAtCheck("neo_hookean", 1e-14));
  PetscCall(TangentAtCheck("rve", 1e-6));
  PetscCall(SpectrumCheck());
  PetscCall(SnapshotRoundTrip());
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "test_eigen: all checks passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
