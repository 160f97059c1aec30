#include "vpLiveOptions.h"

#include "vpArguments.h"
#include "vpInputError.h"
#include "vpPoseFile.h"
#include "vpTrackingOptions.h"

#include <cstdlib>
#include <iostream>

namespace vp
{
namespace
{
/// "HOST:PORT" (the host may be a name or an IPv4 address).
std::pair<std::string, int> ParseHostPort(const std::string& text)
{
  const auto colon = text.rfind(':');
  char* end = nullptr;
  const long port = colon == std::string::npos ? -1 : std::strtol(text.c_str() + colon + 1, &end, 10);
  if (colon == std::string::npos || colon == 0 || end == text.c_str() + colon + 1 || *end != '\0' || port < 1 || port > 65535)
  {
    throw InputError("--igtl", "expected HOST:PORT (a port 1 to 65535), got '" + text + "'");
  }
  return { text.substr(0, colon), static_cast<int>(port) };
}
} // namespace

std::vector<cli::Parameter> LiveStreamOptions(bool toolRequired, bool withReading)
{
  using cli::ParameterType;
  const std::vector<cli::Parameter> reading = PoseReadingOptions();
  cli::Parameter tool = Option(ParameterType::String, "tool-name",
    "The TRANSFORM device (or QTDATA/TDATA element) carrying the scalpel's pose, e.g. StylusToTracker.")
                          .SetPlaceholder("NAME")
                          .SetLogicName("ToolName");
  if (toolRequired)
  {
    tool.SetRequired();
  }
  std::vector<cli::Parameter> options = {
    Option(ParameterType::String, "igtl", "Connect to a tracker's OpenIGTLink server (PlusServer), reconnecting when it is lost.")
      .SetPlaceholder("HOST:PORT"),
    Option(ParameterType::String, "igtl-listen",
      "Serve on this port for clients (3D Slicer, a tracker client); 0: any free port. PORT alone serves this machine's "
      "own programs (loopback); HOST:PORT serves on that address, e.g. the operating room network's 192.168.1.20:18944 "
      "for a Slicer on another machine (0.0.0.0: every interface).")
      .SetPlaceholder("[HOST:]PORT")
      .SetLogicName("ListenPort"),
    Option(ParameterType::String, "pose-from",
      "With --igtl-listen and no --igtl: only a client from this address may steer the scalpel (default: the first "
      "client that sends the tool's pose). The tool's poses from any other peer are refused and counted.")
      .SetPlaceholder("HOST")
      .SetLogicName("PoseFromHost"),
    tool,
    Option(ParameterType::StringEnumeration, "results-to",
      "Which peers the results go to: listen (the clients of --igtl-listen, 3D Slicer), tracker (the --igtl server) or "
      "all. A PlusServer logs a warning for each message type it does not know, so the tracker is sent nothing unless "
      "asked.")
      .SetDefault("listen")
      .SetElements({ "listen", "tracker", "all" })
      .SetLogicName("ResultsTo"),
    Option(ParameterType::Double, "stale-ms", "No pose for this long is tracking lost: said, sent to the peers and recorded.")
      .SetPlaceholder("MS")
      .SetDefault("200")
      .SetLogicName("StaleMs"),
    Option(ParameterType::Double, "duration-s", "Stop after this long (0: at Ctrl-C).").SetPlaceholder("S").SetDefault("0"),
  };
  if (withReading)
  {
    options.insert(options.begin() + 3, { reading[0], reading[1], reading[5] });
  }
  return options;
}

bool WantsLiveStream(const cli::ParsedArguments& args)
{
  return args.IsSet("igtl") || args.IsSet("igtlListen");
}

IgtlLinkSettings ParseLiveStream(const cli::ParsedArguments& args)
{
  IgtlLinkSettings link;
  if (!WantsLiveStream(args))
  {
    throw InputError("--igtl/--igtl-listen", "give --igtl HOST:PORT (a tracker's server), --igtl-listen [HOST:]PORT, or both");
  }
  if (args.IsSet("igtl"))
  {
    std::tie(link.ConnectHost, link.ConnectPort) = ParseHostPort(args.GetString("igtl"));
  }
  if (args.IsSet("igtlListen"))
  {
    std::tie(link.ListenHost, link.ListenPort) = ParseListenAddress(args);
  }
  if (args.IsSet("poseFrom"))
  {
    if (!args.IsSet("igtlListen") || args.IsSet("igtl"))
    {
      throw InputError("--pose-from", "names the client that steers among those --igtl-listen serves; with --igtl the tracker steers");
    }
    link.PoseFromHost = args.GetString("poseFrom");
  }
  if (!args.IsSet("toolName"))
  {
    throw InputError("--tool-name", "name the tool whose pose the stream carries (a TRANSFORM device or a tracking element)");
  }
  link.ToolName = args.GetString("toolName");
  if (link.ToolName.size() > IgtlDeviceNameBytes)
  {
    throw InputError("--tool-name", "'" + link.ToolName + "' is " + std::to_string(link.ToolName.size()) +
      " bytes; an OpenIGTLink device or element name holds " + std::to_string(IgtlDeviceNameBytes) + ", so no message could carry it");
  }
  const std::string to = args.GetString("resultsTo"); // an enumeration: checked
  link.ResultsTo = to == "all" ? IgtlResultsTo::All : to == "tracker" ? IgtlResultsTo::Tracker : IgtlResultsTo::Listeners;
  const PoseReading reading = ParsePoseFrame(args);
  link.Reading = SettlePoseReading(reading);
  return link;
}

std::pair<std::string, int> ParseListenAddress(const cli::ParsedArguments& args)
{
  const std::string text = args.GetString("igtlListen");
  const auto colon = text.rfind(':');
  const std::string host = colon == std::string::npos ? "127.0.0.1" : text.substr(0, colon);
  const std::string number = colon == std::string::npos ? text : text.substr(colon + 1);
  char* end = nullptr;
  const long port = std::strtol(number.c_str(), &end, 10);
  if (number.empty() || *end != '\0' || port < 0 || port > 65535 || host.empty())
  {
    throw InputError("--igtl-listen", "expected PORT or HOST:PORT (a port 0 to 65535), got '" + text + "'");
  }
  return { host, static_cast<int>(port) };
}

void PrintLinkEvents(const std::string& command, IgtlLink& link)
{
  for (const std::string& event : link.TakeEvents())
  {
    std::cerr << command << ": " << event << "\n";
  }
}

double ParseStaleMs(const cli::ParsedArguments& args)
{
  const double staleMs = args.GetNumber("staleMs");
  if (!(staleMs > 0.0))
  {
    throw InputError("--stale-ms", "expected a time in ms above 0, got '" + args.GetString("staleMs") + "'");
  }
  return staleMs;
}

double ParseDurationS(const cli::ParsedArguments& args)
{
  const double durationS = args.GetNumber("durationS");
  if (!(durationS >= 0.0))
  {
    throw InputError("--duration-s", "expected a time in s, 0 or more, got '" + args.GetString("durationS") + "'");
  }
  return durationS;
}
} // namespace vp
