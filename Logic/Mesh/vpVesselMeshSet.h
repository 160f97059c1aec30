#ifndef vpVesselMeshSet_h
#define vpVesselMeshSet_h

#include "vtkVesselSurfaceRepair.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

class vtkVesselDistanceEngine;

namespace vp
{
/// One vessel class's surface as read from its file.
struct NamedMesh
{
  std::string ClassName;
  std::string FileName;
  vtkSmartPointer<vtkPolyData> Mesh;
  /// What RepairVesselMeshes did to it (absent when it was not repaired).
  std::optional<SurfaceRepairReport> Repair;
};

/// Reads each (class, file) pair; throws InputError naming the file on any problem, and
/// ParameterError("Vessels") for a class named twice.
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs);

/// Each mesh replaced by what vtkVesselSurfaceRepair makes of it, its report kept.
void RepairVesselMeshes(std::vector<NamedMesh>& meshes);

/// One line per repaired class saying what the repair changed, then one per class whose surface
/// in the built engine is not closed: its file, its defects, and how its inside is decided, so
/// that nobody reads a vote or a null as the exact answer of a closed surface. repairName is how
/// the front end names the repair (a command says its flag). Each line starts with the class name.
std::vector<std::string> DescribeSurfaceDefects(
  vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes, const std::string& repairName);
} // namespace vp

#endif
