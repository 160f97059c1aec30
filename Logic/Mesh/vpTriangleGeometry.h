#ifndef vpTriangleGeometry_h
#define vpTriangleGeometry_h

#include <algorithm>
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

/// Closest point to p on segment ab (a point when a == b). Returns the squared distance.
inline double ClosestPointOnSegment(const double p[3], const double a[3], const double b[3], double closest[3])
{
  double ab[3], ap[3];
  Sub3(b, a, ab);
  Sub3(p, a, ap);
  const double length2 = Dot3(ab, ab);
  const double t = length2 > 0.0 ? std::min(1.0, std::max(0.0, Dot3(ap, ab) / length2)) : 0.0;
  for (int i = 0; i < 3; ++i)
  {
    closest[i] = a[i] + t * ab[i];
  }
  return Distance2(p, closest);
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
  double normal[3];
  Cross3(ab, ac, normal);
  if (normal[0] == 0.0 && normal[1] == 0.0 && normal[2] == 0.0)
  {
    // Zero area (repeated or collinear corners): the Voronoi regions below divide by zero or
    // follow rounding, so take the nearest of the three edges.
    const double* ends[3][2] = { { a, b }, { b, c }, { c, a } };
    const TriangleFeature features[3] = { TriangleFeature::EdgeAB, TriangleFeature::EdgeBC, TriangleFeature::EdgeCA };
    double best = -1.0;
    for (int e = 0; e < 3; ++e)
    {
      double q[3];
      const double d2 = ClosestPointOnSegment(p, ends[e][0], ends[e][1], q);
      if (best < 0.0 || d2 < best)
      {
        best = d2;
        closest[0] = q[0];
        closest[1] = q[1];
        closest[2] = q[2];
        feature = features[e];
      }
    }
    return best;
  }
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

/// Squared distance between segments p1q1 and p2q2, with the closest points c1 and c2 (Ericson,
/// Real-Time Collision Detection, 5.1.9). Ericson's denominator a*e - b*b is |d1|^2 |d2|^2 sin^2
/// of the angle, so for nearly parallel segments it and the numerator b*f - c*e cancel to rounding
/// noise (at 1e-9 rad it comes out 0 and a crossing pair is reported 1e-9 apart). Written by
/// Lagrange's identity as |d1 x d2|^2 and (d1 x d2).(d2 x r) they lose only a factor 1/sin, which
/// keeps the distance within a few roundings. Zero-length segments are tested exactly, not
/// against an epsilon that would be wrong at some scale: any positive length divides safely, and
/// the clamps take care of overflow.
inline double ClosestPointsOfSegments(const double p1[3], const double q1[3], const double p2[3],
  const double q2[3], double c1[3], double c2[3])
{
  // NaN clamps to 0 so that a division that lost everything still gives a point on the segment.
  auto clamp01 = [](double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; };
  double d1[3], d2[3], r[3];
  Sub3(q1, p1, d1);
  Sub3(q2, p2, d2);
  Sub3(p1, p2, r);
  const double a = Dot3(d1, d1);
  const double e = Dot3(d2, d2);
  const double f = Dot3(d2, r);
  double s = 0.0, t = 0.0;
  if (a == 0.0 && e == 0.0)
  {
    // both points
  }
  else if (a == 0.0)
  {
    t = clamp01(f / e);
  }
  else
  {
    const double c = Dot3(d1, r);
    if (e == 0.0)
    {
      s = clamp01(-c / a);
    }
    else
    {
      const double b = Dot3(d1, d2);
      double n[3], m[3];
      Cross3(d1, d2, n);
      Cross3(d2, r, m);
      const double denom = Dot3(n, n);
      // Parallel: every s is as good once t is clamped and s recomputed from it, so take 0.
      s = denom > 0.0 ? clamp01(Dot3(n, m) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0)
      {
        t = 0.0;
        s = clamp01(-c / a);
      }
      else if (t > 1.0)
      {
        t = 1.0;
        s = clamp01((b - c) / a);
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    c1[k] = p1[k] + d1[k] * s;
    c2[k] = p2[k] + d2[k] * t;
  }
  return Distance2(c1, c2);
}

/// Whether segment pq passes through triangle abc from either side, and where. Only the proper
/// crossing of the plane is reported: a segment in the triangle's plane, or a triangle of zero
/// area, answers false, because callers get that contact from segment and point distances. The
/// line test is Ericson's scalar triple products (5.3.4) taken with both signs, since his segment
/// version (5.3.6) sees only the front face; the point is the plane crossing on pq, so it is on
/// the segment to rounding and in the plane to the rounding of the two plane distances.
inline bool SegmentCrossesTriangle(const double p[3], const double q[3], const double a[3],
  const double b[3], const double c[3], double hit[3])
{
  double ab[3], ac[3], n[3], ap[3], aq[3];
  Sub3(b, a, ab);
  Sub3(c, a, ac);
  Cross3(ab, ac, n);
  Sub3(p, a, ap);
  Sub3(q, a, aq);
  const double dp = Dot3(n, ap);
  const double dq = Dot3(n, aq);
  if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq)
  {
    return false; // one side, or in the plane (also when n is zero)
  }
  double pq[3], pa[3], pb[3], pc[3], x[3];
  Sub3(q, p, pq);
  Sub3(a, p, pa);
  Sub3(b, p, pb);
  Sub3(c, p, pc);
  Cross3(pc, pb, x);
  const double u = Dot3(pq, x);
  Cross3(pa, pc, x);
  const double v = Dot3(pq, x);
  Cross3(pb, pa, x);
  const double w = Dot3(pq, x);
  const bool front = u >= 0.0 && v >= 0.0 && w >= 0.0;
  const bool back = u <= 0.0 && v <= 0.0 && w <= 0.0;
  if (!(front || back) || (u == 0.0 && v == 0.0 && w == 0.0))
  {
    return false;
  }
  const double t = dp / (dp - dq);
  for (int k = 0; k < 3; ++k)
  {
    hit[k] = p[k] + t * pq[k];
  }
  return true;
}

/// Squared minimum distance between triangles a0a1a2 and b0b1b2 over all their points, with a
/// closest pair onA, onB. Triangles that meet have some edge of one crossing the other (the ends
/// of their intersection segment lie on edges), and then the answer is 0 with the crossing point
/// as both. Otherwise the minimum of two disjoint triangles is attained at a vertex-face or an
/// edge-edge pair (Ericson 5.1.11), so the 6 vertex-face and 9 edge-edge distances give it
/// exactly; coplanar contact shows up there as a zero.
/// A triangle of zero area skips its face terms: its points all lie on its edges, which the
/// edge-edge terms cover, and ClosestPointOnTriangle is not made for it (NaN when a == b, a
/// wrong "face" point for some exactly collinear ones).
inline double ClosestPointsOfTriangles(const double a0[3], const double a1[3], const double a2[3],
  const double b0[3], const double b1[3], const double b2[3], double onA[3], double onB[3])
{
  const double* A[3] = { a0, a1, a2 };
  const double* B[3] = { b0, b1, b2 };
  double hit[3];
  for (int i = 0; i < 3; ++i)
  {
    if (SegmentCrossesTriangle(A[i], A[(i + 1) % 3], b0, b1, b2, hit) ||
      SegmentCrossesTriangle(B[i], B[(i + 1) % 3], a0, a1, a2, hit))
    {
      for (int k = 0; k < 3; ++k)
      {
        onA[k] = onB[k] = hit[k];
      }
      return 0.0;
    }
  }
  auto hasArea = [](const double* const T[3]) {
    double e1[3], e2[3], n[3];
    Sub3(T[1], T[0], e1);
    Sub3(T[2], T[0], e2);
    Cross3(e1, e2, n);
    return n[0] != 0.0 || n[1] != 0.0 || n[2] != 0.0;
  };
  double best = Distance2(a0, b0);
  auto keep = [&](double d2, const double x[3], const double y[3]) {
    if (d2 < best) // a NaN never wins
    {
      best = d2;
      for (int k = 0; k < 3; ++k)
      {
        onA[k] = x[k];
        onB[k] = y[k];
      }
    }
  };
  for (int k = 0; k < 3; ++k)
  {
    onA[k] = a0[k];
    onB[k] = b0[k];
  }
  double x[3], y[3];
  TriangleFeature feature;
  if (hasArea(B))
  {
    for (int i = 0; i < 3; ++i)
    {
      keep(ClosestPointOnTriangle(A[i], b0, b1, b2, y, feature), A[i], y);
    }
  }
  if (hasArea(A))
  {
    for (int i = 0; i < 3; ++i)
    {
      keep(ClosestPointOnTriangle(B[i], a0, a1, a2, x, feature), x, B[i]);
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      keep(ClosestPointsOfSegments(A[i], A[(i + 1) % 3], B[j], B[(j + 1) % 3], x, y), x, y);
    }
  }
  return best;
}
} // namespace vp

#endif
