#ifndef vpDemoCommands_h
#define vpDemoCommands_h

#include "vpCommandTable.h"

namespace vp
{
/// The demo module's commands, declared as the VesselProximity module's are (vpCommands.h): the
/// built-in phantom, the demo on it, the module's self-test and the benchmarks, which need the
/// phantom generators and the measurements that a host embedding the logic does not.
cli::ModuleDescription DescribeDemoCommand();
int RunDemoCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeSelfTestCommand();
int RunSelfTestCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeBenchCommand();
int RunBenchCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribePhantomCommand();
int RunPhantomCommand(const cli::ParsedArguments& args, const ModuleServices& module);

/// The demo module's commands, in the order --help lists them.
const std::vector<CommandEntry>& DemoCommandTable();
} // namespace vp

#endif
