#ifndef vpEngineOptions_h
#define vpEngineOptions_h

#include "vpArguments.h"
#include "vpDistanceEngineFactory.h"
#include "vpExactComparison.h"
#include "vtkVesselDistanceEngine.h"

#include <vtkSmartPointer.h>

#include <set>
#include <string>
#include <vector>

namespace vp
{
/// The options every command that computes distances shares: --method (one of methods, default
/// exact; left out when methods is empty: EngineMethodNames gives a front end's), --range and
/// the z-buffer's settings, each named for the logic setting it gives, so the logic's refusals
/// name the flag.
cli::ParameterGroup EngineOptions(const std::vector<std::string>& methods);

/// The engine settings the options give (--range and the z-buffer's), for the given method.
DistanceEngineSettings ParseEngineSettings(const std::string& method, const cli::ParsedArguments& args);

/// The engine --method names, configured from the z-buffer options. "auto" is the z-buffer
/// engine when a Vulkan device opens, else the exact engine, with a note on stderr saying why.
/// "both" returns the z-buffer engine (the caller adds the exact one). Throws InputError for a
/// bad option and DeviceError when the z-buffer engine was asked for and there is no device.
vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const cli::ParsedArguments& args);

/// The note of method auto when it fell back to the exact engine (empty: none), on stderr.
void ReportEngineNote(const std::string& note);
} // namespace vp

#endif
