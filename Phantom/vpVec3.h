#ifndef vpVec3_h
#define vpVec3_h

#include <array>
#include <cmath>

namespace vp
{
/// Small vector algebra for the procedural phantom and its trajectory, which work in plain
/// millimetre triples (the voxel loops and the path design need no VTK objects).
namespace vec3
{
using Vec3 = std::array<double, 3>;

constexpr double Pi = 3.14159265358979323846;

inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline double Norm(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}
inline Vec3 Normalized(const Vec3& a)
{
  return (1.0 / Norm(a)) * a;
}
/// A unit vector perpendicular to unit u, as close to hint as possible (any one if hint is
/// parallel to u).
inline Vec3 PerpendicularTo(const Vec3& u, const Vec3& hint)
{
  Vec3 p = hint - Dot(hint, u) * u;
  if (Norm(p) < 1e-6)
  {
    const Vec3 axis = std::abs(u[0]) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
    p = axis - Dot(axis, u) * u;
  }
  return Normalized(p);
}
/// v turned by angle about unit axis u (Rodrigues).
inline Vec3 Rotate(const Vec3& v, const Vec3& u, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return c * v + s * Cross(u, v) + (Dot(u, v) * (1 - c)) * u;
}
} // namespace vec3
} // namespace vp

#endif
