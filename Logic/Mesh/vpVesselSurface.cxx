#include "vpVesselSurface.h"

#include "vpInputError.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vp
{
namespace
{
struct DirectedEdge
{
  std::uint64_t Key; // undirected: (min << 32) | max
  std::int32_t Triangle;
  std::int8_t Local;   // 0: ab, 1: bc, 2: ca
  bool Forward;        // traversed min -> max
};

std::int32_t FindRoot(std::vector<std::int32_t>& parent, std::int32_t i)
{
  while (parent[i] != i)
  {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void Normalize(std::array<double, 3>& v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (n > 0)
  {
    v[0] /= n;
    v[1] /= n;
    v[2] /= n;
  }
}
/// Pairs the sorted directed edges: each shared edge links its two triangles (neighbours, and
/// their pieces in parent); what cannot pair is counted as a defect, with the pieces.
MeshDefects PairEdges(const std::vector<DirectedEdge>& edges, std::vector<std::array<std::int32_t, 3>>& neighbours,
  std::vector<std::int32_t>& parent, std::vector<std::array<std::int32_t, 2>>& oddEdges)
{
  MeshDefects defects;
  for (std::size_t i = 0; i < edges.size();)
  {
    std::size_t j = i;
    while (j < edges.size() && edges[j].Key == edges[i].Key)
    {
      ++j;
    }
    if ((j - i) % 2 == 1)
    {
      oddEdges.push_back({ static_cast<std::int32_t>(edges[i].Key >> 32), static_cast<std::int32_t>(edges[i].Key & 0xFFFFFFFFu) });
    }
    if (j - i == 1)
    {
      ++defects.BoundaryEdges;
    }
    else if (j - i > 2)
    {
      ++defects.NonManifoldEdges;
    }
    else
    {
      const DirectedEdge& x = edges[i];
      const DirectedEdge& y = edges[i + 1];
      if (x.Forward == y.Forward)
      {
        ++defects.InconsistentEdges;
      }
      neighbours[x.Triangle][x.Local] = y.Triangle;
      neighbours[y.Triangle][y.Local] = x.Triangle;
      parent[FindRoot(parent, x.Triangle)] = FindRoot(parent, y.Triangle);
    }
    i = j;
  }
  for (std::size_t t = 0; t < parent.size(); ++t)
  {
    defects.Components += FindRoot(parent, static_cast<std::int32_t>(t)) == static_cast<std::int32_t>(t) ? 1 : 0;
  }
  return defects;
}
} // namespace

VesselSurface::VesselSurface(const std::string& name, vtkPolyData* mesh)
  : ClassName(name)
{
  if (!mesh || !mesh->GetPoints() || mesh->GetNumberOfPolys() == 0)
  {
    throw InputError(name, "vessel mesh has no triangles");
  }
  vtkPoints* points = mesh->GetPoints();
  const vtkIdType n = points->GetNumberOfPoints();
  if (n >= std::numeric_limits<std::int32_t>::max())
  {
    throw InputError(name, "vessel mesh has too many points");
  }
  this->Points.resize(static_cast<std::size_t>(n));
  this->BoundsMm = { std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
    std::numeric_limits<double>::max(), -std::numeric_limits<double>::max() };
  auto iter = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  std::vector<bool> used(static_cast<std::size_t>(n), false);
  for (iter->GoToFirstCell(); !iter->IsDoneWithTraversal(); iter->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iter->GetCurrentCell(size, ids);
    // Fan-triangulate polygons; callers normally pass triangles already.
    for (vtkIdType k = 1; k + 1 < size; ++k)
    {
      this->Triangles.push_back({ static_cast<std::int32_t>(ids[0]),
        static_cast<std::int32_t>(ids[k]), static_cast<std::int32_t>(ids[k + 1]) });
      used[ids[0]] = used[ids[k]] = used[ids[k + 1]] = true;
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->GetPoint(i, this->Points[i].data());
    if (!used[i])
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const double c = this->Points[i][a];
      if (!std::isfinite(c))
      {
        throw InputError(name, "vessel mesh has a NaN or infinite coordinate");
      }
      this->BoundsMm[2 * a] = std::min(this->BoundsMm[2 * a], c);
      this->BoundsMm[2 * a + 1] = std::max(this->BoundsMm[2 * a + 1], c);
    }
  }
  if (this->Triangles.empty())
  {
    throw InputError(name, "vessel mesh has no triangles");
  }
  this->BuildTopology();
}

void VesselSurface::BuildTopology()
{
  const std::size_t nt = this->Triangles.size();
  std::vector<DirectedEdge> edges;
  edges.reserve(nt * 3);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const auto& tri = this->Triangles[t];
    for (int e = 0; e < 3; ++e)
    {
      const std::uint32_t u = static_cast<std::uint32_t>(tri[e]);
      const std::uint32_t v = static_cast<std::uint32_t>(tri[(e + 1) % 3]);
      const std::uint64_t key = u < v ? (std::uint64_t(u) << 32) | v : (std::uint64_t(v) << 32) | u;
      edges.push_back({ key, static_cast<std::int32_t>(t), static_cast<std::int8_t>(e), u < v });
    }
  }
  std::sort(edges.begin(), edges.end(),
    [](const DirectedEdge& x, const DirectedEdge& y) { return x.Key < y.Key; });

  std::vector<std::array<std::int32_t, 3>> neighbours(nt, { -1, -1, -1 });
  std::vector<std::int32_t> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  this->DefectCounts = PairEdges(edges, neighbours, parent, this->OddEdgeList);
  this->Closed = !this->DefectCounts.Any();
  if (!this->Closed)
  {
    return;
  }
  std::vector<std::array<double, 3>> faceNormals = this->OutwardFaceNormals(parent);
  this->VertexNormals = this->AngleWeightedVertexNormals(faceNormals);
  this->FaceNormals = std::move(faceNormals);
  this->Neighbours = std::move(neighbours);
}

std::vector<std::array<double, 3>> VesselSurface::OutwardFaceNormals(std::vector<std::int32_t>& parent) const
{
  const std::size_t nt = this->Triangles.size();
  // Each connected piece faces outward when its enclosed volume is positive.
  std::vector<double> volume(nt, 0.0);
  std::vector<std::array<double, 3>> faceNormals(nt);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const double* a = this->Point(this->Triangles[t][0]);
    const double* b = this->Point(this->Triangles[t][1]);
    const double* c = this->Point(this->Triangles[t][2]);
    double ab[3], ac[3], bc[3];
    Sub3(b, a, ab);
    Sub3(c, a, ac);
    Cross3(ab, ac, faceNormals[t].data());
    Cross3(b, c, bc);
    volume[FindRoot(parent, static_cast<std::int32_t>(t))] += Dot3(a, bc) / 6.0;
  }
  for (std::size_t t = 0; t < nt; ++t)
  {
    if (volume[FindRoot(parent, static_cast<std::int32_t>(t))] < 0)
    {
      for (double& c : faceNormals[t])
      {
        c = -c;
      }
    }
    Normalize(faceNormals[t]);
  }
  return faceNormals;
}

std::vector<std::array<double, 3>> VesselSurface::AngleWeightedVertexNormals(
  const std::vector<std::array<double, 3>>& faceNormals) const
{
  const std::size_t nt = this->Triangles.size();
  std::vector<std::array<double, 3>> vertexNormals(this->Points.size(), { 0.0, 0.0, 0.0 });
  for (std::size_t t = 0; t < nt; ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const double* p = this->Point(this->Triangles[t][k]);
      const double* q = this->Point(this->Triangles[t][(k + 1) % 3]);
      const double* r = this->Point(this->Triangles[t][(k + 2) % 3]);
      double u[3], v[3];
      Sub3(q, p, u);
      Sub3(r, p, v);
      const double cosine = Dot3(u, v) / std::sqrt(Dot3(u, u) * Dot3(v, v));
      const double angle = std::acos(std::clamp(cosine, -1.0, 1.0));
      for (int a = 0; a < 3; ++a)
      {
        vertexNormals[this->Triangles[t][k]][a] += angle * faceNormals[t][a];
      }
    }
  }
  return vertexNormals;
}

