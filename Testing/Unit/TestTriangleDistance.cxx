// Segment-segment, segment-triangle and triangle-triangle distances of vpTriangleGeometry.h against
// analytic cases, degenerate input and a dense sampling of random pairs.
#include "vpTriangleGeometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace
{
constexpr double Tol = 1e-12;

struct Triangle
{
  double V[3][3];
};

double Norm(const double a[3], const double b[3])
{
  return std::sqrt(vp::Distance2(a, b));
}

/// Distance from p to segment ab by projection, independent of the code under test.
double PointSegment(const double p[3], const double a[3], const double b[3])
{
  double ab[3], ap[3];
  vp::Sub3(b, a, ab);
  vp::Sub3(p, a, ap);
  const double len2 = vp::Dot3(ab, ab);
  const double t = len2 > 0 ? std::clamp(vp::Dot3(ab, ap) / len2, 0.0, 1.0) : 0.0;
  const double q[3] = { a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2] };
  return Norm(p, q);
}

/// Distance from p to the triangle's point set, zero-area triangles included: their points lie on
/// their edges, and ClosestPointOnTriangle is not used where it could divide by zero.
double PointTriangle(const double p[3], const Triangle& t)
{
  double d = std::numeric_limits<double>::infinity();
  for (int e = 0; e < 3; ++e)
  {
    d = std::min(d, PointSegment(p, t.V[e], t.V[(e + 1) % 3]));
  }
  double ab[3], ac[3], n[3];
  vp::Sub3(t.V[1], t.V[0], ab);
  vp::Sub3(t.V[2], t.V[0], ac);
  vp::Cross3(ab, ac, n);
  if (vp::Dot3(n, n) > 0)
  {
    double q[3];
    vp::TriangleFeature feature;
    const double face = std::sqrt(vp::ClosestPointOnTriangle(p, t.V[0], t.V[1], t.V[2], q, feature));
    if (std::isfinite(face))
    {
      d = std::min(d, face);
    }
  }
  return d;
}

double LongestEdge(const Triangle& t)
{
  return std::max({ Norm(t.V[0], t.V[1]), Norm(t.V[1], t.V[2]), Norm(t.V[2], t.V[0]) });
}

/// The distance, with the properties every answer must have: finite, points on their own
/// triangles and exactly that far apart.
double Distance(const Triangle& a, const Triangle& b, double onA[3], double onB[3], double tol = Tol)
{
  const double d2 = vp::ClosestPointsOfTriangles(a.V[0], a.V[1], a.V[2], b.V[0], b.V[1], b.V[2], onA, onB);
  EXPECT_TRUE(std::isfinite(d2));
  EXPECT_GE(d2, 0.0);
  const double d = std::sqrt(d2);
  EXPECT_LT(PointTriangle(onA, a), tol) << "point on the first triangle";
  EXPECT_LT(PointTriangle(onB, b), tol) << "point on the second triangle";
  EXPECT_NEAR(Norm(onA, onB), d, 1e-9 * d) << "points the returned distance apart";
  return d;
}

double Distance(const Triangle& a, const Triangle& b)
{
  double onA[3], onB[3];
  return Distance(a, b, onA, onB);
}

void ExpectPoint(const double p[3], double x, double y, double z, double tol = Tol)
{
  EXPECT_NEAR(p[0], x, tol);
  EXPECT_NEAR(p[1], y, tol);
  EXPECT_NEAR(p[2], z, tol);
}
} // namespace

TEST(SegmentDistance, SkewPerpendicular)
{
  const double p1[3] = { -1, 0, 0 }, q1[3] = { 1, 0, 0 };
  const double p2[3] = { 0.5, -1, 2 }, q2[3] = { 0.5, 3, 2 };
  double c1[3], c2[3];
  EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, p2, q2, c1, c2), 4.0, Tol);
  ExpectPoint(c1, 0.5, 0, 0);
  ExpectPoint(c2, 0.5, 0, 2);
  // Past the end of the first segment: its end point and the foot on the second.
  const double p3[3] = { 3, -1, 2 }, q3[3] = { 3, 1, 2 };
  EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, p3, q3, c1, c2), 4.0 + 4.0, Tol);
  ExpectPoint(c1, 1, 0, 0);
  ExpectPoint(c2, 3, 0, 2);
}

