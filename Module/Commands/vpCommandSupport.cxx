#include "vpCommandSupport.h"

#include "vpInputError.h"
#include "vtkVesselDistanceEngine.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <set>

namespace vp
{
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs)
{
  std::vector<NamedMesh> meshes;
  std::set<std::string> seen;
  for (const auto& pair : pairs)
  {
    if (!seen.insert(pair.first).second)
    {
      throw InputError("--vessels", "class '" + pair.first + "' is given twice");
    }
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(pair.second);
    reader->Read();
    meshes.push_back({ pair.first, pair.second, reader->GetOutput(), std::nullopt });
  }
  return meshes;
}

void RepairVesselMeshes(std::vector<NamedMesh>& meshes)
{
  for (NamedMesh& m : meshes)
  {
    vtkNew<vtkVesselSurfaceRepair> repair;
    repair->SetInputData(m.Mesh);
    repair->Update();
    m.Mesh = repair->GetOutput();
    m.Repair = repair->GetReport();
  }
}

double NowMs()
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes)
{
  for (const NamedMesh& m : meshes)
  {
    if (m.Repair)
    {
      std::cerr << command << ": " << m.ClassName << " (" << m.FileName << "): --repair: " << m.Repair->Describe() << "\n";
    }
  }
  for (int c = 0; c < engine->GetNumberOfVessels(); ++c)
  {
    const VesselSurface& surface = engine->GetSurface(c);
    if (surface.IsClosed())
    {
      continue;
    }
    std::string file;
    for (const NamedMesh& m : meshes)
    {
      file = m.ClassName == surface.Name() ? m.FileName : file;
    }
    std::cerr << command << ": " << surface.Name() << " (" << file << "): the surface is not closed ("
              << surface.Defects().Describe() << "): "
              << "inside is the majority of five rays' crossing parities, and a tip where they disagree is a breach"
              << "\n";
  }
}

nlohmann::ordered_json SurfaceJson(const VesselSurface& surface)
{
  const MeshDefects& d = surface.Defects();
  return { { "closed", surface.IsClosed() }, { "triangles", surface.NumberOfTriangles() },
    { "boundary_edges", d.BoundaryEdges }, { "non_manifold_edges", d.NonManifoldEdges },
    { "inconsistent_edges", d.InconsistentEdges }, { "components", d.Components } };
}

nlohmann::ordered_json SurfacesJson(vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes)
{
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int c = 0; c < engine->GetNumberOfVessels(); ++c)
  {
    const VesselSurface& surface = engine->GetSurface(c);
    nlohmann::ordered_json& entry = out[surface.Name()];
    entry = SurfaceJson(surface);
    for (const NamedMesh& m : meshes)
    {
      if (m.ClassName == surface.Name() && m.Repair)
      {
        const SurfaceRepairReport& r = *m.Repair;
        entry["repair"] = { { "merged_points", r.MergedPoints }, { "removed_degenerate_triangles", r.RemovedDegenerate },
          { "removed_duplicated_triangles", r.RemovedDuplicates }, { "removed_fin_triangles", r.RemovedFins },
          { "filled_holes", r.FilledHoles }, { "added_triangles", r.AddedTriangles },
          { "turned_triangles", r.TurnedTriangles }, { "description", r.Describe() } };
      }
    }
  }
  return out;
}
} // namespace vp
