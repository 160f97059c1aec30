#include "vpMeshRefinement.h"

#include "vpIndexedMesh.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
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

std::uint64_t EdgeKey(vtkIdType a, vtkIdType b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

/// Each edge's midpoint, made once and shared by the triangles on the edge.
class Midpoints
{
public:
  explicit Midpoints(vtkPoints* points)
    : Points(points)
  {
  }
  vtkIdType Of(vtkIdType a, vtkIdType b)
  {
    const auto [it, made] = this->Made.try_emplace(EdgeKey(a, b), 0);
    if (made)
    {
      double x[3], y[3];
      this->Points->GetPoint(a, x);
      this->Points->GetPoint(b, y);
      it->second = this->Points->InsertNextPoint(0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1]), 0.5 * (x[2] + y[2]));
    }
    return it->second;
  }

private:
  vtkPoints* Points;
  std::unordered_map<std::uint64_t, vtkIdType> Made;
};

/// Every triangle into four at its edges' midpoints.
std::vector<Tri> Quarter(vtkPoints* points, const std::vector<Tri>& tris)
{
  Midpoints mid(points);
  std::vector<Tri> next;
  next.reserve(tris.size() * 4);
  for (const Tri& t : tris)
  {
    const vtkIdType ab = mid.Of(t[0], t[1]), bc = mid.Of(t[1], t[2]), ca = mid.Of(t[2], t[0]);
    next.push_back({ t[0], ab, ca });
    next.push_back({ ab, t[1], bc });
    next.push_back({ ca, bc, t[2] });
    next.push_back({ ab, bc, ca });
  }
  return next;
}

/// Bisects edges, the triangles' longest first, each with both its triangles (an edge of more
/// is left alone) and no triangle twice, until the mesh has at least target triangles or no
/// edge is left; returns whether any was split.
bool BisectLongestEdges(vtkPoints* points, std::vector<Tri>& tris, std::size_t target)
{
  struct Side
  {
    std::uint64_t Key;
    std::size_t Triangle;
    int Local; // the edge from corner Local to corner Local + 1
  };
  std::vector<Side> sides;
  sides.reserve(tris.size() * 3);
  std::vector<std::pair<double, std::size_t>> byLongest(tris.size());
  std::vector<int> longest(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
  {
    double best = -1.0;
    for (int e = 0; e < 3; ++e)
    {
      sides.push_back({ EdgeKey(tris[i][e], tris[i][(e + 1) % 3]), i, e });
      const double l = Length2(points, tris[i][e], tris[i][(e + 1) % 3]);
      if (l > best)
      {
        best = l;
        longest[i] = e;
      }
    }
    byLongest[i] = { -best, i };
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) { return x.Key < y.Key; });
  std::sort(byLongest.begin(), byLongest.end());
  std::vector<bool> used(tris.size(), false);
  std::vector<Tri> added;
  Midpoints mid(points);
  std::size_t count = tris.size();
  for (const auto& [negativeLength, i] : byLongest)
  {
    if (count >= target)
    {
      break;
    }
    if (used[i])
    {
      continue;
    }
    const std::uint64_t key = EdgeKey(tris[i][longest[i]], tris[i][(longest[i] + 1) % 3]);
    auto first = std::lower_bound(sides.begin(), sides.end(), key, [](const Side& s, std::uint64_t k) { return s.Key < k; });
    auto last = first;
    while (last != sides.end() && last->Key == key)
    {
      ++last;
    }
    // An edge of more than two triangles, or twice in one (a triangle without area), is left.
    if (last - first > 2 || (last - first == 2 && first->Triangle == (first + 1)->Triangle) ||
      std::any_of(first, last, [&](const Side& s) { return used[s.Triangle]; }))
    {
      continue;
    }
    const vtkIdType m = mid.Of(tris[i][longest[i]], tris[i][(longest[i] + 1) % 3]);
    for (auto s = first; s != last; ++s)
    {
      Tri& t = tris[s->Triangle];
      const vtkIdType a = t[s->Local], b = t[(s->Local + 1) % 3], c = t[(s->Local + 2) % 3];
      t = { a, m, c };
      added.push_back({ m, b, c });
      used[s->Triangle] = true;
      ++count;
    }
  }
  tris.insert(tris.end(), added.begin(), added.end());
  return !added.empty();
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
  // Whole rounds while quartering stays within the target, then bisections for the rest.
  while (!tris.empty() && tris.size() * 4 <= target)
  {
    tris = Quarter(points, tris);
  }
  while (tris.size() < target && BisectLongestEdges(points, tris, target))
  {
  }
  return MakeTriangleMesh(points, tris);
}
} // namespace vp
