#include "vpRigidTransform.h"

#include "vpInputError.h" // NumberText

#include <vtkMath.h>
#include <vtkMatrix4x4.h>

#include <algorithm>
#include <cmath>

namespace vp
{
Matrix4 MultiplyTransforms(const Matrix4& a, const Matrix4& b)
{
  Matrix4 m{};
  vtkMatrix4x4::Multiply4x4(a.data(), b.data(), m.data());
  return m;
}

Matrix4 InvertTransform(const Matrix4& m)
{
  Matrix4 inverse{};
  vtkMatrix4x4::Invert(m.data(), inverse.data());
  return inverse;
}

Matrix4 RotationAboutAxis(Point3 axis, double angleRad, const Point3& translation)
{
  vtkMath::Normalize(axis.data());
  const double c = std::cos(angleRad), s = std::sin(angleRad), t = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2];
  return { t * x * x + c, t * x * y - s * z, t * x * z + s * y, translation[0], //
    t * x * y + s * z, t * y * y + c, t * y * z - s * x, translation[1],         //
    t * x * z - s * y, t * y * z + s * x, t * z * z + c, translation[2],         //
    0, 0, 0, 1 };
}

Point3 TransformPoint(const Matrix4& m, const Point3& p)
{
  return { m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3], m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
    m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11] };
}

Point3 TransformDirection(const Matrix4& m, const Point3& v)
{
  return { m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[4] * v[0] + m[5] * v[1] + m[6] * v[2], m[8] * v[0] + m[9] * v[1] + m[10] * v[2] };
}

double RotationBetweenDeg(const Matrix4& a, const Matrix4& b)
{
  // trace(Ra^T Rb) = 1 + 2 cos(angle)
  double trace = 0.0;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      trace += a[4 * r + c] * b[4 * r + c];
    }
  }
  return vtkMath::DegreesFromRadians(std::acos(std::clamp((trace - 1.0) / 2.0, -1.0, 1.0)));
}

std::string RigidTransformProblem(const Matrix4& m)
{
  if (std::abs(m[12]) > 1e-6 || std::abs(m[13]) > 1e-6 || std::abs(m[14]) > 1e-6 || std::abs(m[15] - 1.0) > 1e-6)
  {
    return "the last matrix row is not 0 0 0 1";
  }
  double worst = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      // (R^T R)_ab: columns a and b of R.
      const double dot = m[a] * m[b] + m[4 + a] * m[4 + b] + m[8 + a] * m[8 + b];
      worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  }
  if (worst > 1e-3)
  {
    return "the rotation is not orthonormal (|R^T R - I| = " + NumberText(worst) + ")";
  }
  const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
    m[2] * (m[4] * m[9] - m[5] * m[8]);
  if (det < 0.0)
  {
    return "the rotation is a reflection (determinant -1)";
  }
  return "";
}
} // namespace vp