TEST(SegmentDistance, ParallelOverlappingAndApart)
{
  double c1[3], c2[3];
  const double p1[3] = { 0, 0, 0 }, q1[3] = { 4, 0, 0 };
  // Overlapping in x over [1, 4]: distance 1 at any x there.
  const double p2[3] = { 1, 1, 0 }, q2[3] = { 6, 1, 0 };
  EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, p2, q2, c1, c2), 1.0, Tol);
  EXPECT_NEAR(c2[0] - c1[0], 0.0, Tol);
  EXPECT_NEAR(c2[1] - c1[1], 1.0, Tol);
  EXPECT_GE(c1[0], 1.0 - Tol);
  EXPECT_LE(c1[0], 4.0 + Tol);
  // The same, antiparallel.
  EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, q2, p2, c1, c2), 1.0, Tol);
  EXPECT_NEAR(c2[0] - c1[0], 0.0, Tol);
  // Apart along their direction: end to end.
  const double p3[3] = { 6, 1, 0 }, q3[3] = { 9, 1, 0 };
  for (bool reversed : { false, true })
  {
    EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, reversed ? q3 : p3, reversed ? p3 : q3, c1, c2), 4.0 + 1.0, Tol);
    ExpectPoint(c1, 4, 0, 0);
    ExpectPoint(c2, 6, 1, 0);
  }
}

TEST(SegmentDistance, CollinearOverlappingAndApart)
{
  double c1[3], c2[3];
  const double p1[3] = { 0, 0, 0 }, q1[3] = { 2, 0, 0 };
  const double p2[3] = { 1, 0, 0 }, q2[3] = { 3, 0, 0 };
  EXPECT_EQ(vp::ClosestPointsOfSegments(p1, q1, p2, q2, c1, c2), 0.0);
  EXPECT_EQ(vp::Distance2(c1, c2), 0.0);
  EXPECT_GE(c1[0], 1.0);
  EXPECT_LE(c1[0], 2.0);
  const double p3[3] = { 5, 0, 0 }, q3[3] = { 3.5, 0, 0 };
  EXPECT_NEAR(vp::ClosestPointsOfSegments(p1, q1, p3, q3, c1, c2), 1.5 * 1.5, Tol);
  ExpectPoint(c1, 2, 0, 0);
  ExpectPoint(c2, 3.5, 0, 0);
}

TEST(SegmentDistance, ZeroLengthSegments)
{
  double c1[3], c2[3];
  const double p[3] = { 1, 2, 3 }, q[3] = { 4, 6, 3 };
  // Point and point.
  EXPECT_EQ(vp::ClosestPointsOfSegments(p, p, q, q, c1, c2), 25.0);
  ExpectPoint(c1, 1, 2, 3, 0);
  ExpectPoint(c2, 4, 6, 3, 0);
  // Point and segment, both ways round: foot inside, then beyond the end.
  const double s0[3] = { 0, 0, 0 }, s1[3] = { 10, 0, 0 };
  const double r[3] = { 4, 3, -4 };
  EXPECT_NEAR(vp::ClosestPointsOfSegments(r, r, s0, s1, c1, c2), 25.0, Tol);
  ExpectPoint(c2, 4, 0, 0);
  EXPECT_NEAR(vp::ClosestPointsOfSegments(s0, s1, r, r, c1, c2), 25.0, Tol);
  ExpectPoint(c1, 4, 0, 0);
  const double beyond[3] = { -3, 4, 0 };
  EXPECT_NEAR(vp::ClosestPointsOfSegments(beyond, beyond, s0, s1, c1, c2), 25.0, Tol);
  ExpectPoint(c2, 0, 0, 0);
  // A point lying on the segment.
  const double on[3] = { 7, 0, 0 };
  EXPECT_EQ(vp::ClosestPointsOfSegments(s0, s1, on, on, c1, c2), 0.0);
}

