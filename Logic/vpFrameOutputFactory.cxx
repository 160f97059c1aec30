#include "vpFrameOutputFactory.h"

#include "vpAlsaAudioOutput.h"
#include "vpInputError.h"
#include "vpOscOutput.h"
#include "vpRegularFile.h"
#include "vpSonification.h"
#include "vpWavAudioOutput.h"

#include <cstdlib>

namespace vp
{
namespace
{
const Sonification& SoundOf(const OutputRequest& request)
{
  static const Sonification defaults = Sonification::Default();
  return request.Sound ? *request.Sound : defaults;
}

std::unique_ptr<FrameOutput> MakeOsc(const OutputRequest& request)
{
  const std::size_t colon = request.Value.rfind(':');
  char* end = nullptr;
  const long port = colon == std::string::npos ? 0 : std::strtol(request.Value.c_str() + colon + 1, &end, 10);
  if (colon == std::string::npos || colon == 0 || !end || *end != '\0' || end == request.Value.c_str() + colon + 1 || port < 1 ||
    port > 65535)
  {
    throw InputError(request.Source, "'" + request.Value + "' is not HOST:PORT (a port 1 to 65535)");
  }
  return std::make_unique<OscOutput>(request.Source, request.Value.substr(0, colon), static_cast<int>(port), SoundOf(request));
}

std::unique_ptr<FrameOutput> MakeAlsa(const OutputRequest& request)
{
  return std::make_unique<AlsaAudioOutput>("default", SoundOf(request), request.Say);
}

std::unique_ptr<FrameOutput> MakeWav(const OutputRequest& request)
{
  if (request.Value.empty())
  {
    throw InputError(request.Source, "a file name is required");
  }
  const std::string input = FileItWouldReplace(request.Value, request.Inputs);
  if (!input.empty())
  {
    throw InputError(request.Source, "'" + request.Value + "' would replace " +
        (input == request.Value ? std::string("an input of this run") : "the run's input '" + input + "'") +
        ": write the sound to another file");
  }
  return std::make_unique<WavAudioOutput>(request.Value, SoundOf(request));
}
} // namespace

const std::vector<OutputMethod>& FrameOutputMethods()
{
  static const std::vector<OutputMethod> methods{
    { "osc", "HOST:PORT",
      "Send each frame as OpenSoundControl messages (distance, level, margin, tracking state and the sound to play) to a "
      "PureData patch (Resources/Audio/VesselProximity.pd) or any OSC peer.",
      OutputForLive | OutputForTrack | OutputForView | OutputForDemo, MakeOsc },
    { "audio", nullptr,
      "Play the sonification on the default sound device (ALSA): silence when safe, beeps faster from caution to danger, a "
      "tone inside a vessel, a two-tone when tracking is lost.",
      OutputForLive | OutputForView, MakeAlsa },
    { "audio-wav", "FILE",
      "Write the run's sonification as a WAV (44.1 kHz) in the recording's time, to review the run with its sound.",
      OutputForTrack | OutputForDemo, MakeWav },
  };
  return methods;
}
} // namespace vp
