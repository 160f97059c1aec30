#include "vpModuleServices.h"

namespace vp
{
std::vector<std::string> VesselProximityServices::Contributors() const
{
  return { "VesselProximity developers (liver surgery navigation)" };
}

std::string VesselProximityServices::Version() const
{
  return VP_VERSION;
}

vtkSmartPointer<vtkVesselProximityLogic> VesselProximityServices::CreateLogic() const
{
  return vtkSmartPointer<vtkVesselProximityLogic>::New();
}

vtkSmartPointer<vtkVesselProximityOverlays> VesselProximityServices::CreateWidgetRepresentation() const
{
  return vtkSmartPointer<vtkVesselProximityOverlays>::New();
}
} // namespace vp
