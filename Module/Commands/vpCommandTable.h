#ifndef vpCommandTable_h
#define vpCommandTable_h

#include "vpCliDescription.h"
#include "vpModuleServices.h"

#include <string>
#include <vector>

namespace vp
{
/// One subcommand of the module: what the host lists and dispatches.
struct CommandEntry
{
  const char* Name;
  /// Its parameters, usage and one-line title (what the host lists).
  cli::ModuleDescription (*Describe)();
  int (*Run)(const cli::ParsedArguments& args, const ModuleServices& module);
};

/// Every command of the VesselProximity module, in the order --help lists them (the demo
/// module's are DemoCommandTable(), in Module/Demo).
const std::vector<CommandEntry>& CommandTable();

/// Runs a command in its module: --help from its description, else its command line parsed
/// against it and the command called with the module (which creates its logic and overlays). What it throws becomes the documented exit code with one line on stderr (1 bad
/// input, 2 bad usage, 3 internal error, 4 no Vulkan device), so no exception crosses the
/// module's C boundary.
int RunCommandReportingErrors(const CommandEntry& command, const std::vector<std::string>& args, const ModuleServices& module);
} // namespace vp

#endif
