#ifndef vpCommandTable_h
#define vpCommandTable_h

#include <string>
#include <vector>

namespace vp
{
/// One subcommand of the module: what the host lists and dispatches.
struct CommandEntry
{
  const char* Name;
  const char* Summary;
  int (*Run)(const std::vector<std::string>& args);
};

/// Every command of the VesselProximity module, in the order --help lists them.
const std::vector<CommandEntry>& CommandTable();

/// Runs a command and turns what it throws into the documented exit codes with one line on
/// stderr (1 bad input, 3 internal error, 4 no Vulkan device), so no exception crosses the
/// module's C boundary.
int RunCommandReportingErrors(const CommandEntry& command, const std::vector<std::string>& args);
} // namespace vp

#endif
