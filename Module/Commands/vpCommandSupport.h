#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpQuantile.h"
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

class vtkPolyData;
class vtkVesselDistanceEngine;

namespace vp
{
struct NamedMesh
{
  std::string ClassName;
  std::string FileName;
  vtkSmartPointer<vtkPolyData> Mesh;
};

/// Reads each CLASS=FILE pair; throws InputError naming the file on any problem, and for a class
/// named twice.
std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs);

/// Creates an output folder and its missing parents, like mkdir -p; returns whether it was new.
/// Throws InputError naming the folder when it cannot be made.
bool CreateOutputFolder(const std::string& folder);

/// One line on stderr (after the engine's Build()) for each class whose surface is not closed:
/// its file, its defects, and how its inside is decided, so that nobody reads a vote or a null as
/// the exact pseudonormal answer of a closed surface.
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes);
/// Per class (after Build()): "closed", and the defects' counts, for the JSON reports.
nlohmann::ordered_json SurfacesJson(vtkVesselDistanceEngine* engine);

/// Milliseconds since an arbitrary origin (steady clock).
double NowMs();
} // namespace vp

#endif
