#include "vpSurfaceJson.h"

#include "vpVesselSurface.h"

namespace vp
{
nlohmann::ordered_json SurfaceJson(const VesselSurface& surface)
{
  const MeshDefects& d = surface.Defects();
  return { { "closed", surface.IsClosed() }, { "triangles", surface.NumberOfTriangles() },
    { "boundary_edges", d.BoundaryEdges }, { "non_manifold_edges", d.NonManifoldEdges },
    { "inconsistent_edges", d.InconsistentEdges }, { "components", d.Components } };
}
} // namespace vp