std::string MeshDefects::Describe() const
{
  std::string text;
  auto add = [&](std::size_t n, const char* what) {
    if (n > 0)
    {
      text += (text.empty() ? "" : ", ") + std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    }
  };
  add(this->BoundaryEdges, "boundary edge");
  add(this->NonManifoldEdges, "non-manifold edge");
  add(this->InconsistentEdges, "inconsistently wound edge");
  if (text.empty())
  {
    text = "closed";
  }
  return text + ", " + std::to_string(this->Components) + (this->Components == 1 ? " component" : " components");
}

std::optional<bool> VesselSurface::IsInside(
  const double p[3], std::size_t t, const double closest[3], TriangleFeature feature) const
{
  if (!this->Closed)
  {
    return std::nullopt;
  }
  double direction[3];
  Sub3(p, closest, direction);
  // Within a picometre the point is on the surface (rounding decides the side beyond that):
  // touching is reported as distance 0, not as a breach.
  if (Dot3(direction, direction) <= 1e-18)
  {
    return false;
  }
  const auto& tri = this->Triangles[t];
  std::array<double, 3> normal{};
  auto edgeNormal = [&](int local) {
    const auto& other = this->FaceNormals[this->Neighbours[t][local]];
    for (int a = 0; a < 3; ++a)
    {
      normal[a] = this->FaceNormals[t][a] + other[a];
    }
  };
  switch (feature)
  {
    case TriangleFeature::Face:
      normal = this->FaceNormals[t];
      break;
    case TriangleFeature::EdgeAB:
      edgeNormal(0);
      break;
    case TriangleFeature::EdgeBC:
      edgeNormal(1);
      break;
    case TriangleFeature::EdgeCA:
      edgeNormal(2);
      break;
    case TriangleFeature::VertexA:
      normal = this->VertexNormals[tri[0]];
      break;
    case TriangleFeature::VertexB:
      normal = this->VertexNormals[tri[1]];
      break;
    case TriangleFeature::VertexC:
      normal = this->VertexNormals[tri[2]];
      break;
  }
  return Dot3(direction, normal.data()) < 0.0;
}
} // namespace vp
