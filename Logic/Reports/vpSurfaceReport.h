#ifndef vpSurfaceReport_h
#define vpSurfaceReport_h

#include "vpSurfaceJson.h"
#include "vpVesselMeshSet.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

class vtkVesselDistanceEngine;

namespace vp
{
class VesselSurface;

/// Per class of a built engine: SurfaceJson, and what a repair did ("repair") when it was made.
nlohmann::ordered_json SurfacesJson(vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);
/// One line per repaired class saying what the repair changed, then one per class whose surface
/// in the built engine is not closed: its file, its defects, and how its inside is decided, so
/// that nobody reads a vote or a null as the exact answer of a closed surface. repairName is how
/// the front end names the repair (a command says its flag). Each line starts with the class name.
std::vector<std::string> DescribeSurfaceDefects(
  vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes, const std::string& repairName);
/// One line per tumour whose surface is not closed: its id, file, defects, and how its inside is
/// decided (a vote of rays; an undecided one counts as inside, so the margin reads violated).
std::vector<std::string> DescribeTumourDefects(const std::vector<NamedMesh>& tumours);
} // namespace vp

#endif
