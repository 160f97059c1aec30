#ifndef vpRigidTransform_h
#define vpRigidTransform_h

#include <array>
#include <string>

namespace vp
{
using Point3 = std::array<double, 3>;
/// A 4x4 homogeneous transform, row-major, millimetres.
using Matrix4 = std::array<double, 16>;

/// a * b: b applied first.
Matrix4 MultiplyTransforms(const Matrix4& a, const Matrix4& b);

Matrix4 InvertTransform(const Matrix4& m);

/// Rotation by angleRad about axis (any length but 0; right-handed), then translation.
Matrix4 RotationAboutAxis(Point3 axis, double angleRad, const Point3& translation);

Point3 TransformPoint(const Matrix4& m, const Point3& p);
/// m's rotation applied to a direction (it turns, it does not move).
Point3 TransformDirection(const Matrix4& m, const Point3& v);

/// Why m is not a rigid transform ("the last matrix row is not 0 0 0 1", "the rotation is not
/// orthonormal (|R^T R - I| = ...)" beyond 1e-3, "the rotation is a reflection (determinant -1)"),
/// or "" when it is one.
std::string RigidTransformProblem(const Matrix4& m);

/// The angle of the rotation that takes a's orientation to b's (degrees, 0 to 180).
double RotationBetweenDeg(const Matrix4& a, const Matrix4& b);
} // namespace vp

#endif