TEST(SegmentDistance, NearlyParallelKeepsItsPrecision)
{
  // Crossing over at x = 0.5 with a gap h, at an angle of 2e-9 rad: a*e - b*b of Ericson's form
  // cancels to rounding noise here; the cross-product form does not.
  for (double h : { 0.0, 1e-9, 1e-6, 1e-3 })
  {
    const double p1[3] = { 0, 0, 0 }, q1[3] = { 1, 0, 0 };
    const double p2[3] = { 0, -1e-9, h }, q2[3] = { 1, 1e-9, h };
    double c1[3], c2[3];
    const double d = std::sqrt(vp::ClosestPointsOfSegments(p1, q1, p2, q2, c1, c2));
    EXPECT_NEAR(d, h, 1e-15 + 1e-12 * h) << "gap " << h;
    EXPECT_NEAR(c1[0], 0.5, 1e-6) << "gap " << h;
  }
}

TEST(SegmentDistance, AgreesWithDenseSamplingOnRandomPairs)
{
  // Reference: every one of N + 1 evenly spaced points of one segment projected onto the other,
  // both ways. The true closest point of a segment of length L is within L / (2N) of a sample,
  // and distance to a set is 1-Lipschitz, so reference - min(L1, L2) / (2N) <= exact <= reference.
  constexpr int N = 2000;
  std::mt19937 random(17);
  std::uniform_real_distribution<double> box(-1.0, 1.0);
  for (int i = 0; i < 1000; ++i)
  {
    double p1[3], q1[3], p2[3], q2[3];
    for (int a = 0; a < 3; ++a)
    {
      p1[a] = box(random);
      q1[a] = box(random);
      p2[a] = box(random);
      q2[a] = box(random);
    }
    if (i % 4 == 1)
    { // parallel
      for (int a = 0; a < 3; ++a)
      {
        q2[a] = p2[a] + 0.7 * (q1[a] - p1[a]);
      }
    }
    else if (i % 4 == 2)
    { // degenerate
      std::copy(p2, p2 + 3, q2);
    }
    double c1[3], c2[3];
    const double d = std::sqrt(vp::ClosestPointsOfSegments(p1, q1, p2, q2, c1, c2));
    double reference = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= N; ++k)
    {
      const double s = static_cast<double>(k) / N;
      double x[3], y[3];
      for (int a = 0; a < 3; ++a)
      {
        x[a] = p1[a] + s * (q1[a] - p1[a]);
        y[a] = p2[a] + s * (q2[a] - p2[a]);
      }
      reference = std::min({ reference, PointSegment(x, p2, q2), PointSegment(y, p1, q1) });
    }
    const double step = std::min(Norm(p1, q1), Norm(p2, q2)) / (2 * N);
    EXPECT_LE(d, reference + 1e-12) << "pair " << i;
    EXPECT_GE(d, reference - step - 1e-12) << "pair " << i;
    EXPECT_LT(PointSegment(c1, p1, q1), 1e-12);
    EXPECT_LT(PointSegment(c2, p2, q2), 1e-12);
  }
}

TEST(SegmentCrossesTriangle, ThroughMissesAndContact)
{
  const double a[3] = { 0, 0, 0 }, b[3] = { 4, 0, 0 }, c[3] = { 0, 4, 0 };
  const double p[3] = { 1, 1, -1 }, q[3] = { 1, 2, 3 };
  double hit[3];
  ASSERT_TRUE(vp::SegmentCrossesTriangle(p, q, a, b, c, hit));
  ExpectPoint(hit, 1, 1.25, 0);
  ASSERT_TRUE(vp::SegmentCrossesTriangle(q, p, a, b, c, hit)) << "from the back side";
  ExpectPoint(hit, 1, 1.25, 0);
  ASSERT_TRUE(vp::SegmentCrossesTriangle(p, q, a, c, b, hit)) << "opposite winding";
  const double short1[3] = { 1, 1, -0.5 };
  EXPECT_FALSE(vp::SegmentCrossesTriangle(p, short1, a, b, c, hit)) << "ends before the plane";
  const double outside0[3] = { 3, 3, -1 }, outside1[3] = { 3, 3, 1 };
  EXPECT_FALSE(vp::SegmentCrossesTriangle(outside0, outside1, a, b, c, hit)) << "crosses the plane outside";
  const double in0[3] = { -1, 1, 0 }, in1[3] = { 3, 1, 0 };
  EXPECT_FALSE(vp::SegmentCrossesTriangle(in0, in1, a, b, c, hit)) << "in the plane: left to distances";
  const double flat[3] = { 8, 0, 0 };
  EXPECT_FALSE(vp::SegmentCrossesTriangle(p, q, a, b, flat, hit)) << "zero-area triangle";
  EXPECT_FALSE(vp::SegmentCrossesTriangle(p, p, a, b, c, hit)) << "zero-length segment";
  const double touch[3] = { 1, 1, 0 };
  ASSERT_TRUE(vp::SegmentCrossesTriangle(p, touch, a, b, c, hit)) << "ends on the face";
  ExpectPoint(hit, 1, 1, 0);
}

