#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpQuantile.h"
#include "vpRunFolder.h" // CreateOutputFolder
#include "vtkVesselSurfaceRepair.h"
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

class vtkPolyData;
class vtkVesselDistanceEngine;
namespace vp
{
class VesselSurface;
}

namespace vp
{
struct NamedMesh
{
  std::string ClassName;
  std::string FileName;
  vtkSmartPointer<vtkPolyData> Mesh;
  /// What --repair did to it (absent without --repair).
  std::optional<SurfaceRepairReport> Repair;
};

/// Reads each CLASS=FILE pair; throws InputError naming the file on any problem, and for a class
/// named twice.
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs);

/// --repair: each mesh replaced by what vtkVesselSurfaceRepair makes of it, its report kept
/// (ReportSurfaceDefects says what changed).
void RepairVesselMeshes(std::vector<NamedMesh>& meshes);


/// One line on stderr (after the engine's Build(), so that no line comes before a refusal) for
/// each class --repair went over, saying what it changed, and for each class whose surface is
/// not closed: its file, its defects, and how its inside is decided, so that nobody reads a vote
/// or a null as the exact pseudonormal answer of a closed surface.
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);
/// "closed", the triangles and the defects' counts of one surface.
nlohmann::ordered_json SurfaceJson(const VesselSurface& surface);
/// Per class (after Build()): "closed", and the defects' counts, for the JSON reports; with
/// --repair, what the repair did ("repair").
nlohmann::ordered_json SurfacesJson(vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);

/// Milliseconds since an arbitrary origin (steady clock).
double NowMs();
} // namespace vp

#endif
