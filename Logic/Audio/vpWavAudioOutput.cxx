#include "vpWavAudioOutput.h"

#include "vpInputError.h"
#include "vpOutputFile.h"
#include "vpToneSynth.h"

#include <nlohmann/json.hpp>
#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vp
{
namespace
{
/// libsndfile's virtual I/O over a string: the WAV is made in memory and written atomically.
struct Memory
{
  std::string Bytes;
  sf_count_t At = 0;
};
sf_count_t Length(void* m) { return static_cast<sf_count_t>(static_cast<Memory*>(m)->Bytes.size()); }
sf_count_t Seek(sf_count_t offset, int whence, void* m)
{
  Memory& mem = *static_cast<Memory*>(m);
  const sf_count_t base = whence == SEEK_SET ? 0 : whence == SEEK_CUR ? mem.At : Length(m);
  mem.At = std::max<sf_count_t>(0, base + offset);
  return mem.At;
}
sf_count_t Read(void* out, sf_count_t count, void* m)
{
  Memory& mem = *static_cast<Memory*>(m);
  const sf_count_t n = std::max<sf_count_t>(0, std::min(count, Length(m) - mem.At));
  std::memcpy(out, mem.Bytes.data() + mem.At, static_cast<std::size_t>(n));
  mem.At += n;
  return n;
}
sf_count_t Write(const void* in, sf_count_t count, void* m)
{
  Memory& mem = *static_cast<Memory*>(m);
  if (mem.At + count > Length(m))
  {
    mem.Bytes.resize(static_cast<std::size_t>(mem.At + count));
  }
  std::memcpy(&mem.Bytes[static_cast<std::size_t>(mem.At)], in, static_cast<std::size_t>(count));
  mem.At += count;
  return count;
}
sf_count_t Tell(void* m) { return static_cast<Memory*>(m)->At; }
} // namespace

std::string EncodeWav(const std::vector<float>& samples, double sampleRateHz)
{
  SF_VIRTUAL_IO io{ Length, Seek, Read, Write, Tell };
  Memory memory;
  SF_INFO info{};
  info.samplerate = static_cast<int>(std::lround(sampleRateHz));
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* file = sf_open_virtual(&io, SFM_WRITE, &info, &memory);
  if (!file)
  {
    throw std::runtime_error(std::string("libsndfile cannot make a WAV: ") + sf_strerror(nullptr));
  }
  const sf_count_t written = sf_writef_float(file, samples.data(), static_cast<sf_count_t>(samples.size()));
  sf_close(file);
  if (written != static_cast<sf_count_t>(samples.size()))
  {
    throw std::runtime_error("libsndfile wrote " + std::to_string(written) + " of " + std::to_string(samples.size()) + " samples");
  }
  return memory.Bytes;
}

WavAudioOutput::WavAudioOutput(std::string fileName, Sonification sound)
  : FileName(std::move(fileName))
  , Sound(std::move(sound))
{
}

void WavAudioOutput::Note(double timeS, const SoundState& state)
{
  // Poses out of time order (a tracker's jitter) sound at the latest time seen: never backwards.
  const bool first = this->Changes.empty();
  this->LastTimeS = first ? timeS : std::max(this->LastTimeS, timeS);
  if (first || state != this->Changes.back().second)
  {
    this->Changes.emplace_back(this->LastTimeS, state);
  }
}

std::vector<float> WavAudioOutput::Render(double sampleRateHz) const
{
  std::vector<float> samples;
  if (this->Changes.empty())
  {
    return samples;
  }
  const double startS = this->Changes.front().first;
  samples.resize(static_cast<std::size_t>(std::llround((this->LastTimeS - startS) * sampleRateHz)));
  ToneSynth synth(sampleRateHz);
  for (std::size_t c = 0; c < this->Changes.size(); ++c)
  {
    const auto at = [&](double timeS) { return std::min(samples.size(), static_cast<std::size_t>(std::llround((timeS - startS) * sampleRateHz))); };
    const std::size_t from = at(this->Changes[c].first);
    const std::size_t to = c + 1 < this->Changes.size() ? at(this->Changes[c + 1].first) : samples.size();
    synth.SetState(this->Changes[c].second);
    if (to > from)
    {
      synth.Render(samples.data() + from, to - from);
    }
  }
  return samples;
}

void WavAudioOutput::OnEnd()
{
  // A 16-bit WAV holds at most 4 GB: 13.5 h of 44.1 kHz mono. Said, not attempted.
  const double spanS = this->Changes.empty() ? 0.0 : this->LastTimeS - this->Changes.front().first;
  if (!(spanS <= MaximumSeconds))
  {
    throw InputError(this->FileName, "the recording spans " + std::to_string(spanS / 3600.0) + " h; a WAV holds at most " +
        std::to_string(static_cast<int>(MaximumSeconds / 3600.0)) + " h");
  }
  const std::vector<float> samples = this->Render(ToneSynth::DefaultSampleRateHz);
  try
  {
    WriteFileAtomically(this->FileName, EncodeWav(samples, ToneSynth::DefaultSampleRateHz));
  }
  catch (const std::runtime_error& e)
  {
    if (dynamic_cast<const InputError*>(&e))
    {
      throw;
    }
    throw InputError(this->FileName, e.what());
  }
  this->Samples = samples.size();
  this->Written = true;
}

void WavAudioOutput::Report(nlohmann::ordered_json& outputs) const
{
  outputs["audio_wav"] = { { "file", this->FileName }, { "written", this->Written }, { "sample_rate_hz", ToneSynth::DefaultSampleRateHz },
    { "seconds", static_cast<double>(this->Samples) / ToneSynth::DefaultSampleRateHz },
    { "starts_at_time_s", this->Changes.empty() ? 0.0 : this->Changes.front().first }, { "changes_of_sound", this->Changes.size() } };
}
} // namespace vp
