#include "vtkBruteForceVesselDistance.h"

#include "vpInsideVote.h"

#include <vtkObjectFactory.h>

#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkBruteForceVesselDistance);

namespace
{
using vp::TriangleFeature;

/// Closest point on segment pq to x; returns the squared distance and the segment parameter.
double ClosestOnSegment(const double x[3], const double p[3], const double q[3], double out[3], double& s)
{
  double d[3], px[3];
  vp::Sub3(q, p, d);
  vp::Sub3(x, p, px);
  const double len2 = vp::Dot3(d, d);
  s = len2 > 0 ? vp::Dot3(px, d) / len2 : 0.0;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  for (int a = 0; a < 3; ++a)
  {
    out[a] = p[a] + s * d[a];
  }
  return vp::Distance2(x, out);
}

/// The paper's per-triangle step, written as the paper states it (plane first, then edges and
/// vertices) rather than by Voronoi regions, so that it checks the exact engine independently.
double PaperTriangleDistance2(const double x[3], const double* v[3], double closest[3], TriangleFeature& feature)
{
  double e1[3], e2[3], n[3], ax[3];
  vp::Sub3(v[1], v[0], e1);
  vp::Sub3(v[2], v[0], e2);
  vp::Cross3(e1, e2, n);
  const double n2 = vp::Dot3(n, n);
  vp::Sub3(x, v[0], ax);
  // Step: foot of the perpendicular from x onto the triangle's plane.
  const double h = vp::Dot3(ax, n) / n2;
  const double foot[3] = { x[0] - h * n[0], x[1] - h * n[1], x[2] - h * n[2] };
  // Step: is the foot inside? Same side of all three edges as the normal.
  bool inside = true;
  for (int k = 0; k < 3 && inside; ++k)
  {
    double edge[3], toFoot[3], c[3];
    vp::Sub3(v[(k + 1) % 3], v[k], edge);
    vp::Sub3(foot, v[k], toFoot);
    vp::Cross3(edge, toFoot, c);
    inside = vp::Dot3(c, n) >= 0.0;
  }
  if (inside)
  {
    closest[0] = foot[0];
    closest[1] = foot[1];
    closest[2] = foot[2];
    feature = TriangleFeature::Face;
    return vp::Distance2(x, foot);
  }
  // Step: otherwise the nearest edge (its end points are the vertex cases).
  static const TriangleFeature edges[3] = { TriangleFeature::EdgeAB, TriangleFeature::EdgeBC, TriangleFeature::EdgeCA };
  static const TriangleFeature vertices[3] = { TriangleFeature::VertexA, TriangleFeature::VertexB, TriangleFeature::VertexC };
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    double q[3], s;
    const double d2 = ClosestOnSegment(x, v[k], v[(k + 1) % 3], q, s);
    if (d2 < best)
    {
      best = d2;
      closest[0] = q[0];
      closest[1] = q[1];
      closest[2] = q[2];
      feature = s <= 0.0 ? vertices[k] : (s >= 1.0 ? vertices[(k + 1) % 3] : edges[k]);
    }
  }
  return best;
}
} // namespace

vtkBruteForceVesselDistance::vtkBruteForceVesselDistance() = default;
vtkBruteForceVesselDistance::~vtkBruteForceVesselDistance() = default;

void vtkBruteForceVesselDistance::ComputeProximity(const double tip[3], const double* axis,
  vp::ProximityResult& result, const vp::ProximityResult* /*previous*/) const
{
  this->BeginResult(tip, result);
  for (std::size_t c = 0; c < this->Surfaces.size(); ++c)
  {
    const vp::VesselSurface& surface = *this->Surfaces[c];
    vp::ClassProximity& out = result.Classes[c];
    double best = std::numeric_limits<double>::infinity();
    TriangleFeature bestFeature = TriangleFeature::Face;
    for (std::size_t t = 0; t < surface.NumberOfTriangles(); ++t)
    {
      const auto& tri = surface.Triangle(t);
      const double* v[3] = { surface.Point(tri[0]), surface.Point(tri[1]), surface.Point(tri[2]) };
      double q[3] = { 0.0, 0.0, 0.0 };
      TriangleFeature feature = TriangleFeature::Face;
      const double d2 = PaperTriangleDistance2(tip, v, q, feature);
      if (d2 < best)
      {
        best = d2;
        out.TriangleId = static_cast<long long>(t);
        out.ClosestPoint[0] = q[0];
        out.ClosestPoint[1] = q[1];
        out.ClosestPoint[2] = q[2];
        bestFeature = feature;
      }
    }
    out.DistanceMm = std::sqrt(best);
    out.InRange = true;
    if (surface.IsClosed())
    {
      out.Inside = surface.IsInside(tip, static_cast<std::size_t>(out.TriangleId), out.ClosestPoint, bestFeature);
    }
    else if (out.DistanceMm <= vp::InsideVote::OnSurfaceMm)
    {
      out.Inside = false;
    }
    else
    {
      // The inside vote with every triangle tested in double: the reference for Embree's rays.
      int crossings[vp::InsideVote::Rays] = {};
      std::vector<double> along;
      for (int r = 0; r < vp::InsideVote::Rays; ++r)
      {
        along.clear();
        for (std::size_t t = 0; t < surface.NumberOfTriangles(); ++t)
        {
          const auto& tri = surface.Triangle(t);
          const double hit = vp::RayTriangle(
            tip, vp::InsideVote::Directions[r], surface.Point(tri[0]), surface.Point(tri[1]), surface.Point(tri[2]));
          if (hit >= 0.0)
          {
            along.push_back(hit);
          }
        }
        crossings[r] = vp::InsideVote::CountCrossings(along);
      }
      out.Inside = vp::InsideVote::Decide(crossings, out.InsideUncertain);
    }
    if (out.DistanceMm > this->RangeMm && !out.Inside.value_or(false) && !out.InsideUncertain)
    {
      // Beyond the range and outside: no answer. Inside is a breach however far the wall.
      out = vp::ClassProximity{};
      out.ClassName = surface.Name();
      continue;
    }
    if (axis)
    {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t t = 0; t < surface.NumberOfTriangles(); ++t)
      {
        const auto& tri = surface.Triangle(t);
        const double hit = vp::RayTriangle(tip, axis, surface.Point(tri[0]), surface.Point(tri[1]), surface.Point(tri[2]));
        if (hit >= 0.0 && hit < nearest)
        {
          nearest = hit;
        }
      }
      if (nearest <= this->RangeMm)
      {
        out.DirectionalMm = nearest;
      }
    }
  }
}
