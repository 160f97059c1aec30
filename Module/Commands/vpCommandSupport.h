#ifndef vpCommandSupport_h
#define vpCommandSupport_h

#include "vpQuantile.h"
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>
#include <utility>
#include <vector>

class vtkPolyData;

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

/// Milliseconds since an arbitrary origin (steady clock).
double NowMs();
} // namespace vp

#endif
