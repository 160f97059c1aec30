#ifndef vpToneSynth_h
#define vpToneSynth_h

#include "vpSonification.h"

#include <cstddef>

namespace vp
{
/// Plays a SoundState as samples: the two voices mixed, their oscillators phase-continuous, every
/// beep shaped by a 5 ms attack and release so that no edge clicks. A new voice starts its beep
/// clock afresh (it begins with a beep: the ear hears the change when it happens); a voice that
/// stays keeps its rhythm across calls. One synthesizer serves the live sound device and the
/// recording's WAV alike, so both sound the same.
class ToneSynth
{
public:
  static constexpr double DefaultSampleRateHz = 44100.0;
  explicit ToneSynth(double sampleRateHz = DefaultSampleRateHz);

  /// What sounds from the next sample on.
  void SetState(const SoundState& state);
  const SoundState& GetState() const { return this->State; }

  /// The next count samples, in [-1, 1].
  void Render(float* samples, std::size_t count);

  double GetSampleRateHz() const { return this->RateHz; }

private:
  struct Player
  {
    Voice Sound;
    double OscillatorPhase = 0.0; ///< cycles, in [0, 1)
    double BeepTimeS = 0.0;       ///< since the voice began
    double Level = 0.0;           ///< the amplitude as it is (smoothed towards its target)
    double LastPitchHz = 0.0;
    void Start(const Voice& voice);
    float Next(double dtS);
  };
  double RateHz;
  SoundState State;
  Player Vessel;
  Player Margin;
};
} // namespace vp

#endif
