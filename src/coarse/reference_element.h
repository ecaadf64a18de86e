#pragma once
/* The coarse element as the model uses it: a Lagrange quadrilateral (Q1 or Q2) on the reference
   square [-1, 1]^2, tabulated at the material points of its quadrature rule and at the points of
   its mass rule. The nodes come in DMPlex's closure order of the element's PetscFE section, so that
   node a is the a-th block of 4 values [ux, uy, vx, vy] of DMPlexVecGetClosure:
     Q1: the 4 vertices, counter-clockwise from (-1, -1);
     Q2: the centre, the 4 edge midpoints (bottom, right, top, left), then the 4 vertices.
   The geometry is always the bilinear map of the 4 vertices (the coordinate section's closure): Q2
   is subparametric, exact for straight-sided quadrilaterals (boxes, Gmsh files of 4-node quads). */
#include <turgor/coarse/coarse_model.h>
#include <string>
#include <vector>

namespace turgor {

/* What a material point contributes to its element's internal force: its whole Cauchy stress, its
   deviator sigma - tr(sigma)/2 I, or its pressure part tr(sigma)/2 I. */
enum class PointPart {
  Whole,
  Deviatoric,
  Pressure
};

struct ReferenceElement {
  std::string              element;     /* -coarse_element: q1, q2 */
  std::string              rule;        /* -coarse_quadrature: sri, full */
  std::string              description; /* for reports */
  PetscInt                 degree = 1;  /* of the Lagrange PetscFE of the section */
  PetscInt                 nodes  = 4;  /* per element, closure order */
  PetscInt                 points = 0;  /* material points per element */
  std::vector<PetscReal>   xi;          /* [points][2] on the reference square */
  std::vector<PetscReal>   w;           /* [points] weights (sum 4 for each part) */
  std::vector<PointPart>   part;        /* [points] */
  std::vector<std::string> where;       /* [points] for failure reports */
  std::vector<PetscReal>   dN;          /* [points][nodes][2] dN_a/dxi */
  PetscInt                 mass_points = 0;
  std::vector<PetscReal>   mass_xi, mass_w, mass_N; /* [mass_points][2], [mass_points], [mass_points][nodes] */
};

/* The element and rule of -coarse_element / -coarse_quadrature, tabulated (q1_element.h,
   q2_element.h). */
PetscErrorCode CreateReferenceElement(CoarseElement element, CoarseQuadrature rule, ReferenceElement *ref);

/* The bilinear map of the vertices X[4][2] (counter-clockwise) at (xi, eta): its inverse Jacobian
   Ji = (dX/dxi)^-1 and det(dX/dxi). */
inline PetscReal GeometryMap(const PetscReal X[4][2], PetscReal xi, PetscReal eta, PetscReal Ji[2][2])
{
  static const PetscReal v[4][2] = {
    {-1, -1},
    {1,  -1},
    {1,  1 },
    {-1, 1 }
  };
  PetscReal J[2][2] = {
    {0, 0},
    {0, 0}
  };
  for (int a = 0; a < 4; a++) {
    const PetscReal d[2] = {0.25 * v[a][0] * (1 + v[a][1] * eta), 0.25 * v[a][1] * (1 + v[a][0] * xi)};
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) J[i][j] += X[a][i] * d[j]; /* J_ij = dX_i / dxi_j */
  }
  const PetscReal det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  Ji[0][0]            = J[1][1] / det;
  Ji[0][1]            = -J[0][1] / det;
  Ji[1][0]            = -J[1][0] / det;
  Ji[1][1]            = J[0][0] / det;
  return det;
}

} // namespace turgor
