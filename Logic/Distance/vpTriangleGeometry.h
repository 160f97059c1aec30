#ifndef vpTriangleGeometry_h
#define vpTriangleGeometry_h

#include <cmath>

namespace vp
{
/// Which part of a triangle holds the closest point: the pseudonormal of that part decides
/// inside/outside (Baerentzen & Aanaes 2005).
enum class TriangleFeature
{
  Face,
  EdgeAB,
  EdgeBC,
  EdgeCA,
  VertexA,
  VertexB,
  VertexC
};

inline double Dot3(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline void Sub3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}

inline void Cross3(const double a[3], const double b[3], double out[3])
{
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

inline double Distance2(const double a[3], const double b[3])
{
  const double d[3] = { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
  return Dot3(d, d);
}

/// Closest point to p on triangle abc by Voronoi regions (Ericson, Real-Time Collision
/// Detection, 5.1.5). Returns the squared distance; writes the point and the feature.
inline double ClosestPointOnTriangle(const double p[3], const double a[3], const double b[3],
  const double c[3], double closest[3], TriangleFeature& feature)
{
  double ab[3], ac[3], ap[3];
  Sub3(b, a, ab);
  Sub3(c, a, ac);
  Sub3(p, a, ap);
  const double d1 = Dot3(ab, ap);
  const double d2 = Dot3(ac, ap);
  auto set = [&](const double q[3], TriangleFeature f) {
    closest[0] = q[0];
    closest[1] = q[1];
    closest[2] = q[2];
    feature = f;
    return Distance2(p, closest);
  };
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return set(a, TriangleFeature::VertexA);
  }
  double bp[3];
  Sub3(p, b, bp);
  const double d3 = Dot3(ab, bp);
  const double d4 = Dot3(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return set(b, TriangleFeature::VertexB);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    const double v = d1 / (d1 - d3);
    const double q[3] = { a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2] };
    return set(q, TriangleFeature::EdgeAB);
  }
  double cp[3];
  Sub3(p, c, cp);
  const double d5 = Dot3(ab, cp);
  const double d6 = Dot3(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return set(c, TriangleFeature::VertexC);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    const double w = d2 / (d2 - d6);
    const double q[3] = { a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2] };
    return set(q, TriangleFeature::EdgeCA);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    const double q[3] = { b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2]) };
    return set(q, TriangleFeature::EdgeBC);
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom;
  const double w = vc * denom;
  const double q[3] = { a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w,
    a[2] + ab[2] * v + ac[2] * w };
  return set(q, TriangleFeature::Face);
}

/// Distance along a ray (origin o, unit direction d) to triangle abc, both sides counted;
/// negative when missed (Moeller & Trumbore 1997).
inline double RayTriangle(const double o[3], const double d[3], const double a[3],
  const double b[3], const double c[3])
{
  double e1[3], e2[3], pv[3], tv[3], qv[3];
  Sub3(b, a, e1);
  Sub3(c, a, e2);
  Cross3(d, e2, pv);
  const double det = Dot3(e1, pv);
  if (std::abs(det) < 1e-300)
  {
    return -1.0;
  }
  const double inv = 1.0 / det;
  Sub3(o, a, tv);
  const double u = Dot3(tv, pv) * inv;
  if (u < 0.0 || u > 1.0)
  {
    return -1.0;
  }
  Cross3(tv, e1, qv);
  const double v = Dot3(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0)
  {
    return -1.0;
  }
  return Dot3(e2, qv) * inv;
}
} // namespace vp

#endif
