#include "vpMeshRefinement.h"

#include "vpIndexedMesh.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <vector>

namespace vp
{
namespace
{
using Tri = std::array<vtkIdType, 3>;

double Length2(vtkPoints* p, vtkIdType a, vtkIdType b)
{
  double x[3], y[3];
  p->GetPoint(a, x);
  p->GetPoint(b, y);
  return (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
}

void Split(vtkPoints* points, const Tri& t, std::vector<Tri>& out)
{
  int longest = 0;
  double best = -1;
  for (int e = 0; e < 3; ++e)
  {
    const double l = Length2(points, t[e], t[(e + 1) % 3]);
    if (l > best)
    {
      best = l;
      longest = e;
    }
  }
  const vtkIdType a = t[longest], b = t[(longest + 1) % 3], c = t[(longest + 2) % 3];
  double x[3], y[3];
  points->GetPoint(a, x);
  points->GetPoint(b, y);
  const vtkIdType m = points->InsertNextPoint(0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1]), 0.5 * (x[2] + y[2]));
  out.push_back({ a, m, c });
  out.push_back({ m, b, c });
}
} // namespace

vtkSmartPointer<vtkPolyData> RefineToTriangleCount(vtkPolyData* mesh, std::size_t target)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->DeepCopy(mesh->GetPoints());
  std::vector<Tri> tris;
  auto iter = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    iter->GetCurrentCell(n, ids);
    if (n == 3)
    {
      tris.push_back({ ids[0], ids[1], ids[2] });
    }
  }
  // Whole rounds while doubling stays within the target, then the largest of the rest.
  while (!tris.empty() && tris.size() * 2 <= target)
  {
    std::vector<Tri> next;
    next.reserve(tris.size() * 2);
    for (const Tri& t : tris)
    {
      Split(points, t, next);
    }
    tris.swap(next);
  }
  if (!tris.empty() && tris.size() < target)
  {
    const std::size_t extra = target - tris.size();
    std::vector<std::pair<double, std::size_t>> bySize(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i)
    {
      bySize[i] = { -std::max({ Length2(points, tris[i][0], tris[i][1]), Length2(points, tris[i][1], tris[i][2]),
                      Length2(points, tris[i][2], tris[i][0]) }), i };
    }
    std::nth_element(bySize.begin(), bySize.begin() + static_cast<std::ptrdiff_t>(extra), bySize.end());
    std::vector<bool> split(tris.size(), false);
    for (std::size_t k = 0; k < extra; ++k)
    {
      split[bySize[k].second] = true;
    }
    std::vector<Tri> next;
    next.reserve(target);
    for (std::size_t i = 0; i < tris.size(); ++i)
    {
      if (split[i])
      {
        Split(points, tris[i], next);
      }
      else
      {
        next.push_back(tris[i]);
      }
    }
    tris.swap(next);
  }
  return MakeTriangleMesh(points, tris);
}
} // namespace vp
