#include <turgor/physics/cell_pressure.h>
#include <turgor/core/geometry.h>
#include <turgor/core/vector_clones.h>
#include <cmath>

namespace turgor {

/* Names in the order of CellPressure::Law (read as a PetscInt: PETSc 3.18's PetscEnum holds only 0 and 1). */
static const char *const kLaws[] = {"constant", "gas", "elastic"};

PetscErrorCode CellPressure::SetFromOptions(MPI_Comm comm, const TermContext &ctx)
{
  PetscFunctionBeginUser;
  PetscInt e = (PetscInt)law;
  PetscOptionsBegin(comm, "pressure_", "Pressure of closed polygonal cells", "turgor");
  PetscCall(
    TurgorOptionsEList(ctx.params, "-law", "Pressure law: constant p0, gas p0 A0/A, elastic p0 - K (A - A0)/A0", "CellPressure", kLaws, 3, kLaws[e], &e, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-p0", "Reference pressure p0 [N/m]", "CellPressure", p0, &p0, NULL));
  PetscCall(TurgorOptionsReal(ctx.params, "-bulk_modulus", "Bulk modulus K of the elastic law [N/m]", "CellPressure", bulk_modulus, &bulk_modulus, NULL));
  PetscCall(
    TurgorOptionsReal(ctx.params, "-ramp_time", "The turgor builds up linearly over this time [µs]; 0: at once", "CellPressure", ramp_time, &ramp_time, NULL));
  PetscOptionsEnd();
  law = (Law)e;
  PetscCheck(std::isfinite(p0), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -pressure_p0 = %g: must be finite", (double)p0);
  PetscCheck(law != GAS || p0 >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -pressure_p0 = %g: a gas pressure must be >= 0", (double)p0);
  PetscCheck(ramp_time >= 0 && std::isfinite(ramp_time), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -pressure_ramp_time = %g: must be finite and >= 0",
             (double)ramp_time);
  PetscCheck(bulk_modulus >= 0 && std::isfinite(bulk_modulus), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -pressure_bulk_modulus = %g: must be finite and >= 0",
             (double)bulk_modulus);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellPressure::SetUp(const ParticleSet &P, NeighbourSearch &nb)
{
  PetscFunctionBeginUser;
  closed_.clear();
  consecutive_.clear();
  for (size_t c = 0; c < P.OwnedPolygons(); c++) { /* this rank's cells (particles.h) */
    const std::vector<PetscInt> &nodes = P.polygons[c].nodes;
    if (P.polygons[c].open || nodes.size() < 3) continue;
    bool in_order = true;
    for (size_t k = 1; k < nodes.size(); k++) in_order = in_order && nodes[k] == nodes[0] + (PetscInt)k;
    closed_.push_back((PetscInt)c);
    consecutive_.push_back(in_order);
  }
  A0_.assign(P.polygons.size(), 0.0);
  P_        = &P;
  have_ref_ = false;
  PetscFunctionReturn(PETSC_SUCCESS);
}

void CellPressure::SetReference(const PetscReal *X)
{
  for (PetscInt c : closed_) A0_[c] = PolygonArea(P_->polygons[c].nodes, X);
  have_ref_ = true;
}

PetscReal CellPressure::Pressure(PetscReal A, PetscReal A0) const
{
  switch (law) {
  case GAS:
    return p0 * A0 / A;
  case ELASTIC:
    return p0 - bulk_modulus * (A - A0) / A0;
  default:
    return p0;
  }
}

/* The pressure forces of a closed cell whose N nodes are numbered consecutively, X = x + 2 i0 and
   F = f + 2 i0: the general loop's bits (edge k's force hp (dy, -dx) added to node k, then to node
   k + 1, so that node m gets (f_m + F_(m-1)) + F_m and node 0 (f_0 + F_0) + F_(N-1)), each node written
   once with both its edges' forces: no index reads, no chain of read-modify-writes through f from one
   edge to the next, and an interior loop the compiler vectorises. */
TURGOR_VECTOR_CLONES
static void ConsecutiveRingForces(const PetscReal *__restrict X, size_t N, PetscReal hp, PetscReal *__restrict F)
{
  auto edge_x = [&](size_t k, size_t l) { return hp * (X[2 * l + 1] - X[2 * k + 1]); };
  auto edge_y = [&](size_t k, size_t l) { return -hp * (X[2 * l] - X[2 * k]); };
  F[0]        = (F[0] + edge_x(0, 1)) + edge_x(N - 1, 0);
  F[1]        = (F[1] + edge_y(0, 1)) + edge_y(N - 1, 0);
  for (size_t m = 1; m + 1 < N; m++) {
    F[2 * m]     = (F[2 * m] + hp * (X[2 * m + 1] - X[2 * m - 1])) + hp * (X[2 * m + 3] - X[2 * m + 1]);
    F[2 * m + 1] = (F[2 * m + 1] + -hp * (X[2 * m] - X[2 * m - 2])) + -hp * (X[2 * m + 2] - X[2 * m]);
  }
  const size_t m = N - 1;
  F[2 * m]       = (F[2 * m] + edge_x(m - 1, m)) + edge_x(m, 0);
  F[2 * m + 1]   = (F[2 * m + 1] + edge_y(m - 1, m)) + edge_y(m, 0);
}

PetscErrorCode CellPressure::AddForces(const ForceInput &in, PetscReal *f, PetscReal *virial)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  const PetscReal  *x       = in.x;
  const ForceGrain &grain   = in.Grain();
  const bool        rounded = grain.On(); /* once: f's stores could alias the grain */
  PetscReal         w[4]    = {0, 0, 0, 0};
  for (size_t q = 0; q < closed_.size(); q++) {
    const PetscInt     c    = closed_[q];
    const PolygonCell &C    = in.P->polygons[c];
    const size_t       N    = C.nodes.size();
    const bool         fast = consecutive_[q] && !rounded && !virial; /* the rounded shares and the virial: the general loop */
    const PetscReal   *X    = x + 2 * C.nodes[0];
    const PetscReal    A    = fast ? PolygonSignedArea(N, [X](size_t k) { return Point2{X[2 * k], X[2 * k + 1]}; }) : PolygonArea(C.nodes, x);
    PetscCheck(law != GAS || A > 0, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "Cell %" PetscInt_FMT " has area %g: the gas law needs A > 0 (inverted cell)", c,
               (double)A);
    const PetscReal hp = 0.5 * Scale(in.t) * Pressure(A, A0_[c]);
    if (fast) {
      ConsecutiveRingForces(X, N, hp, f + 2 * C.nodes[0]);
      continue;
    }
    for (size_t k = 0; k < N; k++) {                                     /* bar i -> j, CCW: outward normal x length = (dy, -dx) */
      const PetscInt i = C.nodes[k], j = C.nodes[k + 1 < N ? k + 1 : 0]; /* not (k + 1) % N: a division per node */
      PetscReal      fx = hp * (x[2 * j + 1] - x[2 * i + 1]), fy = -hp * (x[2 * j] - x[2 * i]);
      if (rounded) grain(fx, fy);
      f[2 * i] += fx;
      f[2 * i + 1] += fy;
      f[2 * j] += fx;
      f[2 * j + 1] += fy;
      if (virial) { /* -sum f (x) x; each cell's forces sum to zero, so this is translation invariant */
        const PetscReal sx = x[2 * i] + x[2 * j], sy = x[2 * i + 1] + x[2 * j + 1];
        w[0] -= fx * sx;
        w[1] -= fx * sy;
        w[2] -= fy * sx;
        w[3] -= fy * sy;
      }
    }
  }
  if (virial)
    for (int q = 0; q < 4; q++) virial[q] += w[q];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The turgor's stiffness on a cell's nodes, at the full pressure (a build-up ramp reaches it):
   -dp/dA g g^T with g = grad A, a rank-one matrix whose largest eigenvalue against the masses is
   exactly -dp/dA sum |g_i|^2 / m_i (the elastic law's K / A0, the gas law's p0 A0 / A^2), and
   p d^2A/dx^2, whose rows hold two entries of 1/2 (Gershgorin: |p| / m). The largest over the cells
   at the state given; a cell's nodes are all on the rank that has the cell. */
PetscErrorCode CellPressure::AddTimeStepLimits(const ForceInput &in, std::vector<TimeStepLimit> &limits)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  const PetscReal *x  = in.x;
  PetscReal        w2 = 0;
  for (PetscInt c : closed_) {
    const PolygonCell &C = in.P->polygons[c];
    const size_t       N = C.nodes.size();
    const PetscReal    A = PolygonArea(C.nodes, x), A0 = A0_[c];
    const PetscReal    dpdA = law == ELASTIC ? bulk_modulus / A0 : law == GAS && A > 0 ? p0 * A0 / (A * A) : 0; /* -dp/dA */
    PetscReal          sum = 0, mmin = PETSC_MAX_REAL;
    for (size_t k = 0; k < N; k++) {
      const PetscInt  i = C.nodes[k], h = C.nodes[(k + N - 1) % N], j = C.nodes[(k + 1) % N];
      const PetscReal gx = 0.5 * (x[2 * j + 1] - x[2 * h + 1]), gy = 0.5 * (x[2 * h] - x[2 * j]), m = in.P->mass[i];
      sum += (gx * gx + gy * gy) / m;
      mmin = std::min(mmin, m);
    }
    w2 = std::max(w2, std::fabs(dpdA) * sum + std::fabs(Pressure(A, A0)) / mmin);
  }
  if (w2 > 0) {
    char why[160];
    PetscCall(PetscSNPrintf(why, sizeof why, "pressure: omega_max <= %.4g /µs (law %s: -dp/dA |grad A|^2 / m + |p| / m, %zu cells)", (double)std::sqrt(w2),
                            kLaws[law], closed_.size()));
    limits.push_back({2.0 / std::sqrt(w2), why});
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* E = -int_{A0}^{A} p da: constant -p0 (A - A0); gas -p0 A0 ln(A/A0); elastic
   -p0 (A - A0) + K (A - A0)^2 / (2 A0). */
PetscErrorCode CellPressure::Energy(const ForceInput &in, PetscReal *E, PetscBool *has)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  *E = 0;
  for (PetscInt c : closed_) {
    const PetscReal A = PolygonArea(in.P->polygons[c].nodes, in.x), A0 = A0_[c], dA = A - A0;
    switch (law) {
    case GAS:
      *E -= p0 * A0 * std::log(A / A0);
      break;
    case ELASTIC:
      *E += -p0 * dA + 0.5 * bulk_modulus * dA * dA / A0;
      break;
    default:
      *E -= p0 * dA;
    }
  }
  *E *= Scale(in.t);
  *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* dE/dt at fixed positions during the ramp: E0(x) / T (E0 the energy at the full turgor). */
PetscReal CellPressure::ExplicitTimePower(const ForceInput &in)
{
  if (!(ramp_time > 0 && in.t < ramp_time)) return 0;
  ForceInput full = in;
  full.t          = ramp_time;
  PetscReal E;
  PetscBool has;
  PetscCallAbort(PETSC_COMM_SELF, Energy(full, &E, &has));
  return E / ramp_time;
}

/* The pressure of every closed polygon (0 for one with fewer than 3 nodes, which has none). */
PetscErrorCode CellPressure::OutputFields(const ForceInput &in, std::vector<TermField> &fields)
{
  PetscFunctionBeginUser;
  if (!have_ref_) SetReference(in.x);
  TermField F{TermField::CELL, "pressure", "N/m", {}};
  for (size_t c = 0; c < in.P->polygons.size(); c++) {
    const PolygonCell &C = in.P->polygons[c];
    if (C.open) continue;
    F.values.push_back(C.nodes.size() >= 3 ? Scale(in.t) * Pressure(PolygonArea(C.nodes, in.x), A0_[c]) : 0.0);
  }
  fields.push_back(std::move(F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CellPressure::View(PetscViewer viewer) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(viewer, "pressure: %zu closed cells, law %s, p0 = %g N/m, K = %g N/m\n", closed_.size(), kLaws[law], (double)p0,
                                   (double)bulk_modulus));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
