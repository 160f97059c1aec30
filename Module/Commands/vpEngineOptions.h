#ifndef vpEngineOptions_h
#define vpEngineOptions_h

#include "vpArguments.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <set>
#include <string>
#include <vector>

namespace vp
{
/// The options every command that computes distances shares, with their help text.
/// The engine settings' help (--range and the z-buffer's).
extern const char* EngineSettingsUsage;
/// --method's help, listing only the methods the command accepts, then EngineSettingsUsage.
std::string EngineOptionsUsage(const std::set<std::string>& methods);
std::set<std::string> EngineValueOptions();

/// The engine --method names, configured from the z-buffer options. "auto" is the z-buffer
/// engine when a Vulkan device opens, else the exact engine, with a note on stderr saying why.
/// "both" returns the z-buffer engine (the caller adds the exact one). Throws InputError for a
/// bad option and DeviceError when the z-buffer engine was asked for and there is no device.
vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const Arguments& args);

/// The accuracy contract of one answer against the exact one: within boundMm when both are in
/// range; out of range when the exact one is, unless it lies within boundMm beyond the range.
bool WithinErrorBound(const ClassProximity& answer, const ClassProximity& exact, double rangeMm, double boundMm);

/// An engine's answers checked against the exact engine's, tip by tip: the largest difference
/// where both are in range, and the answers that break the accuracy contract above.
struct ExactComparison
{
  double MaxAbsDifferenceMm = 0.0;
  int Compared = 0;     ///< class answers in range in both
  int OutsideBound = 0; ///< class answers outside WithinErrorBound
  /// Adds one tip (the same classes in the same order); within, when given, receives one flag
  /// per class.
  void Add(const ProximityResult& answer, const ProximityResult& exact, double rangeMm, double boundMm,
    std::vector<char>* within = nullptr);
};
} // namespace vp

#endif