TEST(TriangleDistance, ParallelPlanesOverlapping)
{
  const Triangle a = { { { 0, 0, 0 }, { 4, 0, 0 }, { 0, 4, 0 } } };
  const Triangle b = { { { 1, 1, 3 }, { 5, 1, 3 }, { 1, 5, 3 } } };
  double onA[3], onB[3];
  EXPECT_NEAR(Distance(a, b, onA, onB), 3.0, Tol);
  EXPECT_NEAR(onA[2], 0.0, Tol);
  EXPECT_NEAR(onB[0] - onA[0], 0.0, Tol);
  EXPECT_NEAR(onB[1] - onA[1], 0.0, Tol);
  EXPECT_NEAR(Distance(b, a), 3.0, Tol);
}

TEST(TriangleDistance, SkewEdgesFacingEachOther)
{
  // An edge along x at z = 0 below one along y at z = 2; the rest of each triangle leans away.
  const Triangle a = { { { -2, 0, 0 }, { 2, 0, 0 }, { 0.5, -1, -3 } } };
  const Triangle b = { { { 0, -2, 2 }, { 0, 2, 2 }, { 1, 1, 5 } } };
  double onA[3], onB[3];
  EXPECT_NEAR(Distance(a, b, onA, onB), 2.0, Tol);
  ExpectPoint(onA, 0, 0, 0);
  ExpectPoint(onB, 0, 0, 2);
  EXPECT_NEAR(Distance(b, a, onB, onA), 2.0, Tol);
  ExpectPoint(onA, 0, 0, 0);
  ExpectPoint(onB, 0, 0, 2);
}

TEST(TriangleDistance, VertexAboveFace)
{
  const Triangle a = { { { -5, -5, 0 }, { 5, -5, 0 }, { 0, 5, 0 } } };
  const Triangle b = { { { 3, 3, 6 }, { 1, 0.5, 2.5 }, { -3, 2, 7 } } };
  double onA[3], onB[3];
  EXPECT_NEAR(Distance(a, b, onA, onB), 2.5, Tol);
  ExpectPoint(onA, 1, 0.5, 0);
  ExpectPoint(onB, 1, 0.5, 2.5);
  EXPECT_NEAR(Distance(b, a, onB, onA), 2.5, Tol);
  ExpectPoint(onA, 1, 0.5, 0);
}

TEST(TriangleDistance, CrossingTriangles)
{
  // b stands in the plane y = 0 and pierces a's interior; no vertex or edge of either is near the
  // other's, so only the crossing test finds the zero.
  const Triangle a = { { { -2, -2, 0 }, { 2, -2, 0 }, { 0, 3, 0 } } };
  const Triangle b = { { { 0, 0, -1 }, { 0.5, 0, 1 }, { -0.5, 0, 1 } } };
  for (bool swapped : { false, true })
  {
    double onA[3], onB[3];
    EXPECT_EQ(swapped ? Distance(b, a, onB, onA) : Distance(a, b, onA, onB), 0.0);
    EXPECT_EQ(Norm(onA, onB), 0.0);
    EXPECT_NEAR(onA[1], 0.0, Tol) << "in b's plane";
    EXPECT_NEAR(onA[2], 0.0, Tol) << "in a's plane";
    EXPECT_LE(std::abs(onA[0]), 0.25 + Tol) << "on the intersection segment";
  }
}

