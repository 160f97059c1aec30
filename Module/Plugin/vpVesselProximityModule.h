#ifndef vpVesselProximityModule_h
#define vpVesselProximityModule_h

#include "vpModuleServices.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

/// The VesselProximity loadable module, as qSlicerVesselProximityModule would be in Slicer: it
/// declares the module's metadata and creates its logic and its widget representation, nothing
/// more. Every command runs in it: the entry point hands it to the command table, and the
/// commands take their logic and overlays from it. The computation lives in the logic (Logic/), the drawing in the overlays (Widgets/),
/// the commands in Module/Commands; the C entry point (vpVesselProximityModulePlugin.cxx) hands
/// all of it to the host.
class vpVesselProximityModule : public vp::VesselProximityServices
{
public:
  std::string Name() const { return "VesselProximity"; }
  std::string Title() const { return "Vessel Proximity"; }
  std::vector<std::string> Categories() const { return { "IGT" }; }
  std::string HelpText() const;
  std::string AcknowledgementText() const;
};

#endif
