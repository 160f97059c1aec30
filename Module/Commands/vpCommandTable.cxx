#include "vpCommandTable.h"

#include "vpCommands.h"
#include "vpArguments.h"

#include <vtkObject.h>

#include <iostream>

namespace vp
{
const std::vector<CommandEntry>& CommandTable()
{
  static const std::vector<CommandEntry> table{
    { "view", DescribeViewCommand, RunViewCommand },
    { "models", DescribeModelsCommand, RunModelsCommand },
    { "distance", DescribeDistanceCommand, RunDistanceCommand },
    { "track", DescribeTrackCommand, RunTrackCommand },
    { "batch", DescribeBatchCommand, RunBatchCommand },
    { "live", DescribeLiveCommand, RunLiveCommand },
    { "serve", DescribeServeCommand, RunServeCommand },
    { "register", DescribeRegisterCommand, RunRegisterCommand },
    { "plan", DescribePlanCommand, RunPlanCommand },
  };
  return table;
}

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
      return cli::FinishStandardOutput("vesselproximity", 0);
    }
    return cli::FinishStandardOutput("vesselproximity", command.Run(cli::ParseArguments(description, args), module));
  }
  catch (...)
  {
    return cli::ReportFailure(description, "vesselproximity");
  }
}
} // namespace vp
