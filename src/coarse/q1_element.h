#pragma once
/* Bilinear quadrilateral (Q1) element on the reference square [-1, 1]^2: shape functions, their
   reference-configuration gradients at a point, and the quadrature rules of the coarse model.
   Vertices come counter-clockwise from DMPlex's closure: (-1,-1), (1,-1), (1,1), (-1,1). */
#include <turgor/core/tensor2.h>
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

/* Gradients dN_a/dX at (xi, eta) for vertex coordinates X[4][2]; returns det(dX/dxi). */
inline PetscReal Gradients(const PetscReal X[4][2], PetscReal xi, PetscReal eta, PetscReal dN[4][2])
{
  PetscReal dNr[4][2], J[2][2] = {
                         {0, 0},
                         {0, 0}
  };
  for (int a = 0; a < 4; a++) {
    dNr[a][0] = 0.25 * kXi[a][0] * (1 + kXi[a][1] * eta);
    dNr[a][1] = 0.25 * kXi[a][1] * (1 + kXi[a][0] * xi);
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) J[i][j] += X[a][i] * dNr[a][j]; /* J_ij = dX_i / dxi_j */
  }
  const PetscReal det      = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  const PetscReal Ji[2][2] = {
    {J[1][1] / det,  -J[0][1] / det},
    {-J[1][0] / det, J[0][0] / det }
  };
  for (int a = 0; a < 4; a++)
    for (int i = 0; i < 2; i++) dN[a][i] = dNr[a][0] * Ji[0][i] + dNr[a][1] * Ji[1][i];
  return det;
}

/* What a material point contributes to its element's internal force: its whole Cauchy stress, its
   deviator sigma - tr(sigma)/2 I, or its pressure part tr(sigma)/2 I. */
enum class PointPart {
  Whole,
  Deviatoric,
  Pressure
};

/* A quadrature rule of the coarse element: its material points on the reference square, their
   weights and parts, and their names for failure reports. */
struct Rule {
  const char *name;        /* the -coarse_quadrature value */
  const char *description; /* for reports */
  int         points;      /* material points per element */
  const PetscReal (*xi)[2];
  const PetscReal   *w;
  const PointPart   *part;
  const char *const *where;
};

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
static const PointPart   kSRIPart[5]  = {PointPart::Deviatoric, PointPart::Deviatoric, PointPart::Deviatoric, PointPart::Deviatoric, PointPart::Pressure};
static const char *const kSRIWhere[5] = {"Gauss point 1", "Gauss point 2", "Gauss point 3", "Gauss point 4", "centre"};
static const PointPart   kFullPart[4] = {PointPart::Whole, PointPart::Whole, PointPart::Whole, PointPart::Whole};

static const Rule kRules[2] = {
  {"sri",  "selective reduced integration", 5, kSRIXi, kSRIW, kSRIPart,  kSRIWhere},
  {"full", "full 2 x 2 integration",        4, kSRIXi, kSRIW, kFullPart, kSRIWhere}
};

/* 3 x 3 Gauss rule for the consistent mass matrix (exact for N_a N_b det J on any quad). */
static const PetscReal kG3[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};
static const PetscReal kW3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

} // namespace q1
} // namespace turgor
