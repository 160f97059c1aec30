#include "vpAlsaAudioOutput.h"

#include "vpClock.h"
#include "vpToneSynth.h"

#include <alsa/asoundlib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <utility>
#include <vector>

namespace vp
{
namespace
{
constexpr unsigned LatencyUs = 50000; // what the device buffers: the sound follows a frame within it
constexpr std::size_t PeriodSamples = 441; // 10 ms at 44.1 kHz

/// An ALSA handle let go however the thread leaves.
struct Pcm
{
  snd_pcm_t* Handle = nullptr;
  ~Pcm()
  {
    if (this->Handle)
    {
      snd_pcm_drop(this->Handle);
      snd_pcm_close(this->Handle);
    }
  }
};
} // namespace

AlsaAudioOutput::AlsaAudioOutput(std::string device, Sonification sound, std::function<void(const std::string&)> say)
  : Device(std::move(device))
  , Sound(std::move(sound))
  , Say(std::move(say))
{
  this->Player = std::thread([this] { this->Play(); });
}

AlsaAudioOutput::~AlsaAudioOutput()
{
  this->Stopping = true;
  this->Player.join();
}

void AlsaAudioOutput::Hand(const SoundState& state)
{
  std::lock_guard<std::mutex> hold(this->Lock);
  this->Wanted = state;
}

void AlsaAudioOutput::OnEnd()
{
  this->Hand(SoundState()); // silence; a view that goes on after a replay is heard again
}

void AlsaAudioOutput::Play()
{
  Pcm pcm;
  // Opened without waiting (a device another program holds would block the open, and the run's
  // end with it), then written to with waiting, which paces the thread.
  int status = snd_pcm_open(&pcm.Handle, this->Device.c_str(), SND_PCM_STREAM_PLAYBACK, SND_PCM_NONBLOCK);
  if (status >= 0)
  {
    status = snd_pcm_nonblock(pcm.Handle, 0);
  }
  if (status >= 0)
  {
    status = snd_pcm_set_params(pcm.Handle, SND_PCM_FORMAT_FLOAT, SND_PCM_ACCESS_RW_INTERLEAVED, 1,
      static_cast<unsigned>(ToneSynth::DefaultSampleRateHz), 1, LatencyUs);
  }
  if (status < 0)
  {
    {
      std::lock_guard<std::mutex> hold(this->Lock);
      this->Failure = "no sound device '" + this->Device + "': " + snd_strerror(status);
    }
    if (this->Say)
    {
      this->Say("audio: no sound device '" + this->Device + "' (" + snd_strerror(status) + "): tracking goes on without sound");
    }
    return;
  }
  this->Opened = true;
  ToneSynth synth;
  std::vector<float> period(PeriodSamples);
  const double startMs = NowMs();
  while (!this->Stopping)
  {
    {
      std::lock_guard<std::mutex> hold(this->Lock);
      synth.SetState(this->Wanted);
    }
    synth.Render(period.data(), period.size());
    snd_pcm_sframes_t written = snd_pcm_writei(pcm.Handle, period.data(), period.size());
    if (written == -EPIPE || written == -ESTRPIPE)
    {
      ++this->Underruns;
      written = snd_pcm_recover(pcm.Handle, static_cast<int>(written), 1);
    }
    if (written < 0)
    {
      ++this->Failures;
      {
        std::lock_guard<std::mutex> hold(this->Lock);
        this->Failure = "the sound device '" + this->Device + "' failed: " + snd_strerror(static_cast<int>(written));
      }
      if (this->Say)
      {
        this->Say("audio: the sound device '" + this->Device + "' failed (" + snd_strerror(static_cast<int>(written)) +
          "): tracking goes on without sound");
      }
      this->Opened = false;
      return;
    }
    this->Played += static_cast<std::size_t>(written);
    // A device that takes samples faster than it plays them (a null sink) must not make this
    // thread spin: never more than the device's latency ahead of the clock.
    const double aheadMs = 1000.0 * static_cast<double>(this->Played.load()) / ToneSynth::DefaultSampleRateHz - (NowMs() - startMs);
    if (aheadMs > LatencyUs / 1000.0)
    {
      std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(1000.0 * (aheadMs - LatencyUs / 1000.0))));
    }
  }
}

void AlsaAudioOutput::Report(nlohmann::ordered_json& outputs) const
{
  std::lock_guard<std::mutex> hold(this->Lock);
  outputs["audio"] = { { "device", this->Device }, { "played_s", static_cast<double>(this->Played.load()) / ToneSynth::DefaultSampleRateHz },
    { "underruns", this->Underruns.load() }, { "failures", this->Failures.load() }, { "problem", this->Failure } };
}

} // namespace vp
