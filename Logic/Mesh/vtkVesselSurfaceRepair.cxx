#include "vtkVesselSurfaceRepair.h"

#include "vpIndexedMesh.h"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkFillHolesFilter.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataNormals.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkVesselSurfaceRepair);

namespace
{
using Triangle = std::array<vtkIdType, 3>;

std::vector<Triangle> Triangles(vtkPolyData* mesh)
{
  std::vector<Triangle> out;
  out.reserve(static_cast<std::size_t>(mesh->GetNumberOfPolys()));
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
  {
    if (ids->GetNumberOfIds() == 3)
    {
      out.push_back({ ids->GetId(0), ids->GetId(1), ids->GetId(2) });
    }
  }
  return out;
}

using EdgeKey = std::pair<vtkIdType, vtkIdType>;
EdgeKey Key(vtkIdType a, vtkIdType b)
{
  return a < b ? EdgeKey{ a, b } : EdgeKey{ b, a };
}

std::map<EdgeKey, std::vector<std::size_t>> EdgeUses(const std::vector<Triangle>& triangles)
{
  std::map<EdgeKey, std::vector<std::size_t>> uses;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    for (int e = 0; e < 3; ++e)
    {
      uses[Key(triangles[t][e], triangles[t][(e + 1) % 3])].push_back(t);
    }
  }
  return uses;
}

// The first of each set of triangles on the same three points, in order. (VTK 9.1's
// vtkRemoveDuplicatePolys does the same but leaks a vtkIdList whenever it finds no duplicate,
// which fails every sanitizer run that repairs a surface without one.)
std::vector<Triangle> WithoutDuplicates(const std::vector<Triangle>& triangles)
{
  std::set<Triangle> seen;
  std::vector<Triangle> kept;
  kept.reserve(triangles.size());
  for (const Triangle& t : triangles)
  {
    Triangle key = t;
    std::sort(key.begin(), key.end());
    if (seen.insert(key).second)
    {
      kept.push_back(t);
    }
  }
  return kept;
}

// A fin hangs off a non-manifold edge by that edge alone: its two other edges are its own. Such
// a triangle encloses nothing, and it is what an export leaves when it glues a stray face on.
std::vector<Triangle> WithoutFins(const std::vector<Triangle>& triangles, std::size_t& removed)
{
  const auto uses = EdgeUses(triangles);
  std::vector<bool> fin(triangles.size(), false);
  for (const auto& [edge, users] : uses)
  {
    if (users.size() < 3)
    {
      continue;
    }
    for (std::size_t t : users)
    {
      int own = 0;
      for (int e = 0; e < 3; ++e)
      {
        own += uses.at(Key(triangles[t][e], triangles[t][(e + 1) % 3])).size() == 1 ? 1 : 0;
      }
      fin[t] = fin[t] || own == 2;
    }
  }
  std::vector<Triangle> kept;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    if (!fin[t])
    {
      kept.push_back(triangles[t]);
    }
  }
  removed = triangles.size() - kept.size();
  return kept;
}

// The boundary's loops: the pieces of the graph of edges used by one triangle.
std::size_t BoundaryLoops(const std::vector<Triangle>& triangles)
{
  std::map<vtkIdType, vtkIdType> parent;
  auto root = [&](vtkIdType v) {
    while (parent[v] != v)
    {
      v = parent[v] = parent[parent[v]];
    }
    return v;
  };
  for (const auto& [edge, users] : EdgeUses(triangles))
  {
    if (users.size() == 1)
    {
      parent.emplace(edge.first, edge.first);
      parent.emplace(edge.second, edge.second);
      parent[root(edge.first)] = root(edge.second);
    }
  }
  std::size_t loops = 0;
  for (const auto& [v, p] : parent)
  {
    loops += root(v) == v ? 1 : 0;
  }
  return loops;
}

std::size_t UsedPoints(const std::vector<Triangle>& triangles)
{
  std::set<vtkIdType> used;
  for (const Triangle& t : triangles)
  {
    used.insert(t.begin(), t.end());
  }
  return used.size();
}

// Whether b is a with its winding reversed (the same three points, the other cyclic order).
bool Reversed(const Triangle& a, const Triangle& b)
{
  for (int r = 0; r < 3; ++r)
  {
    if (a[0] == b[r] && a[1] == b[(r + 2) % 3] && a[2] == b[(r + 1) % 3])
    {
      return true;
    }
  }
  return false;
}

void Plural(std::ostringstream& out, bool& first, std::size_t n, const char* what, const char* thing)
{
  if (n == 0)
  {
    return;
  }
  out << (first ? "" : ", ") << what << " " << n << " " << thing << (n == 1 ? "" : "s");
  first = false;
}
} // namespace

