#ifndef vpAlsaAudioOutput_h
#define vpAlsaAudioOutput_h

#include "vpFrameOutput.h"
#include "vpSonification.h"

#include <atomic>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace vp
{
/// The sonification played live on a sound device through ALSA (the default device unless told
/// otherwise), by a thread of its own: a frame only hands over what should sound (the newest
/// wins), so sound never delays a frame. The device is opened on the thread; none there is said
/// once (say) and tracking goes on in silence; a device that fails while playing (unplugged) is
/// said and counted, never fatal. The same synthesizer as the recording's WAV (vp::ToneSynth).
class AlsaAudioOutput : public FrameOutput
{
public:
  /// say: a line for the user, called from the output's thread.
  AlsaAudioOutput(std::string device, Sonification sound, std::function<void(const std::string&)> say);
  ~AlsaAudioOutput() override;
  AlsaAudioOutput(const AlsaAudioOutput&) = delete;
  AlsaAudioOutput& operator=(const AlsaAudioOutput&) = delete;

  void OnFrame(const TrackedFrame& frame) override { this->Hand(this->Sound.ForFrame(frame)); }
  void OnLost(const TrackedPose&) override { this->Hand(this->Sound.ForLostPose()); }
  /// Falls silent (the device is let go when the output is).
  void OnEnd() override;

  /// Its problems are said as they happen (say), so Problems() has nothing to add.
  void Report(nlohmann::ordered_json& outputs) const override;

  /// Whether the device was opened (false until the thread has tried, and when it failed).
  bool IsPlaying() const { return this->Opened.load(); }
  /// Samples handed to the device so far.
  std::size_t GetSamplesPlayed() const { return this->Played.load(); }

private:
  void Hand(const SoundState& state);
  void Play();

  std::string Device;
  Sonification Sound;
  std::function<void(const std::string&)> Say;
  mutable std::mutex Lock;
  SoundState Wanted; ///< under Lock
  std::string Failure; ///< under Lock: why the device could not be opened or stopped playing
  std::atomic<bool> Stopping{ false };
  std::atomic<bool> Opened{ false };
  std::atomic<std::size_t> Played{ 0 };
  std::atomic<std::size_t> Underruns{ 0 };
  std::atomic<std::size_t> Failures{ 0 };
  std::thread Player;
};
} // namespace vp

#endif
