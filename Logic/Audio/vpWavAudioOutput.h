#ifndef vpWavAudioOutput_h
#define vpWavAudioOutput_h

#include "vpFrameOutput.h"
#include "vpSonification.h"

#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// The run's sonification as a WAV file (44.1 kHz, 16-bit mono, through libsndfile), in the
/// recording's time: its first sample is the first pose's time and it lasts to the last pose's,
/// so that second s of the sound is time first + s of frames.csv and of distance.png's axis. The
/// same synthesizer as the live sound (vp::ToneSynth): a run is reviewed with the sound it made.
/// Written whole at the end of the run (or not at all: an InputError names the file).
class WavAudioOutput : public FrameOutput
{
public:
  /// The longest recording written: 12 h (a WAV's 4 GB hold 13.5 h of 44.1 kHz 16-bit mono).
  static constexpr double MaximumSeconds = 12.0 * 3600.0;
  WavAudioOutput(std::string fileName, Sonification sound);

  void OnFrame(const TrackedFrame& frame) override { this->Note(frame.TimeS, this->Sound.ForFrame(frame)); }
  void OnLost(const TrackedPose& pose) override { this->Note(pose.TimeS, this->Sound.ForLostPose()); }
  void OnEnd() override;

  void Report(nlohmann::ordered_json& outputs) const override;

  /// The samples of the states noted so far, from the first pose's time to the last's.
  std::vector<float> Render(double sampleRateHz) const;

private:
  void Note(double timeS, const SoundState& state);

  std::string FileName;
  Sonification Sound;
  /// Each change of what sounds, from the first pose on, and the last pose's time.
  std::vector<std::pair<double, SoundState>> Changes;
  double LastTimeS = 0.0;
  std::size_t Samples = 0;
  bool Written = false;
};

/// 16-bit mono PCM WAV bytes of the samples (libsndfile, in memory); what WavAudioOutput writes.
std::string EncodeWav(const std::vector<float>& samples, double sampleRateHz);
} // namespace vp

#endif
