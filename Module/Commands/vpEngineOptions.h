#ifndef vpEngineOptions_h
#define vpEngineOptions_h

#include "vpArguments.h"
#include "vpDistanceEngineSettings.h"
#include "vpExactComparison.h"
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
/// The flag that sets a parameter of the logic (ParameterError's name: "RangeMm" -> "--range"),
/// or the name itself when no command has a flag for it.
std::string FlagOfParameter(const std::string& parameter);

/// The engine settings the options give (--range and the z-buffer's), for the given method.
DistanceEngineSettings ParseEngineSettings(const std::string& method, const Arguments& args);

/// The engine --method names, configured from the z-buffer options. "auto" is the z-buffer
/// engine when a Vulkan device opens, else the exact engine, with a note on stderr saying why.
/// "both" returns the z-buffer engine (the caller adds the exact one). Throws InputError for a
/// bad option and DeviceError when the z-buffer engine was asked for and there is no device.
vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const Arguments& args);
} // namespace vp

#endif
