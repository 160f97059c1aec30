#ifndef vpSurfaceReport_h
#define vpSurfaceReport_h

#include "vpVesselMeshSet.h"

#include <nlohmann/json.hpp>

#include <vector>

class vtkVesselDistanceEngine;

namespace vp
{
class VesselSurface;

/// "closed", the triangles and the defects' counts of one surface, as the JSON reports give them.
nlohmann::ordered_json SurfaceJson(const VesselSurface& surface);
/// Per class of a built engine: SurfaceJson, and what a repair did ("repair") when it was made.
nlohmann::ordered_json SurfacesJson(vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);
} // namespace vp

#endif
