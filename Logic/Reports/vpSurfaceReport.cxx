#include "vpSurfaceReport.h"

#include "vpVesselSurface.h"
#include "vtkVesselDistanceEngine.h"

namespace vp
{
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