namespace vp
{
std::string SurfaceRepairReport::Describe() const
{
  std::ostringstream out;
  bool first = true;
  Plural(out, first, this->MergedPoints, "merged", "coincident point");
  Plural(out, first, this->RemovedDegenerate, "removed", "degenerate triangle");
  Plural(out, first, this->RemovedDuplicates, "removed", "duplicated triangle");
  Plural(out, first, this->RemovedFins, "removed", "fin triangle");
  if (this->FilledHoles > 0 || this->AddedTriangles > 0)
  {
    out << (first ? "" : ", ") << "filled " << this->FilledHoles << " hole" << (this->FilledHoles == 1 ? "" : "s")
        << " with " << this->AddedTriangles << " triangle" << (this->AddedTriangles == 1 ? "" : "s");
    first = false;
  }
  Plural(out, first, this->TurnedTriangles, "turned", "triangle");
  if (first)
  {
    out << "nothing to repair";
  }
  out << "; " << (this->After.Any() ? "still not closed (" + this->After.Describe() + ")" : "now " + this->After.Describe());
  return out.str();
}
} // namespace vp

vtkVesselSurfaceRepair::vtkVesselSurfaceRepair() = default;
vtkVesselSurfaceRepair::~vtkVesselSurfaceRepair() = default;

void vtkVesselSurfaceRepair::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaximumHoleRadiusMm: " << this->MaximumHoleRadiusMm << "\n";
  os << indent << "Report: " << this->Report.Describe() << "\n";
}

int vtkVesselSurfaceRepair::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Report = {};
  vp::SurfaceRepairReport& report = this->Report;

  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->SetInputData(input);
  triangulate->Update();
  const std::vector<Triangle> given = Triangles(triangulate->GetOutput());
  if (given.empty())
  {
    output->Initialize();
    return 1;
  }
  vtkSmartPointer<vtkPolyData> mesh = vp::MakeTriangleMesh(triangulate->GetOutput()->GetPoints(), given);
  report.Before = vp::VesselSurface("repair", mesh).Defects();

  // Exact coincidence only: a tolerance would move points, and a repair must not move the wall.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(mesh);
  clean->PointMergingOn();
  clean->ToleranceIsAbsoluteOn();
  clean->SetAbsoluteTolerance(0.0);
  clean->ConvertPolysToLinesOff();
  clean->ConvertLinesToPointsOff();
  clean->Update();
  std::vector<Triangle> cleaned = Triangles(clean->GetOutput());
  report.MergedPoints = UsedPoints(given) - UsedPoints(cleaned);
  report.RemovedDegenerate = given.size() - cleaned.size();

  const std::vector<Triangle> deduplicated = WithoutDuplicates(cleaned);
  report.RemovedDuplicates = cleaned.size() - deduplicated.size();

  std::vector<Triangle> current = WithoutFins(deduplicated, report.RemovedFins);
  vtkSmartPointer<vtkPoints> points = clean->GetOutput()->GetPoints();

  const std::size_t loopsBefore = BoundaryLoops(current);
  if (loopsBefore > 0 && this->MaximumHoleRadiusMm > 0.0)
  {
    vtkNew<vtkFillHolesFilter> fill;
    fill->SetInputData(vp::MakeTriangleMesh(points, current));
    fill->SetHoleSize(this->MaximumHoleRadiusMm);
    vtkNew<vtkTriangleFilter> fillTriangles;
    fillTriangles->SetInputConnection(fill->GetOutputPort());
    fillTriangles->Update();
    const std::vector<Triangle> filled = Triangles(fillTriangles->GetOutput());
    report.AddedTriangles = filled.size() - current.size();
    report.FilledHoles = loopsBefore - std::min(loopsBefore, BoundaryLoops(filled));
    current = filled;
    points = fillTriangles->GetOutput()->GetPoints();
  }

  // One winding for every piece; which way each piece faces is VesselSurface's to decide (by
  // the sign of its volume), so no auto-orientation here. The filter skips its consistency pass
  // when it is asked for no normals at all, hence the cell normals nobody reads.
  vtkNew<vtkPolyDataNormals> wind;
  wind->SetInputData(vp::MakeTriangleMesh(points, current));
  wind->ConsistencyOn();
  wind->SplittingOff();
  wind->AutoOrientNormalsOff();
  wind->ComputePointNormalsOff();
  wind->ComputeCellNormalsOn();
  wind->Update();
  const std::vector<Triangle> wound = Triangles(wind->GetOutput());
  // Only the given triangles count as turned: the hole filler's come in either winding, and
  // vtkFillHolesFilter appends them after the given ones.
  const std::size_t kept = current.size() - report.AddedTriangles;
  for (std::size_t t = 0; t < std::min(wound.size(), kept); ++t)
  {
    report.TurnedTriangles += Reversed(current[t], wound[t]) ? 1 : 0;
  }

  vtkSmartPointer<vtkPolyData> repaired = vp::MakeTriangleMesh(points, wound);
  report.After = vp::VesselSurface("repair", repaired).Defects();
  output->ShallowCopy(repaired);
  return 1;
}
