#ifndef vpVesselProximityDemoModule_h
#define vpVesselProximityDemoModule_h

#include "vpModuleServices.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

/// The VesselProximity demo module: the built-in liver phantom and the CUSA-like handpiece, the
/// demo that tracks one through the other, the module self-test and the benchmarks. A module of
/// its own, as Slicer keeps its sample data and self-tests apart from the modules they exercise,
/// so that the VesselProximity module a host embeds links neither the phantom generators nor the
/// measurements. It runs on the VesselProximity module's logic and overlays, as a Slicer module
/// uses the logic of a module it depends on.
class vpVesselProximityDemoModule : public vp::VesselProximityServices
{
public:
  std::string Name() const { return "VesselProximityDemo"; }
  std::string Title() const { return "Vessel Proximity Demo"; }
  std::vector<std::string> Categories() const { return { "IGT", "Developer Tools" }; }
  std::string HelpText() const;
  std::string AcknowledgementText() const;
};

#endif
