#include "vpSonification.h"

#include "vpInputError.h"
#include "vpJsonFile.h"

#include <cmath>
#include <sstream>

namespace vp
{
namespace
{
Voice Beeps(double pitchHz, double perSecond, double duty, Timbre wave)
{
  Voice v;
  v.PitchHz = pitchHz;
  v.BeepsPerSecond = perSecond;
  v.Duty = duty;
  v.Wave = wave;
  // A square wave sounds twice as loud as a sine of the same peak: half the gain.
  v.Gain = wave == Timbre::Square ? 0.25 : 0.5;
  return v;
}

/// The number at key, within [low, high], or what it was when the entry lacks it.
double Number(const nlohmann::json& entry, const char* key, double low, double high, double was, const std::string& where)
{
  if (!entry.contains(key))
  {
    return was;
  }
  const nlohmann::json& value = entry.at(key);
  if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < low || value.get<double>() > high)
  {
    std::ostringstream range;
    range << where << "." << key << ": " << value.dump() << " is not a number from " << low << " to " << high;
    throw InputError(range.str());
  }
  return value.get<double>();
}

Voice ReadVoice(const nlohmann::json& entry, Voice voice, const std::string& where)
{
  if (!entry.is_object())
  {
    throw InputError(where + ": not an object of pitch_hz, alt_pitch_hz, beeps_per_second, duty, timbre, gain");
  }
  for (const auto& item : entry.items())
  {
    static const char* const known[] = { "pitch_hz", "alt_pitch_hz", "beeps_per_second", "duty", "timbre", "gain" };
    bool ok = false;
    for (const char* k : known)
    {
      ok = ok || item.key() == k;
    }
    if (!ok)
    {
      throw InputError(where + "." + item.key() + ": unknown (pitch_hz, alt_pitch_hz, beeps_per_second, duty, timbre, gain)");
    }
  }
  voice.PitchHz = Number(entry, "pitch_hz", 0.0, 20000.0, voice.PitchHz, where);
  voice.AltPitchHz = Number(entry, "alt_pitch_hz", 0.0, 20000.0, voice.AltPitchHz, where);
  for (const double hz : { voice.PitchHz, voice.AltPitchHz })
  {
    if (hz > 0.0 && hz < 20.0)
    {
      throw InputError(where + ": a pitch of " + std::to_string(hz) + " Hz cannot be heard (0 for silence, else 20 to 20000)");
    }
  }
  voice.BeepsPerSecond = Number(entry, "beeps_per_second", 0.0, 50.0, voice.BeepsPerSecond, where);
  voice.Duty = Number(entry, "duty", 0.0, 1.0, voice.Duty, where);
  if (voice.Duty <= 0.0)
  {
    throw InputError(where + ".duty: 0 would never sound (above 0 to 1)");
  }
  voice.Gain = Number(entry, "gain", 0.0, 1.0, voice.Gain, where);
  if (entry.contains("timbre"))
  {
    const nlohmann::json& t = entry.at("timbre");
    const std::string name = t.is_string() ? t.get<std::string>() : t.dump();
    if (name == "sine")
      voice.Wave = Timbre::Sine;
    else if (name == "square")
      voice.Wave = Timbre::Square;
    else if (name == "triangle")
      voice.Wave = Timbre::Triangle;
    else
      throw InputError(where + ".timbre: " + t.dump() + " is not sine, square or triangle");
  }
  return voice;
}

/// Each entry of the section over the voice of its name (names: name(i) for i < n).
template <std::size_t N, class NameOf>
void ReadSection(const nlohmann::json& root, const char* section, std::array<Voice, N>& voices, NameOf name, const std::string& file)
{
  if (!root.contains(section))
  {
    return;
  }
  const nlohmann::json& entries = root.at(section);
  if (!entries.is_object())
  {
    throw InputError(file, std::string(section) + ": not an object of voices by name");
  }
  for (const auto& item : entries.items())
  {
    std::size_t i = 0;
    while (i < N && item.key() != name(i))
    {
      ++i;
    }
    if (i == N)
    {
      std::string names;
      for (std::size_t k = 0; k < N; ++k)
      {
        names += (k ? ", " : "") + std::string(name(k));
      }
      throw InputError(file, std::string(section) + "." + item.key() + ": unknown (" + names + ")");
    }
    voices[i] = ReadVoice(item.value(), voices[i], file + ": " + section + "." + item.key());
  }
}
} // namespace

