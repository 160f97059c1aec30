#include "vpSurfaceReport.h"

#include "vpClassName.h"
#include "vpVesselSurface.h"
#include "vtkVesselDistanceEngine.h"

namespace vp
{
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

std::vector<std::string> DescribeSurfaceDefects(
  vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes, const std::string& repairName)
{
  std::vector<std::string> lines;
  for (const NamedMesh& m : meshes)
  {
    if (m.Repair)
    {
      lines.push_back(m.ClassName + " (" + m.FileName + "): " + repairName + ": " + m.Repair->Describe());
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
    lines.push_back(surface.Name() + " (" + file + "): the surface is not closed (" + surface.Defects().Describe() +
      "): inside is the majority of five rays' crossing parities, and a tip where they disagree is a breach");
  }
  return lines;
}

std::vector<std::string> DescribeTumourDefects(const std::vector<NamedMesh>& tumours)
{
  std::vector<std::string> lines;
  for (const NamedMesh& t : tumours)
  {
    const VesselSurface surface(t.ClassName, t.Mesh);
    if (!surface.IsClosed())
    {
      lines.push_back(TumourSpoken(t.ClassName) + " (" + t.FileName + "): the surface is not closed (" +
        surface.Defects().Describe() + "): inside is the majority of five rays' crossing parities, and a tip where they " +
        "disagree is inside");
    }
  }
  return lines;
}
} // namespace vp
