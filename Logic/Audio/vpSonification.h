#ifndef vpSonification_h
#define vpSonification_h

#include "vpDangerLevels.h"
#include "vpMarginLevels.h"
#include "vpPoseFile.h"
#include "vpTrackedFrame.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <string>

namespace vp
{
/// A voice's waveform: the vessels speak in sine and square, the margin in triangle, so that the
/// ear tells them apart at any pitch.
enum class Timbre
{
  Sine,
  Square,
  Triangle
};
const char* TimbreName(Timbre timbre);

/// What one voice plays while a state lasts: beeps of PitchHz at BeepsPerSecond (each sounding
/// for Duty of its period), or a continuous tone when BeepsPerSecond is 0, or silence when
/// PitchHz or Gain is 0. With AltPitchHz, the second half of each period sounds at that pitch
/// instead: the two-tone of tracking lost.
struct Voice
{
  double PitchHz = 0.0;
  double AltPitchHz = 0.0;
  double BeepsPerSecond = 0.0;
  double Duty = 0.5;
  Timbre Wave = Timbre::Sine;
  double Gain = 0.5; ///< 0 to 1; the two voices together never clip (each at most 0.5 of full scale)

  bool Silent() const { return this->PitchHz <= 0.0 || this->Gain <= 0.0; }
  bool Continuous() const { return !this->Silent() && this->BeepsPerSecond <= 0.0; }
  bool operator==(const Voice& o) const;
  bool operator!=(const Voice& o) const { return !(*this == o); }
};

/// What sounds at one moment: the vessels' voice (the frame's worst level, tip or instrument, or
/// tracking lost) and the margin's voice (the worst tumour's margin level), mixed.
struct SoundState
{
  Voice Vessel;
  Voice Margin;
  bool operator==(const SoundState& o) const { return this->Vessel == o.Vessel && this->Margin == o.Margin; }
  bool operator!=(const SoundState& o) const { return !(*this == o); }
};

/// The sonification, defined once: danger level, margin level and tracking lost to voices, like a
/// parking sensor (SlicerIGT's BreachWarning with its SoundControl patch beeps the same way):
///
/// | state | pitch (Hz) | beeps/s | duty | timbre |
/// |---|---|---|---|---|
/// | safe | silence | | | |
/// | caution | 660 | 2 | 0.30 | sine |
/// | warning | 880 | 4 | 0.40 | sine |
/// | danger | 1175 | 8 | 0.50 | square |
/// | breach (inside a vessel) | 1319 | continuous | | square |
/// | margin clear | silence | | | |
/// | margin near | 440 | 1 | 0.30 | triangle |
/// | margin violated | 440 | 3 | 0.40 | triangle |
/// | inside the tumour | 392 | continuous | | triangle |
/// | tracking lost | 988 / 784 two-tone | 2 | 1.00 | sine |
///
/// A JSON file (Read) replaces any entry or any field of one; the user guide's audio section shows
/// the format.
class Sonification
{
public:
  static Sonification Default();
  /// The defaults with the file's entries over them: {"levels": {"caution": {"pitch_hz": ...,
  /// "alt_pitch_hz", "beeps_per_second", "duty", "timbre": "sine|square|triangle", "gain"}, ...},
  /// "margin": {"near": {...}, ...}, "lost": {...}}. Throws InputError naming the file and the
  /// entry for an unknown name, a wrong type or a value out of range (pitch 0 or 20 to 20000 Hz,
  /// 0 to 50 beeps/s, duty above 0 to 1, gain 0 to 1).
  static Sonification Read(const std::string& fileName);
  /// The same from JSON already parsed; fileName names it in errors.
  static Sonification FromJson(const nlohmann::json& root, const std::string& fileName);

  const Voice& ForLevel(DangerLevel level) const { return this->Levels[static_cast<int>(level)]; }
  const Voice& ForMargin(MarginLevel level) const { return this->Margins[static_cast<int>(level)]; }
  const Voice& ForLost() const { return this->Lost; }

  /// What a frame sounds like; what a lost pose sounds like (the margin silent: nothing is known).
  SoundState ForFrame(const TrackedFrame& frame) const;
  SoundState ForLostPose() const;

  std::array<Voice, NumberOfDangerLevels> Levels;
  std::array<Voice, NumberOfMarginLevels> Margins;
  Voice Lost;
};
} // namespace vp

#endif