TEST(TriangleDistance, CoplanarOverlappingAndContained)
{
  const double s = std::sqrt(3.0);
  const Triangle up = { { { 0, 2, 5 }, { -s, -1, 5 }, { s, -1, 5 } } };
  const Triangle down = { { { 0, -2, 5 }, { s, 1, 5 }, { -s, 1, 5 } } };
  EXPECT_EQ(Distance(up, down), 0.0);
  const Triangle inner = { { { 0, 0, 5 }, { 0.1, 0, 5 }, { 0, 0.1, 5 } } };
  EXPECT_EQ(Distance(up, inner), 0.0);
  EXPECT_EQ(Distance(inner, up), 0.0);
}

TEST(TriangleDistance, CoplanarApart)
{
  const Triangle a = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } };
  // Vertex to vertex.
  const Triangle b = { { { 3, 0, 0 }, { 4, 0, 0 }, { 3, 1, 0 } } };
  double onA[3], onB[3];
  EXPECT_NEAR(Distance(a, b, onA, onB), 2.0, Tol);
  ExpectPoint(onA, 1, 0, 0);
  ExpectPoint(onB, 3, 0, 0);
  // Parallel edges x + y = 1 and x + y = 3: a whole range of closest pairs.
  const Triangle c = { { { 3, 0, 0 }, { 0, 3, 0 }, { 3, 3, 0 } } };
  EXPECT_NEAR(Distance(a, c, onA, onB), std::sqrt(2.0), Tol);
  EXPECT_NEAR(onA[0] + onA[1], 1.0, Tol);
  EXPECT_NEAR(onB[0] - onA[0], 1.0, Tol);
  EXPECT_NEAR(onB[1] - onA[1], 1.0, Tol);
}

TEST(TriangleDistance, SharedVertexAndEdge)
{
  const Triangle a = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } };
  const Triangle vertex = { { { -1, 0, 1 }, { 0, 0, 0 }, { 0, -1, 1 } } };
  double onA[3], onB[3];
  EXPECT_EQ(Distance(a, vertex, onA, onB), 0.0);
  ExpectPoint(onA, 0, 0, 0);
  const Triangle edge = { { { 1, 0, 0 }, { 0, 0, 0 }, { 0.5, -1, 2 } } };
  EXPECT_EQ(Distance(a, edge, onA, onB), 0.0);
  EXPECT_NEAR(onA[1], 0.0, Tol);
  EXPECT_NEAR(onA[2], 0.0, Tol);
}

TEST(TriangleDistance, ZeroAreaTriangles)
{
  // b lies in the plane z = 1 + x; the segment x in [0, 2] on the x axis is nearest it at the
  // origin, 1/sqrt(2) away, with the foot (-0.5, 0, 0.5) inside b.
  const Triangle b = { { { -3, -3, -2 }, { 3, -3, 4 }, { -3, 3, -2 } } };
  const double h = 1 / std::sqrt(2.0);
  const Triangle collinear = { { { 0, 0, 0 }, { 2, 0, 0 }, { 1, 0, 0 } } };
  const Triangle repeated = { { { 0, 0, 0 }, { 0, 0, 0 }, { 2, 0, 0 } } };
  const Triangle repeatedLast = { { { 2, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } } };
  for (const Triangle& a : { collinear, repeated, repeatedLast })
  {
    double onA[3], onB[3];
    EXPECT_NEAR(Distance(a, b, onA, onB), h, Tol);
    ExpectPoint(onA, 0, 0, 0);
    ExpectPoint(onB, -0.5, 0, 0.5);
    EXPECT_NEAR(Distance(b, a, onB, onA), h, Tol) << "the zero-area triangle second";
    ExpectPoint(onA, 0, 0, 0);
  }
  // One point, three times: the point's distance to b's plane.
  const Triangle point = { { { 0.5, 0, 0 }, { 0.5, 0, 0 }, { 0.5, 0, 0 } } };
  double onA[3], onB[3];
  EXPECT_NEAR(Distance(point, b, onA, onB), 1.5 * h, Tol);
  ExpectPoint(onB, -0.25, 0, 0.75);
  EXPECT_NEAR(Distance(b, point), 1.5 * h, Tol);
  // Both without area: segment and point, segment and segment, point and point.
  const Triangle far = { { { 1, 3, 4 }, { 1, 3, 4 }, { 1, 3, 4 } } };
  EXPECT_NEAR(Distance(collinear, far, onA, onB), 5.0, Tol);
  ExpectPoint(onA, 1, 0, 0);
  const Triangle across = { { { 1, -1, 2 }, { 1, 1, 2 }, { 1, 0, 2 } } };
  EXPECT_NEAR(Distance(repeated, across, onA, onB), 2.0, Tol);
  ExpectPoint(onA, 1, 0, 0);
  EXPECT_NEAR(Distance(point, far), std::sqrt(0.25 + 9 + 16), Tol);
  // A vertical segment through a face.
  const Triangle floor = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } } };
  const Triangle needle = { { { 0.25, 0.25, -1 }, { 0.25, 0.25, 1 }, { 0.25, 0.25, 0.5 } } };
  EXPECT_EQ(Distance(needle, floor, onA, onB), 0.0);
  ExpectPoint(onA, 0.25, 0.25, 0);
}

