#include "vpCommandSupport.h"

#include "vpEngineOptions.h"
#include "vtkScalpelModel.h"
#include "vtkVesselProximityLogic.h"

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

void ReportOpenedScene(
  const std::string& command, vtkVesselProximityLogic* proximity, const OpenedScene& scene, const std::string& scalpelFile)
{
  ReportEngineNote(scene.EngineNote);
  std::cerr << command << ": " << proximity->GetScalpel()->GetTipSource() << "\n";
  ReportSurfaceDefects(command, proximity->GetDistanceEngine(), scene.Vessels);
  if (scene.PenetrationUnknown)
  {
    std::cerr << command << ": " << scalpelFile
              << ": the surface is not closed, so the instrument's penetration depth and volume cannot be known (left empty)\n";
  }
}
} // namespace vp
