#pragma once
/* Bilinear quadrilateral (Q1) element on the reference square [-1, 1]^2: shape functions, their
   reference-configuration gradients at a point, and its quadrature rules. Vertices come
   counter-clockwise from DMPlex's closure: (-1,-1), (1,-1), (1,1), (-1,1). The formulas are the
   textbook ones, written out (rather than tabulated from a PetscFE as Q2 is) so that the seed's
   element keeps its bit-for-bit results. */
#include "reference_element.h"
#include <cmath>

namespace turgor {
namespace q1 {

static const PetscReal kXi[4][2] = {
  {-1, -1},
  {1,  -1},
  {1,  1 },
  {-1, 1 }
};

inline void Shape(PetscReal xi, PetscReal eta, PetscReal N[4])
{
  for (int a = 0; a < 4; a++) N[a] = 0.25 * (1 + kXi[a][0] * xi) * (1 + kXi[a][1] * eta);
}

/* dN_a/dxi at (xi, eta). */
inline void ReferenceGradients(PetscReal xi, PetscReal eta, PetscReal dNr[4][2])
{
  for (int a = 0; a < 4; a++) {
    dNr[a][0] = 0.25 * kXi[a][0] * (1 + kXi[a][1] * eta);
    dNr[a][1] = 0.25 * kXi[a][1] * (1 + kXi[a][0] * xi);
  }
}

/* Gradients dN_a/dX at (xi, eta) for vertex coordinates X[4][2]; returns det(dX/dxi). */
inline PetscReal Gradients(const PetscReal X[4][2], PetscReal xi, PetscReal eta, PetscReal dN[4][2])
{
  PetscReal       dNr[4][2], Ji[2][2];
  const PetscReal det = GeometryMap(X, xi, eta, Ji);
  ReferenceGradients(xi, eta, dNr);
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 2; i++) dN[a][i] = dNr[a][0] * Ji[0][i] + dNr[a][1] * Ji[1][i];
  return det;
}

static const PetscReal kG = 0.57735026918962576451; /* 1/sqrt(3) */

/* sri: 2 x 2 Gauss points (deviatoric stress) and the centre (pressure), TW 562 §5's selective
   reduced integration, 5 points. full: the whole stress at the 2 x 2 Gauss points, 4 points. The
   Gauss points come first, in the same order, in both. */
static const PetscReal kSRIXi[5][2] = {
  {-kG, -kG},
  {kG,  -kG},
  {kG,  kG },
  {-kG, kG },
  {0,   0  }
};
static const PetscReal   kSRIW[5]     = {1, 1, 1, 1, 4};
static const char *const kSRIWhere[5] = {"Gauss point 1", "Gauss point 2", "Gauss point 3", "Gauss point 4", "centre"};

/* 3 x 3 Gauss rule for the consistent mass matrix (exact for N_a N_b det J on any quad). */
static const PetscReal kG3[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
static const PetscReal kW3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

/* The element tabulated at the points of `rule` (sri or full) and of the mass rule. */
inline void Tabulate(CoarseQuadrature rule, ReferenceElement *ref)
{
  const bool sri   = rule == CoarseQuadrature::SRI;
  ref->element     = "q1";
  ref->rule        = sri ? "sri" : "full";
  ref->description = sri ? "Q1, selective reduced integration (deviator at the 2 x 2 Gauss points, pressure at the centre)" : "Q1, full 2 x 2 integration";
  ref->degree      = 1;
  ref->nodes       = 4;
  ref->points      = sri ? 5 : 4;
  ref->xi.clear();
  ref->w.clear();
  ref->part.clear();
  ref->where.clear();
  ref->dN.clear();
  for (int q = 0; q < ref->points; q++) {
    PetscReal dNr[4][2];
    ref->xi.insert(ref->xi.end(), {kSRIXi[q][0], kSRIXi[q][1]});
    ref->w.push_back(kSRIW[q]);
    ref->part.push_back(!sri ? PointPart::Whole : q < 4 ? PointPart::Deviatoric : PointPart::Pressure);
    ref->where.push_back(kSRIWhere[q]);
    ReferenceGradients(kSRIXi[q][0], kSRIXi[q][1], dNr);
    for (int a = 0; a < 4; a++) ref->dN.insert(ref->dN.end(), {dNr[a][0], dNr[a][1]});
  }
  ref->mass_points = 9;
  ref->mass_xi.clear();
  ref->mass_w.clear();
  ref->mass_N.clear();
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      PetscReal N[4];
      Shape(kG3[i], kG3[j], N);
      ref->mass_xi.insert(ref->mass_xi.end(), {kG3[i], kG3[j]});
      ref->mass_w.push_back(kW3[i] * kW3[j]);
      ref->mass_N.insert(ref->mass_N.end(), N, N + 4);
    }
}

} // namespace q1
} // namespace turgor
