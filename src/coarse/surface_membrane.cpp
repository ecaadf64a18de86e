#include <turgor/coarse/surface_membrane.h>
#include <cmath>

namespace turgor {

PetscErrorCode SurfaceMembrane::SetFromOptions(MPI_Comm comm, ParameterList *params)
{
  char      name[64];
  PetscInt  v[8], n = 8;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(name, label.c_str(), sizeof name));
  PetscOptionsBegin(comm, "coarse_skin_", "Membrane along boundary faces of the coarse mesh (a surface stiffness the periodic RVE lacks)", "turgor");
  PetscCall(TurgorOptionsReal(params, "-stiffness", "Axial stiffness EA of the membrane along the faces [µN]; 0: none", "SurfaceMembrane", stiffness,
                              &stiffness, NULL));
  PetscCall(TurgorOptionsString(params, "-label", "Label of the faces that carry it", "SurfaceMembrane", name, name, sizeof name, NULL));
  PetscCall(PetscOptionsIntArray("-values", "Label values that carry it (box: 1 bottom, 2 right, 3 top, 4 left; default 1,3)", "SurfaceMembrane", v, &n, &set));
  PetscOptionsEnd();
  PetscCheck(stiffness >= 0 && std::isfinite(stiffness), comm, PETSC_ERR_ARG_OUTOFRANGE, "Option -coarse_skin_stiffness = %g: must be >= 0 (0: none)",
             (double)stiffness);
  PetscCheck(!set || (n > 0 && n < 8), comm, PETSC_ERR_ARG_SIZ, "Option -coarse_skin_values: give 1 to 7 label values");
  if (set) values.assign(v, v + n);
  label = name;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SurfaceMembrane::SetUp(DM dm, PetscInt c_start, PetscInt c_end, PetscInt edge_nodes)
{
  DMLabel  l;
  PetscInt found = 0;
  PetscFunctionBeginUser;
  edges_.clear();
  nodes_ = edge_nodes;
  if (!Active()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMGetLabel(dm, label.c_str(), &l));
  PetscCheck(l, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG, "Option -coarse_skin_label = %s: the mesh has no such label", label.c_str());
  PetscInt e_start, e_end;
  PetscCall(DMPlexGetDepthStratum(dm, 1, &e_start, &e_end));
  for (PetscInt value : values) {
    IS              is;
    const PetscInt *pts;
    PetscInt        np;
    PetscCall(DMLabelGetStratumIS(l, value, &is));
    if (!is) continue;
    PetscCall(ISGetLocalSize(is, &np));
    PetscCall(ISGetIndices(is, &pts));
    for (PetscInt k = 0; k < np; k++) {
      const PetscInt  e = pts[k];
      const PetscInt *supp;
      PetscInt        ns;
      if (e < e_start || e >= e_end) continue; /* the label's vertices */
      PetscCall(DMPlexGetSupportSize(dm, e, &ns));
      PetscCall(DMPlexGetSupport(dm, e, &supp));
      if (ns == 1 && supp[0] >= c_start && supp[0] < c_end) edges_.push_back(e);
    }
    PetscCall(ISRestoreIndices(is, &pts));
    PetscCall(ISDestroy(&is));
  }
  found = (PetscInt)edges_.size();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCheck(found > 0, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG,
             "Options -coarse_skin_label %s / -coarse_skin_values: no boundary edge carries the membrane of -coarse_skin_stiffness %g", label.c_str(),
             (double)stiffness);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Closure order: Q2, the edge's own node then its two vertices; Q1, the two vertices. The section
   holds [u_x, u_y, v_x, v_y] per node; the coordinates are the vertices' (straight edges: the middle
   node halfway). */
PetscErrorCode SurfaceMembrane::EdgeNodes(DM dm, Vec Uloc, PetscInt e, PetscReal *X, PetscReal *x) const
{
  DM           cdm;
  Vec          coords;
  PetscScalar *c = NULL, *u = NULL;
  PetscInt     nc = 0, nu = 0;
  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateDM(dm, &cdm));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMPlexVecGetClosure(cdm, NULL, coords, e, &nc, &c));
  PetscCall(DMPlexVecGetClosure(dm, NULL, Uloc, e, &nu, &u));
  PetscCheck(nc == 4 && nu == 4 * nodes_, PETSC_COMM_SELF, PETSC_ERR_PLIB,
             "surface membrane: edge %" PetscInt_FMT " has %" PetscInt_FMT " coordinates and %" PetscInt_FMT " dofs", e, nc, nu);
  const int v0 = nodes_ == 3 ? 1 : 0; /* the first vertex's place among the nodes */
  for (int d = 0; d < 2; d++) {
    X[2 * v0 + d]       = PetscRealPart(c[d]);
    X[2 * (v0 + 1) + d] = PetscRealPart(c[2 + d]);
    if (nodes_ == 3) X[d] = 0.5 * (X[2 + d] + X[4 + d]);
  }
  for (PetscInt a = 0; a < nodes_; a++)
    for (int d = 0; d < 2; d++) x[2 * a + d] = X[2 * a + d] + PetscRealPart(u[4 * a + d]);
  PetscCall(DMPlexVecRestoreClosure(cdm, NULL, coords, e, &nc, &c));
  PetscCall(DMPlexVecRestoreClosure(dm, NULL, Uloc, e, &nu, &u));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* dN/dxi of the edge's nodes at xi, in closure order */
