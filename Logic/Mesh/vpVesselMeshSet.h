#ifndef vpVesselMeshSet_h
#define vpVesselMeshSet_h

#include "vtkVesselSurfaceRepair.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>


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
  /// What the user reads ("tumour 03 (livertumor03)", from a models.json); empty: ClassName.
  std::string DisplayName = {};
};

/// Each vessel with its surface: the one given (Mesh), else read from its FileName. Throws
/// InputError naming the file on any problem, and ParameterError("Vessels") for a class named
/// twice or a name that cannot be a class's (ClassNameProblem).
std::vector<NamedMesh> LoadVesselMeshes(std::vector<NamedMesh> vessels);
/// The same for (class, file) pairs, every surface read.
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs);

/// The tumours' surfaces, each under its id (NamedMesh::ClassName): the one given, else read from
/// its FileName. Throws InputError naming the file on any problem, and ParameterError("Tumours")
/// for an id that could not be a class's name (vp::ClassNameProblem) or one given twice.
std::vector<NamedMesh> LoadTumourMeshes(std::vector<NamedMesh> tumours);

/// The tumours of a list of entries, each FILE (its id: the file's name without its extension,
/// what a class name may not hold made '_', "tumour_" before one that does not start with a
/// letter; made unique by "_2", "_3"), ID=FILE (the id as given), or a models folder or its
/// models.json (every tumour it lists, under its id and display name). Nothing but a models.json
/// is read. Throws InputError(source, ...) for an entry without a file, and InputError naming the
/// models.json for one that is not one or lists no tumour.
std::vector<NamedMesh> TumourEntries(const std::vector<std::string>& entries, const std::string& source);

/// Each mesh replaced by what vtkVesselSurfaceRepair makes of it, its report kept.
void RepairVesselMeshes(std::vector<NamedMesh>& meshes);

} // namespace vp

#endif
