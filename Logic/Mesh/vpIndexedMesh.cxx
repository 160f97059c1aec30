#include "vpIndexedMesh.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace vp
{
namespace
{
struct PointKey
{
  std::array<std::uint64_t, 3> Bits;
  bool operator==(const PointKey& other) const { return Bits == other.Bits; }
};

struct PointKeyHash
{
  std::size_t operator()(const PointKey& k) const
  {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint64_t b : k.Bits)
    {
      h ^= b + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    }
    return static_cast<std::size_t>(h);
  }
};

PointKey MakeKey(const double p[3])
{
  PointKey key;
  for (int i = 0; i < 3; ++i)
  {
    const double v = p[i] == 0.0 ? 0.0 : p[i]; // -0 and +0 are the same point
    std::memcpy(&key.Bits[i], &v, sizeof(double));
  }
  return key;
}

bool IsDegenerate(const double a[3], const double b[3], const double c[3])
{
  const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double e2[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double e3[3] = { c[0] - b[0], c[1] - b[1], c[2] - b[2] };
  const double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
    e1[0] * e2[1] - e1[1] * e2[0] };
  const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double longest2 = std::max({ e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2],
    e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2], e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2] });
  // A sliver whose height is below 1e-12 of its longest edge has no direction of its own.
  return !(twiceArea > 1e-12 * longest2);
}
} // namespace

template <typename Real>
vtkSmartPointer<vtkPolyData> BuildIndexedMesh(
  const Real* coordinates, std::size_t triangleCount, std::size_t* degenerateDropped)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  auto connectivity = vtkSmartPointer<vtkIdTypeArray>::New();
  connectivity->SetNumberOfComponents(1);
  connectivity->Allocate(static_cast<vtkIdType>(triangleCount * 3));
  std::unordered_map<PointKey, vtkIdType, PointKeyHash> index;
  index.reserve(triangleCount); // closed meshes have about half as many points as triangles
  std::size_t dropped = 0;
  for (std::size_t t = 0; t < triangleCount; ++t)
  {
    double corner[3][3];
    vtkIdType ids[3];
    for (int k = 0; k < 3; ++k)
    {
      for (int i = 0; i < 3; ++i)
      {
        corner[k][i] = static_cast<double>(coordinates[9 * t + 3 * k + i]);
      }
      const auto inserted = index.emplace(MakeKey(corner[k]), points->GetNumberOfPoints());
      if (inserted.second)
      {
        points->InsertNextPoint(corner[k]);
      }
      ids[k] = inserted.first->second;
    }
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2] ||
      IsDegenerate(corner[0], corner[1], corner[2]))
    {
      ++dropped;
      continue;
    }
    for (vtkIdType id : ids)
    {
      connectivity->InsertNextValue(id);
    }
  }
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  polys->SetData(3, connectivity);
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  if (degenerateDropped)
  {
    *degenerateDropped = dropped;
  }
  return mesh;
}

template vtkSmartPointer<vtkPolyData> BuildIndexedMesh<float>(const float*, std::size_t, std::size_t*);
template vtkSmartPointer<vtkPolyData> BuildIndexedMesh<double>(const double*, std::size_t, std::size_t*);

vtkSmartPointer<vtkPolyData> MakeTriangleMesh(vtkPoints* points, const std::vector<std::array<vtkIdType, 3>>& triangles)
{
  vtkNew<vtkCellArray> cells;
  cells->AllocateExact(static_cast<vtkIdType>(triangles.size()), static_cast<vtkIdType>(3 * triangles.size()));
  for (const auto& t : triangles)
  {
    cells->InsertNextCell(3, t.data());
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(cells);
  return mesh;
}
} // namespace vp
