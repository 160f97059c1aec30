#ifndef vpDefectiveMeshes_h
#define vpDefectiveMeshes_h

// Shared by the tests of inside on defective meshes and of their repair: a closed surface made
// defective in each of the ways exports and hand edits make them.
#include "vpTestSupport.h"
#include "vpTriangleGeometry.h"
#include "vpVesselSurface.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselSurfaceRepair.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vp
{
namespace test
{
using Points = std::vector<std::array<double, 3>>;
using Triangles = std::vector<std::array<std::int32_t, 3>>;

inline vtkSmartPointer<vtkPolyData> MakeMesh(const Points& points, const Triangles& triangles)
{
  vtkNew<vtkPoints> p;
  p->SetDataTypeToDouble(); // the copies keep the original's points to the last bit
  for (const auto& x : points)
  {
    p->InsertNextPoint(x.data());
  }
  vtkNew<vtkCellArray> cells;
  for (const auto& t : triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    cells->InsertNextCell(3, ids);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(p);
  mesh->SetPolys(cells);
  return mesh;
}

inline std::array<double, 3> Centroid(const Points& points, const std::array<std::int32_t, 3>& t)
{
  std::array<double, 3> c{};
  for (int k = 0; k < 3; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      c[a] += points[t[k]][a] / 3.0;
    }
  }
  return c;
}

// The triangles whose centroid lies within radiusMm of the centroid of triangle `around`.
inline std::vector<std::size_t> Patch(const Points& points, const Triangles& triangles, std::size_t around, double radiusMm)
{
  const auto centre = Centroid(points, triangles[around]);
  std::vector<std::size_t> patch;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    if (vp::Distance2(Centroid(points, triangles[t]).data(), centre.data()) <= radiusMm * radiusMm)
    {
      patch.push_back(t);
    }
  }
  return patch;
}

struct Defective
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
  std::function<bool(const vp::MeshDefects&)> Reported;
};

inline std::vector<Defective> DefectiveCopies(const Points& points, const Triangles& triangles)
{
  std::vector<Defective> copies;
  const std::size_t at = triangles.size() / 3; // somewhere along the vessel, not at its start
  {
    Triangles holed = triangles;
    holed.erase(holed.begin() + static_cast<std::ptrdiff_t>(at));
    copies.push_back({ "one triangle removed (a hole)", MakeMesh(points, holed),
      [](const vp::MeshDefects& d) { return d.BoundaryEdges == 3 && d.NonManifoldEdges == 0; } });
  }
  {
    // A point duplicated, the copy taken by one triangle: a crack around it (as exports that
    // write each face's points on their own leave them, when their points are not merged).
    Points cracked = points;
    Triangles crack = triangles;
    cracked.push_back(points[triangles[at][0]]);
    crack[at][0] = static_cast<std::int32_t>(cracked.size() - 1);
    copies.push_back({ "a point duplicated (a crack)", MakeMesh(cracked, crack),
      [](const vp::MeshDefects& d) { return d.BoundaryEdges == 4 && d.NonManifoldEdges == 0; } });
  }
  {
    // A point duplicated and a triangle repeated on the copy: its far edge is shared by three
    // triangles (non-manifold), its two others by one (boundary), where an export wrote a face
    // twice with its own points.
    Points repeated = points;
    Triangles twice = triangles;
    repeated.push_back(points[triangles[at][0]]);
    twice.push_back({ static_cast<std::int32_t>(repeated.size() - 1), triangles[at][1], triangles[at][2] });
    copies.push_back({ "a triangle repeated on a duplicated point (non-manifold)", MakeMesh(repeated, twice),
      [](const vp::MeshDefects& d) { return d.NonManifoldEdges == 1 && d.BoundaryEdges == 2; } });
  }
  {
    // A fin: a new triangle on an edge of the surface, standing 1 mm out of it.
    Points finned = points;
    Triangles fin = triangles;
    const auto& t = triangles[at];
    std::array<double, 3> tip{};
    for (int a = 0; a < 3; ++a)
    {
      tip[a] = 0.5 * (points[t[0]][a] + points[t[1]][a]) + (points[t[0]][a] - points[t[2]][a]) * 0.1;
    }
    finned.push_back(tip);
    fin.push_back({ t[0], t[1], static_cast<std::int32_t>(finned.size() - 1) });
    copies.push_back({ "a fin on an edge (non-manifold)", MakeMesh(finned, fin),
      [](const vp::MeshDefects& d) { return d.NonManifoldEdges == 1; } });
  }
  {
    Triangles flipped = triangles;
    for (std::size_t t : Patch(points, triangles, at, 3.0))
    {
      std::swap(flipped[t][1], flipped[t][2]);
    }
    copies.push_back({ "a patch wound the wrong way", MakeMesh(points, flipped),
      [](const vp::MeshDefects& d) { return d.InconsistentEdges > 0; } });
  }
  {
    Triangles doubled = triangles;
    for (std::size_t t : Patch(points, triangles, at, 3.0))
    {
      doubled.push_back(triangles[t]);
    }
    copies.push_back({ "a duplicated sheet", MakeMesh(points, doubled),
      [](const vp::MeshDefects& d) { return d.NonManifoldEdges > 0; } });
  }
  return copies;
}

/// IRCADb's vessel meshes of patients 1 and 4 ("3Dircadb1.4 portal_vein", ...) that
/// vtkVesselSurfaceRepair closes; empty without the extracted data.
inline std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> ClosedIrcadbVessels()
{
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> closed;
  const std::string extracted = ExtractedDataDir();
  if (extracted.empty())
  {
    return closed;
  }
  for (const char* patient : { "3Dircadb1.1", "3Dircadb1.4" })
  {
    for (const auto& [className, file] : { std::make_pair("portal_vein", "portalvein.vtk"),
           std::make_pair("hepatic_vein", "venoussystem.vtk"), std::make_pair("hepatic_artery", "artery.vtk") })
    {
      vtkNew<vtkVesselMeshReader> reader;
      reader->SetFileName(extracted + "/ircadb/" + patient + "/MESHES_VTK/" + file);
      reader->Read();
      vtkNew<vtkVesselSurfaceRepair> repair;
      repair->SetInputData(reader->GetOutput());
      repair->Update();
      if (!repair->GetReport().After.Any())
      {
        closed.emplace_back(std::string(patient) + " " + className, repair->GetOutput());
      }
    }
  }
  return closed;
}
} // namespace test
} // namespace vp

#endif
