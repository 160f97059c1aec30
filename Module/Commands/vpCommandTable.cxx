#include "vpCommandTable.h"

#include "vpCommands.h"
#include "vpEngineOptions.h"
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
    { "demo", "the main job on the built-in liver phantom: DICOM, models, tracked CUSA, both engines, report", RunDemoCommand },
    { "view", "interactive window: vessels, scalpel moved by mouse and keys or replayed, live overlays", RunViewCommand },
    { "selftest", "the module self-test: the demo's pipeline end to end with assertions", RunSelfTestCommand },
    { "models", "segmented labelmaps (DICOM series, DICOM SEG, NRRD, .seg.nrrd, NIfTI) to vessel surface models",
      RunModelsCommand },
    { "distance", "distance from scalpel tip(s) to each vessel class (exact, zbuffer, both, brute, auto)", RunDistanceCommand },
    { "track", "replay tracked scalpel poses: frames.csv, summary.json, distance.png, danger levels", RunTrackCommand },
    { "register", "scalpel registration: landmarks, surface ICP, pivot calibration (JSON result)", RunRegisterCommand },
    { "bench", "engines side by side with the brute-force reference, JSON with --json", RunBenchCommand },
    { "phantom", "write the built-in analytic vessels (STL) for a first run", RunPhantomCommand },
  };
  return table;
}

int RunCommandReportingErrors(const CommandEntry& command, const std::vector<std::string>& args)
{
  // Our errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  try
  {
    return command.Run(args);
  }
  catch (const ParameterError& e)
  {
    std::cerr << "vesselproximity: error: " << FlagOfParameter(e.GetParameter()) << ": " << e.GetProblem() << "\n";
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
} // namespace vp