static void EdgeDerivatives(PetscInt nodes, PetscReal xi, PetscReal dN[3])
{
  if (nodes == 3) {
    dN[0] = -2 * xi;
    dN[1] = xi - 0.5;
    dN[2] = xi + 0.5;
  } else {
    dN[0] = -0.5;
    dN[1] = 0.5;
  }
}

/* Gauss points and weights on [-1, 1]: 2 for Q1's edges, 3 for Q2's (N_i' N_j' of degree 2) */
static int EdgeRule(PetscInt nodes, const PetscReal **xi, const PetscReal **w)
{
  static const PetscReal x2[2] = {-0.57735026918962576, 0.57735026918962576}, w2[2] = {1, 1};
  static const PetscReal x3[3] = {-0.77459666924148338, 0, 0.77459666924148338}, w3[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  *xi = nodes == 3 ? x3 : x2;
  *w  = nodes == 3 ? w3 : w2;
  return nodes == 3 ? 3 : 2;
}

/* The edge's kinematics at its Gauss points: weights, dN/dxi, |X'| and x' */
PetscErrorCode SurfaceMembrane::EdgeKinematics(DM dm, Vec Uloc, PetscInt e, EdgeState *k) const
{
  PetscReal        X[6], x[6];
  const PetscReal *xi, *w;
  PetscFunctionBeginUser;
  PetscCall(EdgeNodes(dm, Uloc, e, X, x));
  k->points = EdgeRule(nodes_, &xi, &w);
  for (int g = 0; g < k->points; g++) {
    PetscReal Xp[2] = {0, 0};
    EdgeDerivatives(nodes_, xi[g], k->dN[g]);
    k->w[g]     = w[g];
    k->xp[g][0] = k->xp[g][1] = 0;
    for (PetscInt a = 0; a < nodes_; a++)
      for (int d = 0; d < 2; d++) Xp[d] += k->dN[g][a] * X[2 * a + d], k->xp[g][d] += k->dN[g][a] * x[2 * a + d];
    k->lX[g] = std::hypot(Xp[0], Xp[1]);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SurfaceMembrane::AddForce(DM dm, Vec Uloc, Vec Floc) const
{
  PetscFunctionBeginUser;
  for (PetscInt e : edges_) {
    EdgeState k;
    PetscReal fe[12] = {0};
    PetscCall(EdgeKinematics(dm, Uloc, e, &k));
    for (int g = 0; g < k.points; g++) {
      const PetscReal lx = std::hypot(k.xp[g][0], k.xp[g][1]), N = stiffness * (lx / k.lX[g] - 1);
      for (PetscInt a = 0; a < nodes_; a++)
        for (int d = 0; d < 2; d++) fe[4 * a + 2 + d] += k.w[g] * N * (k.xp[g][d] / lx) * k.dN[g][a];
    }
    PetscCall(DMPlexVecSetClosure(dm, NULL, Floc, e, fe, ADD_VALUES));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SurfaceMembrane::AddStiffness(DM dm, Vec Uloc, Mat J) const
{
  PetscFunctionBeginUser;
  const PetscInt ne = 4 * nodes_;
  for (PetscInt e : edges_) {
    EdgeState k;
    PetscReal ke[144] = {0};
    PetscCall(EdgeKinematics(dm, Uloc, e, &k));
    for (int g = 0; g < k.points; g++) {
      const PetscReal lx = std::hypot(k.xp[g][0], k.xp[g][1]), t[2] = {k.xp[g][0] / lx, k.xp[g][1] / lx};
      const PetscReal axial = stiffness / k.lX[g], lateral = stiffness * (lx / k.lX[g] - 1) / lx;
      for (PetscInt a = 0; a < nodes_; a++)
        for (PetscInt b = 0; b < nodes_; b++)
          for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++)
              ke[(4 * a + 2 + i) * ne + 4 * b + j] += k.w[g] * k.dN[g][a] * k.dN[g][b] * (axial * t[i] * t[j] + lateral * ((i == j ? 1.0 : 0.0) - t[i] * t[j]));
    }
    PetscCall(DMPlexMatSetClosure(dm, NULL, NULL, J, e, ke, ADD_VALUES));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace turgor
