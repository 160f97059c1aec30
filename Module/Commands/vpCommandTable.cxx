#include "vpCommandTable.h"

#include "vpCommands.h"
#include "vpArguments.h"
#include "vpInputError.h"
#include "vpVulkanContext.h"

#include <vtkObject.h>

#include <exception>
#include <iostream>
#include <new>

namespace vp
{
const std::vector<CommandEntry>& CommandTable()
{
  static const std::vector<CommandEntry> table{
    { "demo", DescribeDemoCommand, RunDemoCommand },
    { "view", DescribeViewCommand, RunViewCommand },
    { "selftest", DescribeSelfTestCommand, RunSelfTestCommand },
    { "models", DescribeModelsCommand, RunModelsCommand },
    { "distance", DescribeDistanceCommand, RunDistanceCommand },
    { "track", DescribeTrackCommand, RunTrackCommand },
    { "register", DescribeRegisterCommand, RunRegisterCommand },
    { "bench", DescribeBenchCommand, RunBenchCommand },
    { "phantom", DescribePhantomCommand, RunPhantomCommand },
  };
  return table;
}

namespace
{
/// The exception being handled, as one line on stderr and its exit code.
int ReportFailure(const cli::ModuleDescription& description)
{
  try
  {
    throw;
  }
  catch (const cli::UsageError& e)
  {
    std::cerr << "vesselproximity: error: " << e.what() << "\n";
    return 2;
  }
  catch (const ParameterError& e)
  {
    std::cerr << "vesselproximity: error: " << cli::DisplayNameOfSetting(description, e.GetParameter()) << ": "
              << e.GetProblem() << "\n";
    return 1;
  }
  catch (const InputError& e)
  {
    std::cerr << "vesselproximity: error: " << e.what() << "\n";
    return 1;
  }
  catch (const DeviceError& e)
  {
    std::cerr << "vesselproximity: error: " << e.what() << "\n";
    return 4;
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << "vesselproximity: error: out of memory\n";
    return 3;
  }
  catch (const std::exception& e)
  {
    std::cerr << "vesselproximity: internal error: " << e.what() << "\n";
    return 3;
  }
}
} // namespace

int RunCommandReportingErrors(const CommandEntry& command, const std::vector<std::string>& args, const ModuleServices& module)
{
  // Our errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  const cli::ModuleDescription description = command.Describe();
  try
  {
    cli::ValidateDescription(description);
    if (WantsHelp(args))
    {
      std::cout << cli::WriteHelp(description);
      return 0;
    }
    return command.Run(cli::ParseArguments(description, args), module);
  }
  catch (...)
  {
    return ReportFailure(description);
  }
}
} // namespace vp
