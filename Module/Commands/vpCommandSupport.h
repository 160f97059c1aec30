#ifndef vpCommandSupport_h
#define vpCommandSupport_h

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

/// Value at quantile q (0..1) of the samples, by nearest rank; 0 for none.
double Quantile(std::vector<double> samples, double q);

/// Creates an output folder and its missing parents, like mkdir -p; returns whether it was new.
/// Throws InputError naming the folder when it cannot be made.
bool CreateOutputFolder(const std::string& folder);

/// Milliseconds since an arbitrary origin (steady clock).
double NowMs();
} // namespace vp

#endif
