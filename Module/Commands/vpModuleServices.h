#ifndef vpModuleServices_h
#define vpModuleServices_h

#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityOverlays.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace vp
{
/// What a command asks of the module it runs in, as a Slicer module's widget asks its module:
/// the logic, and the widget representation that draws it. The module class
/// (vpVesselProximityModule) is the one that creates them; the entry point hands it to every
/// command through the command table.
class ModuleServices
{
public:
  virtual ~ModuleServices() = default;
  virtual vtkSmartPointer<vtkVesselProximityLogic> CreateLogic() const = 0;
  virtual vtkSmartPointer<vtkVesselProximityOverlays> CreateWidgetRepresentation() const = 0;
};

/// What the VesselProximity module and its demo module share: they run on one logic and one
/// widget representation, by the same people, at the same version. Each adds its name, title,
/// categories, help and acknowledgement.
class VesselProximityServices : public ModuleServices
{
public:
  std::vector<std::string> Contributors() const;
  std::string Version() const;
  vtkSmartPointer<vtkVesselProximityLogic> CreateLogic() const override;
  vtkSmartPointer<vtkVesselProximityOverlays> CreateWidgetRepresentation() const override;
};
} // namespace vp

#endif
