#include "vpCommandSupport.h"

#include <iostream>

namespace vp
{
void ReportSurfaceDefects(const std::string& command, vtkVesselDistanceEngine* engine, const std::vector<NamedMesh>& meshes)
{
  for (const std::string& line : DescribeSurfaceDefects(engine, meshes, "--repair"))
  {
    std::cerr << command << ": " << line << "\n";
  }
}
} // namespace vp
