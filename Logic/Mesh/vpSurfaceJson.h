#ifndef vpSurfaceJson_h
#define vpSurfaceJson_h

#include <nlohmann/json.hpp>

namespace vp
{
class VesselSurface;

/// "closed", the triangles and the defects' counts of one surface, as the JSON reports give them
/// (models.json, summary.json, the distance report).
nlohmann::ordered_json SurfaceJson(const VesselSurface& surface);
} // namespace vp

#endif
