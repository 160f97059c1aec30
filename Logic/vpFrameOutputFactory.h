#ifndef vpFrameOutputFactory_h
#define vpFrameOutputFactory_h

#include "vpFrameOutput.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace vp
{
class Sonification;

/// Which front ends offer an output (bits of OutputMethod::Offered).
enum OutputOffer : unsigned
{
  OutputForLive = 1u,  ///< live
  OutputForTrack = 2u, ///< track (a recording, computed as fast as it goes)
  OutputForView = 4u,  ///< the interactive view
  OutputForDemo = 8u,  ///< the demo
};

/// What an output is made from: the option's value and what every output may need.
struct OutputRequest
{
  std::string Source;  ///< how the front end names the option (its flag), for errors
  std::string Value;   ///< its value (empty for a switch)
  const Sonification* Sound = nullptr; ///< the sonification (the default, or the user's file)
  /// What the run reads: an output written to a file refuses to replace one of them.
  std::vector<std::string> Inputs;
  /// A line for the user (a device that cannot be opened), from any thread.
  std::function<void(const std::string&)> Say;
};

/// An output a front end offers on request: the registry (FrameOutputMethods) is the one place
/// that lists them; each front end's options, their help and the outputs it makes come from it.
/// Adding one is its class, its line here and its sources in Logic/CMakeLists.txt.
struct OutputMethod
{
  const char* Name;      ///< the option's name ("osc", "audio-wav")
  const char* ValueName; ///< what its value is ("HOST:PORT", "FILE"); null for a switch
  const char* Help;      ///< one sentence
  unsigned Offered;      ///< OutputOffer bits
  /// The output, ready for frames. Throws InputError(request.Source, ...) for a bad value.
  std::unique_ptr<FrameOutput> (*Make)(const OutputRequest& request);
};

/// Every output offered on request, in the order front ends list them.
const std::vector<OutputMethod>& FrameOutputMethods();
} // namespace vp

#endif
