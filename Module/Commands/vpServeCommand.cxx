// vesselproximity serve: a recording served over OpenIGTLink at its own times, as PlusServer's
// saved-data source replays one: the live path exercised with real tracking data, no tracker.
#include "vpArguments.h"
#include "vpCommands.h"
#include "vpIgtlPoseStreamer.h"
#include "vpInputError.h"
#include "vpLiveOptions.h"
#include "vpPoseFile.h"
#include "vpSignalHold.h"
#include "vpTrackingOptions.h"

#include <atomic>
#include <cstdio>
#include <iostream>

namespace vp
{
cli::ModuleDescription DescribeServeCommand()
{
  using cli::ParameterType;
  std::vector<cli::Parameter> stream = {
    Option(ParameterType::File, "poses", "The recording: a PLUS sequence (.igs.mha, .igs.nrrd), a pose CSV or JSON.")
      .SetChannel(cli::Channel::Input)
      .SetRequired(),
    Option(ParameterType::String, "igtl-listen",
      "The port to serve on (0: any free port, printed); PORT alone serves this machine (loopback), HOST:PORT that address.")
      .SetPlaceholder("[HOST:]PORT")
      .SetRequired(),
    Option(ParameterType::String, "device", "The TRANSFORM's device name the poses are sent as, e.g. StylusToReference (20 bytes at most).")
      .SetPlaceholder("NAME")
      .SetRequired(),
    Option(ParameterType::Double, "speed", "Faster (or slower) than recorded: 2 sends the poses at twice their rate.")
      .SetPlaceholder("F")
      .SetDefault("1"),
    Option(ParameterType::Double, "wait-s", "How long to wait for a first client.").SetPlaceholder("S").SetDefault("30"),
  };
  for (const cli::Parameter& p : PoseReadingOptions())
  {
    stream.push_back(p);
  }
  return cli::ModuleDescription::Subcommand("vesselproximity serve",
    "serve a recording over OpenIGTLink at its own times, as a tracker server would",
    "Serves the poses of a recording as TRANSFORM messages to every OpenIGTLink client, at their recorded times (from "
    "the first), as PlusServer's saved-data source replays one; a frame the tracker lost is sent as nothing. Ends "
    "after the last pose, or at Ctrl-C.",
    { { "Stream", "", stream } });
}

int RunServeCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  SignalHold hold; // Ctrl-C ends the stream, answered below
  const auto [host, port] = ParseListenAddress(args);
  const double speed = args.GetNumber("speed");
  if (!(speed > 0.0))
  {
    throw InputError("--speed", "expected a factor above 0, got '" + args.GetString("speed") + "'");
  }
  const double waitS = args.GetNumber("waitS");
  if (!(waitS >= 0.0))
  {
    throw InputError("--wait-s", "expected a time in s, 0 or more, got '" + args.GetString("waitS") + "'");
  }
  const std::string file = args.GetString("poses");
  const PoseReading reading = ParsePoseReading(args);
  const std::size_t count = PoseStream::CountPoses(file, reading); // a bad recording is refused before serving
  IgtlPoseStreamer streamer(port, args.GetString("device"), host);
  std::cerr << "serve: " << count << " poses of " << file << " as " << args.GetString("device") << " on port " << streamer.GetPort()
            << "; waiting for a client\n";
  PoseStream poses(file, count, reading);
  const std::atomic<bool> stop{ false };
  const std::size_t sent = streamer.Stream(poses, speed, waitS, stop, [](std::size_t done, std::size_t expected) {
    std::fprintf(stderr, "serve: pose %zu of %zu\n", done, expected);
  });
  const int signal = SignalHold::Answer();
  if (sent == 0 && !signal)
  {
    throw InputError("--igtl-listen", "no client connected within " + args.GetString("waitS") + " s");
  }
  std::printf("served %zu of %zu poses (lost frames sent as nothing)%s\n", sent, count, signal ? "; ended by a signal" : "");
  return 0;
}
} // namespace vp