TEST(TriangleDistance, AgreesWithDenseSamplingOnRandomPairs)
{
  // Reference: the barycentric grid of step 1/N on each triangle, every grid point taken to the
  // other triangle by ClosestPointOnTriangle. Each value is the distance of two points of the
  // triangles, so exact <= reference. The exact closest point of A lies in a grid cell, a copy of
  // A scaled by 1/N, so within LA / N of a grid point (distance to a cell vertex is convex, at
  // most the cell's longest edge); distance to B is 1-Lipschitz, so
  // reference <= exact + min(LA, LB) / N.
  constexpr int N = 40;
  std::mt19937 random(2024);
  std::uniform_real_distribution<double> box(-1.0, 1.0), unit(0.0, 1.0);
  auto randomTriangle = [&](Triangle& t) {
    for (auto& v : t.V)
    {
      for (double& c : v)
      {
        c = box(random);
      }
    }
  };
  auto randomDirection = [&](double v[3]) {
    double len = 0;
    do
    {
      for (int k = 0; k < 3; ++k)
      {
        v[k] = box(random);
      }
      len = std::sqrt(vp::Dot3(v, v));
    } while (len < 0.1 || len > 1);
    for (int k = 0; k < 3; ++k)
    {
      v[k] /= len;
    }
  };
  auto reference = [&](const Triangle& from, const Triangle& to) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= N; ++i)
    {
      for (int j = 0; i + j <= N; ++j)
      {
        const double u = static_cast<double>(i) / N, v = static_cast<double>(j) / N;
        double x[3];
        for (int k = 0; k < 3; ++k)
        {
          x[k] = from.V[0][k] + u * (from.V[1][k] - from.V[0][k]) + v * (from.V[2][k] - from.V[0][k]);
        }
        best = std::min(best, PointTriangle(x, to));
      }
    }
    return best;
  };
  int touching = 0, near = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const double scale = (i % 3 == 0) ? 0.01 : (i % 3 == 1 ? 1.0 : 100.0);
    const int kind = (i / 3) % 6;
    Triangle a, b;
    randomTriangle(a);
    randomTriangle(b);
    const double gap = std::pow(10.0, -7 * unit(random)) * (unit(random) < 0.5 ? -1 : 1);
    if (kind == 1)
    { // apart
      double d[3];
      randomDirection(d);
      for (auto& v : b.V)
      {
        for (int k = 0; k < 3; ++k)
        {
          v[k] += 3 * d[k];
        }
      }
    }
    else if (kind == 2)
    { // a vertex of b just off a point of a's face, on either side
      double e1[3], e2[3], n[3];
      vp::Sub3(a.V[1], a.V[0], e1);
      vp::Sub3(a.V[2], a.V[0], e2);
      vp::Cross3(e1, e2, n);
      const double len = std::sqrt(vp::Dot3(n, n));
      double u = unit(random), v = unit(random);
      if (u + v > 1)
      {
        u = 1 - u;
        v = 1 - v;
      }
      for (int k = 0; k < 3; ++k)
      {
        const double x = a.V[0][k] + u * e1[k] + v * e2[k];
        const double shift = x + gap * n[k] / len - b.V[0][k];
        for (auto& w : b.V)
        {
          w[k] += shift;
        }
      }
    }
    else if (kind == 3)
    { // an edge of b passing just off a point of an edge of a
      const double s = unit(random);
      double x[3], d[3], off[3];
      for (int k = 0; k < 3; ++k)
      {
        x[k] = a.V[0][k] + s * (a.V[1][k] - a.V[0][k]);
      }
      randomDirection(d);
      randomDirection(off);
      const double t = unit(random);
      for (int k = 0; k < 3; ++k)
      {
        b.V[0][k] = x[k] + gap * off[k] - t * d[k];
        b.V[1][k] = x[k] + gap * off[k] + (1 - t) * d[k];
      }
    }
    else if (kind == 4)
    { // coplanar or nearly parallel planes
      for (auto& v : a.V)
      {
        v[2] = 0;
      }
      for (auto& v : b.V)
      {
        v[2] = (i % 2) ? 0.0 : 0.01 * gap + 1e-3 * v[0];
      }
    }
    else if (kind == 5)
    { // a sliver: the third vertex within a relative 1e-7 .. 1e-14 of the line of the first two
      const double s = 2 * unit(random) - 0.5;
      const double width = std::pow(10.0, -7 - 7 * unit(random));
      for (int k = 0; k < 3; ++k)
      {
        a.V[2][k] = a.V[0][k] + s * (a.V[1][k] - a.V[0][k]) + width * box(random);
      }
    }
    for (Triangle* t : { &a, &b })
    {
      for (auto& v : t->V)
      {
        for (double& c : v)
        {
          c *= scale;
        }
      }
    }
    const double tol = 1e-9 * scale;
    double onA[3], onB[3];
    const double d = Distance(a, b, onA, onB, tol);
    const double ref = std::min(reference(a, b), reference(b, a));
    const double bound = std::min(LongestEdge(a), LongestEdge(b)) / N;
    EXPECT_LE(d, ref + tol) << "pair " << i << " kind " << kind;
    EXPECT_GE(d, ref - bound - tol) << "pair " << i << " kind " << kind;
    // Order of the triangles and of their vertices changes nothing.
    const Triangle b2 = { { { b.V[2][0], b.V[2][1], b.V[2][2] }, { b.V[0][0], b.V[0][1], b.V[0][2] },
      { b.V[1][0], b.V[1][1], b.V[1][2] } } };
    double onB2[3], onA2[3];
    EXPECT_NEAR(Distance(b2, a, onB2, onA2, tol), d, tol) << "pair " << i;
    touching += d == 0;
    near += d > 0 && d < 1e-3 * scale;
  }
  // The draw covers what it is meant to: contact, near contact and clear gaps.
  EXPECT_GT(touching, 200);
  EXPECT_GT(near, 150);
}

// A triangle with two equal corners once gave NaN (0/0 on its zero-length edge), and the exact
// engine's "d2 >= best" test let the NaN through as the answer.
TEST(PointTriangleDistance, RepeatedCornerGivesTheSegmentDistance)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  const double a[3] = { 0, 0, 0 };
  const double c[3] = { 1, 0, 0 };
  for (int i = 0; i < 2000; ++i)
  {
    const double p[3] = { coordinate(random), coordinate(random), coordinate(random) };
    double closest[3], onSegment[3], self[3];
    vp::TriangleFeature feature;
    const double d2 = vp::ClosestPointOnTriangle(p, a, a, c, closest, feature);
    const double expected = vp::ClosestPointsOfSegments(p, p, a, c, self, onSegment);
    ASSERT_TRUE(std::isfinite(d2)) << "point " << p[0] << ", " << p[1] << ", " << p[2];
    EXPECT_NEAR(d2, expected, 1e-12);
    const double d2b = vp::ClosestPointOnTriangle(p, a, c, c, closest, feature);
    ASSERT_TRUE(std::isfinite(d2b));
    EXPECT_NEAR(d2b, expected, 1e-12);
  }
}
