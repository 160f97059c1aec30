// vesselproximity: the host program. Dispatches to the subcommands documented in DESIGN.md.
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpVulkanContext.h"

#include <vtkObject.h>

#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const char* Help =
  "usage: vesselproximity COMMAND [options]   (COMMAND --help for its options)\n"
  "commands:\n"
  "  models     segmented labelmaps (DICOM series, NRRD, .seg.nrrd, NIfTI) to vessel surface models\n"
  "  distance   distance from scalpel tip(s) to each vessel class (exact, zbuffer, both, brute, auto)\n"
  "  track      replay tracked scalpel poses: frames.csv, summary.json, distance.png, danger levels\n"
  "  register   scalpel registration: landmarks, surface ICP, pivot calibration (JSON result)\n"
  "  bench      engines side by side with the brute-force reference, JSON with --json\n"
  "  phantom    write the built-in analytic vessels (STL) for a first run\n"
  "exit codes: 0 success, 1 bad input (one line on stderr names the file and the problem),\n"
  "            2 bad usage, 3 internal error, 4 no usable Vulkan device (z-buffer engine)\n";
}

int main(int argc, char* argv[])
{
  // Our errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help"))
  {
    std::cout << Help;
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version"))
  {
    std::cout << "vesselproximity " VP_VERSION "\n";
    return 0;
  }
  const std::string command = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  try
  {
    if (command == "models")
    {
      return vp::RunModelsCommand(args);
    }
    if (command == "distance")
    {
      return vp::RunDistanceCommand(args);
    }
    if (command == "track")
    {
      return vp::RunTrackCommand(args);
    }
    if (command == "register")
    {
      return vp::RunRegisterCommand(args);
    }
    if (command == "bench")
    {
      return vp::RunBenchCommand(args);
    }
    if (command == "phantom")
    {
      return vp::RunPhantomCommand(args);
    }
    std::cerr << "vesselproximity: error: unknown command '" << command << "' (see vesselproximity --help)\n";
    return 2;
  }
  catch (const vp::InputError& e)
  {
    std::cerr << "vesselproximity: error: " << e.what() << "\n";
    return 1;
  }
  catch (const vp::DeviceError& e)
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
