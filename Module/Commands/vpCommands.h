#ifndef vpCommands_h
#define vpCommands_h

#include "vpCliDescription.h"
#include "vpModuleServices.h"

namespace vp
{
/// Each subcommand of the VesselProximity module (the demo module's are in vpDemoCommands.h)
/// declares its parameters once (Describe…), and the command table parses its command line with
/// them (and answers --help from them). Run… takes the parsed arguments, writes
/// its result to stdout (or files), and returns the process exit code. Bad input throws
/// InputError, caught by the table.
cli::ModuleDescription DescribeDistanceCommand();
int RunDistanceCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeBatchCommand();
int RunBatchCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeModelsCommand();
int RunModelsCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeTrackCommand();
int RunTrackCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeLiveCommand();
int RunLiveCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeServeCommand();
int RunServeCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeRegisterCommand();
int RunRegisterCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribeViewCommand();
int RunViewCommand(const cli::ParsedArguments& args, const ModuleServices& module);
cli::ModuleDescription DescribePlanCommand();
int RunPlanCommand(const cli::ParsedArguments& args, const ModuleServices& module);
} // namespace vp

#endif
