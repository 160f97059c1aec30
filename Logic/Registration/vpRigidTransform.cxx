#include "vpRigidTransform.h"

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
} // namespace vp
