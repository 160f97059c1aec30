#include "vpAnalyticShapes.h"

#include "vpInputError.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <array>
#include <cmath>
#include <vector>

namespace vp
{
namespace
{
constexpr double Pi = 3.14159265358979323846;

/// Collects local-frame points and triangles, then places them.
class MeshBuilder
{
public:
  vtkIdType Add(double x, double y, double z)
  {
    this->Local.push_back({ x, y, z });
    return static_cast<vtkIdType>(this->Local.size() - 1);
  }
  void Triangle(vtkIdType a, vtkIdType b, vtkIdType c)
  {
    const vtkIdType ids[3] = { a, b, c };
    this->Polys->InsertNextCell(3, ids);
  }
  void Quad(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType d)
  {
    this->Triangle(a, b, c);
    this->Triangle(a, c, d);
  }
  vtkSmartPointer<vtkPolyData> Place(const double center[3], const double* axis)
  {
    double r[3][3];
    RotationFromZ(axis, r);
    auto points = vtkSmartPointer<vtkPoints>::New();
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(this->Local.size()));
    for (std::size_t i = 0; i < this->Local.size(); ++i)
    {
      const auto& p = this->Local[i];
      double q[3];
      for (int a = 0; a < 3; ++a)
      {
        q[a] = center[a] + r[a][0] * p[0] + r[a][1] * p[1] + r[a][2] * p[2];
      }
      points->SetPoint(static_cast<vtkIdType>(i), q);
    }
    auto mesh = vtkSmartPointer<vtkPolyData>::New();
    mesh->SetPoints(points);
    mesh->SetPolys(this->Polys);
    return mesh;
  }

private:
  std::vector<std::array<double, 3>> Local;
  vtkSmartPointer<vtkCellArray> Polys = vtkSmartPointer<vtkCellArray>::New();
};

void Require(bool ok, const char* what)
{
  if (!ok)
  {
    throw InputError("shape", what);
  }
}
} // namespace

void RotationFromZ(const double* axis, double r[3][3])
{
  double z[3] = { 0, 0, 1 };
  if (axis)
  {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    Require(n > 0, "axis must not be zero");
    z[0] = axis[0] / n;
    z[1] = axis[1] / n;
    z[2] = axis[2] / n;
  }
  // Any x perpendicular to z; y = z x x keeps the frame right-handed (windings stay outward).
  double x[3] = { 1, 0, 0 };
  if (std::abs(z[0]) > 0.9)
  {
    x[0] = 0;
    x[1] = 1;
  }
  const double d = x[0] * z[0] + x[1] * z[1] + x[2] * z[2];
  for (int a = 0; a < 3; ++a)
  {
    x[a] -= d * z[a];
  }
  const double xn = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (double& c : x)
  {
    c /= xn;
  }
  const double y[3] = { z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0] };
  for (int a = 0; a < 3; ++a)
  {
    r[a][0] = x[a];
    r[a][1] = y[a];
    r[a][2] = z[a];
  }
}

vtkSmartPointer<vtkPolyData> MakeSphere(const double center[3], double radius, int rings, int segments)
{
  Require(radius > 0 && rings >= 3 && segments >= 3, "sphere needs radius > 0, rings >= 3, segments >= 3");
  MeshBuilder m;
  const vtkIdType north = m.Add(0, 0, radius);
  std::vector<vtkIdType> ring(static_cast<std::size_t>((rings - 1) * segments));
  for (int i = 1; i < rings; ++i)
  {
    const double theta = Pi * i / rings;
    for (int j = 0; j < segments; ++j)
    {
      const double phi = 2 * Pi * j / segments;
      ring[(i - 1) * segments + j] = m.Add(radius * std::sin(theta) * std::cos(phi),
        radius * std::sin(theta) * std::sin(phi), radius * std::cos(theta));
    }
  }
  const vtkIdType south = m.Add(0, 0, -radius);
  auto at = [&](int i, int j) { return ring[(i - 1) * segments + (j % segments)]; };
  for (int j = 0; j < segments; ++j)
  {
    m.Triangle(north, at(1, j), at(1, j + 1));
    for (int i = 1; i + 1 < rings; ++i)
    {
      m.Quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
    m.Triangle(south, at(rings - 1, j + 1), at(rings - 1, j));
  }
  return m.Place(center, nullptr);
}

vtkSmartPointer<vtkPolyData> MakeCappedCylinder(
  const double center[3], const double* axis, double radius, double length, int segments)
{
  Require(radius > 0 && length > 0 && segments >= 3, "cylinder needs radius > 0, length > 0, segments >= 3");
  MeshBuilder m;
  const double h = 0.5 * length;
  std::vector<vtkIdType> bottom(segments), top(segments);
  for (int j = 0; j < segments; ++j)
  {
    const double phi = 2 * Pi * j / segments;
    bottom[j] = m.Add(radius * std::cos(phi), radius * std::sin(phi), -h);
    top[j] = m.Add(radius * std::cos(phi), radius * std::sin(phi), h);
  }
  const vtkIdType bottomCenter = m.Add(0, 0, -h);
  const vtkIdType topCenter = m.Add(0, 0, h);
  for (int j = 0; j < segments; ++j)
  {
    const int k = (j + 1) % segments;
    m.Quad(bottom[j], bottom[k], top[k], top[j]);
    m.Triangle(topCenter, top[j], top[k]);
    m.Triangle(bottomCenter, bottom[k], bottom[j]);
  }
  return m.Place(center, axis);
}

vtkSmartPointer<vtkPolyData> MakeTorus(const double center[3], const double* axis, double ringRadius,
  double tubeRadius, int ringSegments, int tubeSegments)
{
  Require(ringRadius > tubeRadius && tubeRadius > 0 && ringSegments >= 3 && tubeSegments >= 3,
    "torus needs ring radius > tube radius > 0 and >= 3 segments");
  MeshBuilder m;
  std::vector<vtkIdType> ids(static_cast<std::size_t>(ringSegments * tubeSegments));
  for (int i = 0; i < ringSegments; ++i)
  {
    const double u = 2 * Pi * i / ringSegments;
    for (int j = 0; j < tubeSegments; ++j)
    {
      const double v = 2 * Pi * j / tubeSegments;
      const double rho = ringRadius + tubeRadius * std::cos(v);
      ids[i * tubeSegments + j] = m.Add(rho * std::cos(u), rho * std::sin(u), tubeRadius * std::sin(v));
    }
  }
  auto at = [&](int i, int j) { return ids[(i % ringSegments) * tubeSegments + (j % tubeSegments)]; };
  for (int i = 0; i < ringSegments; ++i)
  {
    for (int j = 0; j < tubeSegments; ++j)
    {
      m.Quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return m.Place(center, axis);
}
} // namespace vp
