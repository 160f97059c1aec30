#include "vpApproachGeometry.h"

#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBBTree.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

Vector3 Cross(const Vector3& a, const Vector3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double Dot(const Vector3& a, const Vector3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// A unit vector perpendicular to unit v: v crossed with the axis it is least along.
Vector3 Perpendicular(const Vector3& v)
{
  int least = 0;
  for (int a = 1; a < 3; ++a)
  {
    least = std::abs(v[a]) < std::abs(v[least]) ? a : least;
  }
  Vector3 axis{ 0, 0, 0 };
  axis[least] = 1.0;
  return Normalized(Cross(v, axis));
}
} // namespace

double Length(const Vector3& v)
{
  return std::sqrt(Dot(v, v));
}

Vector3 Normalized(const Vector3& v)
{
  const double length = Length(v);
  return { v[0] / length, v[1] / length, v[2] / length };
}

Vector3 EnclosedVolumeCentre(vtkPolyData* surface)
{
  // Each triangle and the origin make a signed tetrahedron; their volume-weighted centres sum to
  // the enclosed volume's centre, whatever the origin (taken at the first point, for precision).
  vtkPoints* points = surface->GetPoints();
  Vector3 origin{ 0, 0, 0 }, sum{ 0, 0, 0 }, mean{ 0, 0, 0 };
  const vtkIdType n = points ? points->GetNumberOfPoints() : 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    origin = i == 0 ? Vector3{ p[0], p[1], p[2] } : origin;
    for (int a = 0; a < 3; ++a)
    {
      mean[a] += p[a] / static_cast<double>(n);
    }
  }
  double volume = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    surface->GetCellPoints(c, ids);
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k) // a polygon as a fan of triangles
    {
      Vector3 v[3];
      for (int j = 0; j < 3; ++j)
      {
        double p[3];
        points->GetPoint(ids->GetId(j == 0 ? 0 : k + j - 1), p);
        v[j] = { p[0] - origin[0], p[1] - origin[1], p[2] - origin[2] };
      }
      const double six = Dot(v[0], Cross(v[1], v[2]));
      volume += six / 6.0;
      for (int a = 0; a < 3; ++a)
      {
        sum[a] += six / 6.0 * (v[0][a] + v[1][a] + v[2][a]) / 4.0;
      }
    }
  }
  if (!(std::abs(volume) > 1e-9))
  {
    return mean;
  }
  return { origin[0] + sum[0] / volume, origin[1] + sum[1] / volume, origin[2] + sum[2] / volume };
}

std::vector<double> LineCrossings(vtkOBBTree* tree, const Vector3& originMm, const Vector3& direction, double lengthMm)
{
  const double end[3] = { originMm[0] + lengthMm * direction[0], originMm[1] + lengthMm * direction[1],
    originMm[2] + lengthMm * direction[2] };
  vtkNew<vtkPoints> hits;
  tree->IntersectWithLine(originMm.data(), end, hits, nullptr);
  std::vector<double> t;
  for (vtkIdType i = 0; i < hits->GetNumberOfPoints(); ++i)
  {
    double p[3];
    hits->GetPoint(i, p);
    t.push_back((p[0] - originMm[0]) * direction[0] + (p[1] - originMm[1]) * direction[1] + (p[2] - originMm[2]) * direction[2]);
  }
  std::sort(t.begin(), t.end());
  // A line through an edge or a vertex crosses once but meets every triangle there.
  t.erase(std::unique(t.begin(), t.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), t.end());
  return t;
}

std::array<double, 4> QuaternionTurning(const Vector3& from, const Vector3& to)
{
  const double dot = Dot(from, to);
  if (dot < -1.0 + 1e-12)
  {
    const Vector3 axis = Perpendicular(from);
    return { 0.0, axis[0], axis[1], axis[2] };
  }
  // The half-way quaternion: (1 + cos, sin * axis), normalised.
  const Vector3 c = Cross(from, to);
  const double w = 1.0 + dot;
  const double norm = std::sqrt(w * w + Dot(c, c));
  return { w / norm, c[0] / norm, c[1] / norm, c[2] / norm };
}

double DistanceOutOfBox(const Vector3& pointMm, const Vector3& direction, const std::array<double, 6>& box)
{
  double exit = 1e300;
  for (int a = 0; a < 3; ++a)
  {
    if (pointMm[a] < box[2 * a] || pointMm[a] > box[2 * a + 1])
    {
      return 0.0;
    }
    if (direction[a] > 0.0)
    {
      exit = std::min(exit, (box[2 * a + 1] - pointMm[a]) / direction[a]);
    }
    else if (direction[a] < 0.0)
    {
      exit = std::min(exit, (box[2 * a] - pointMm[a]) / direction[a]);
    }
  }
  return exit;
}

std::vector<ConeDirection> ConeDirections(const Vector3& axis, double maxDeg, double stepDeg)
{
  std::vector<ConeDirection> directions;
  if (!(maxDeg > 0.0) || !(stepDeg > 0.0))
  {
    return directions;
  }
  const Vector3 u = Perpendicular(axis), v = Cross(axis, u);
  const int rings = static_cast<int>(std::ceil(maxDeg / stepDeg - 1e-9));
  for (int r = 1; r <= rings; ++r)
  {
    const double angleDeg = std::min(r * stepDeg, maxDeg);
    const double theta = angleDeg * Pi / 180.0;
    const int around = std::max(6, static_cast<int>(std::ceil(2.0 * Pi * std::sin(theta) / (stepDeg * Pi / 180.0) - 1e-9)));
    for (int k = 0; k < around; ++k)
    {
      const double phi = 2.0 * Pi * k / around;
      ConeDirection d;
      for (int a = 0; a < 3; ++a)
      {
        d.Direction[a] = std::cos(theta) * axis[a] + std::sin(theta) * (std::cos(phi) * u[a] + std::sin(phi) * v[a]);
      }
      d.Direction = Normalized(d.Direction);
      d.AngleDeg = angleDeg;
      directions.push_back(d);
    }
  }
  return directions;
}
} // namespace vp
