#ifndef vpDistanceEngineFactory_h
#define vpDistanceEngineFactory_h

#include "vpDistanceEngineSettings.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <string>
#include <vector>

namespace vp
{
/// Where a method is offered: the front ends' kinds of work (bits of EngineMethod::Offered).
enum EngineOffer : unsigned
{
  OfferedForTips = 1u,      ///< tips answered in a batch (the distance command)
  OfferedForTracking = 2u,  ///< a tracked instrument's frames (track, live, Slicer's track CLI)
  OfferedInView = 4u,       ///< the interactive view
  OfferedToSlicerTips = 8u, ///< Slicer's distance CLI
};

/// One way to answer: the registry of engines (EngineMethods) is the one place that lists them;
/// --method's choices and help, the Slicer CLIs' enumerations and MakeDistanceEngine come from it.
struct EngineMethod
{
  const char* Name; ///< DistanceEngineSettings::Method, --method's value
  const char* Help; ///< one phrase, "exact: Embree BVH, exact"
  unsigned Offered; ///< EngineOffer bits
  /// The engine, set up from the settings and its device opened; note (may be null) says why
  /// a fallback was taken.
  vtkSmartPointer<vtkVesselDistanceEngine> (*Make)(const DistanceEngineSettings& settings, std::string* note);
};

/// Every method, in the order front ends list them.
const std::vector<EngineMethod>& EngineMethods();
/// The methods offered for a kind of work (an EngineOffer bit), by name.
std::vector<std::string> EngineMethodNames(EngineOffer offer);
/// Their help phrases joined by separator.
std::string EngineMethodHelp(const std::vector<std::string>& names, const std::string& separator);

/// The engine the settings describe, its Vulkan device opened (a missing one is reported before
/// any file is read). Throws ParameterError naming the setting for a bad value, and DeviceError
/// when the z-buffer engine was asked for and there is no device. With Method auto and no device,
/// the exact engine, and *note (when given) says why.
vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const DistanceEngineSettings& settings, std::string* note = nullptr);
} // namespace vp

#endif