const char* TimbreName(Timbre timbre)
{
  switch (timbre)
  {
    case Timbre::Square:
      return "square";
    case Timbre::Triangle:
      return "triangle";
    case Timbre::Sine:
    default:
      return "sine";
  }
}

bool Voice::operator==(const Voice& o) const
{
  return this->PitchHz == o.PitchHz && this->AltPitchHz == o.AltPitchHz && this->BeepsPerSecond == o.BeepsPerSecond &&
    this->Duty == o.Duty && this->Wave == o.Wave && this->Gain == o.Gain;
}

Sonification Sonification::Default()
{
  Sonification s;
  s.Levels[static_cast<int>(DangerLevel::Safe)] = Voice{ 0.0, 0.0, 0.0, 0.5, Timbre::Sine, 0.0 };
  s.Levels[static_cast<int>(DangerLevel::Caution)] = Beeps(660.0, 2.0, 0.30, Timbre::Sine);
  s.Levels[static_cast<int>(DangerLevel::Warning)] = Beeps(880.0, 4.0, 0.40, Timbre::Sine);
  s.Levels[static_cast<int>(DangerLevel::Danger)] = Beeps(1175.0, 8.0, 0.50, Timbre::Square);
  s.Levels[static_cast<int>(DangerLevel::Breach)] = Beeps(1319.0, 0.0, 1.0, Timbre::Square);
  s.Margins[static_cast<int>(MarginLevel::Clear)] = Voice{ 0.0, 0.0, 0.0, 0.5, Timbre::Triangle, 0.0 };
  s.Margins[static_cast<int>(MarginLevel::Near)] = Beeps(440.0, 1.0, 0.30, Timbre::Triangle);
  s.Margins[static_cast<int>(MarginLevel::Violated)] = Beeps(440.0, 3.0, 0.40, Timbre::Triangle);
  s.Margins[static_cast<int>(MarginLevel::Inside)] = Beeps(392.0, 0.0, 1.0, Timbre::Triangle);
  s.Lost = Beeps(988.0, 2.0, 1.0, Timbre::Sine);
  s.Lost.AltPitchHz = 784.0;
  return s;
}

Sonification Sonification::Read(const std::string& fileName)
{
  return FromJson(ReadJsonFile(fileName, "a sonification (JSON)"), fileName);
}

Sonification Sonification::FromJson(const nlohmann::json& root, const std::string& fileName)
{
  if (!root.is_object())
  {
    throw InputError(fileName, "not a JSON object of levels, margin and lost");
  }
  for (const auto& item : root.items())
  {
    if (item.key() != "levels" && item.key() != "margin" && item.key() != "lost")
    {
      throw InputError(fileName, item.key() + ": unknown (levels, margin, lost)");
    }
  }
  Sonification s = Default();
  ReadSection(root, "levels", s.Levels, [](std::size_t i) { return DangerLevelName(static_cast<DangerLevel>(i)); }, fileName);
  ReadSection(root, "margin", s.Margins, [](std::size_t i) { return MarginLevelName(static_cast<MarginLevel>(i)); }, fileName);
  if (root.contains("lost"))
  {
    s.Lost = ReadVoice(root.at("lost"), s.Lost, fileName + ": lost");
  }
  return s;
}

SoundState Sonification::ForFrame(const TrackedFrame& frame) const
{
  SoundState state;
  state.Vessel = this->ForLevel(frame.Level);
  state.Margin = this->ForMargin(frame.Tumour ? frame.Tumour->Level : MarginLevel::Clear);
  return state;
}

SoundState Sonification::ForLostPose() const
{
  SoundState state;
  state.Vessel = this->Lost;
  state.Margin = this->ForMargin(MarginLevel::Clear);
  return state;
}
} // namespace vp
