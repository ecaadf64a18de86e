#pragma once
/* Small 2 x 2 tensors for material points: deformation gradients, their rates, Cauchy stresses. */
#include <turgor/core/petsc_compat.h>
#include <cmath>

namespace turgor {

struct Tensor2 {
  PetscReal a[2][2] = {
    {0, 0},
    {0, 0}
  };

  static Tensor2 Identity()
  {
    return {
      {{1, 0}, {0, 1}}
    };
  }
  static Tensor2 Zero() { return {}; }
  static Tensor2 Rotation(PetscReal theta)
  {
    return {
      {{std::cos(theta), -std::sin(theta)}, {std::sin(theta), std::cos(theta)}}
    };
  }
  static Tensor2 Unit(int k, int l) /* e_k (x) e_l */
  {
    Tensor2 E;
    E.a[k][l] = 1;
    return E;
  }
  PetscReal       &operator()(int i, int j) { return a[i][j]; }
  const PetscReal &operator()(int i, int j) const { return a[i][j]; }
  PetscReal        Det() const { return a[0][0] * a[1][1] - a[0][1] * a[1][0]; }
  PetscReal        Trace() const { return a[0][0] + a[1][1]; }
  PetscReal        Norm() const { return std::sqrt(a[0][0] * a[0][0] + a[0][1] * a[0][1] + a[1][0] * a[1][0] + a[1][1] * a[1][1]); }
  Tensor2          T() const
  {
    return {
      {{a[0][0], a[1][0]}, {a[0][1], a[1][1]}}
    };
  }
  Tensor2 Inverse() const
  {
    const PetscReal d = Det();
    return {
      {{a[1][1] / d, -a[0][1] / d}, {-a[1][0] / d, a[0][0] / d}}
    };
  }
  Tensor2 Sym() const
  {
    return {
      {{a[0][0], 0.5 * (a[0][1] + a[1][0])}, {0.5 * (a[0][1] + a[1][0]), a[1][1]}}
    };
  }
  void Apply(const PetscReal x[2], PetscReal y[2]) const /* y = A x */
  {
    y[0] = a[0][0] * x[0] + a[0][1] * x[1];
    y[1] = a[1][0] * x[0] + a[1][1] * x[1];
  }
};

inline Tensor2 operator*(const Tensor2 &A, const Tensor2 &B)
{
  Tensor2 C;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) C.a[i][j] = A.a[i][0] * B.a[0][j] + A.a[i][1] * B.a[1][j];
  return C;
}
inline Tensor2 operator+(const Tensor2 &A, const Tensor2 &B)
{
  Tensor2 C;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) C.a[i][j] = A.a[i][j] + B.a[i][j];
  return C;
}
inline Tensor2 operator-(const Tensor2 &A, const Tensor2 &B)
{
  Tensor2 C;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) C.a[i][j] = A.a[i][j] - B.a[i][j];
  return C;
}
inline Tensor2 operator*(PetscReal s, const Tensor2 &A)
{
  Tensor2 C;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++) C.a[i][j] = s * A.a[i][j];
  return C;
}

} // namespace turgor
