#include "vpToneSynth.h"

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
constexpr double EdgeS = 0.005; // attack and release of every beep
constexpr double Pi = 3.14159265358979323846;

double Wave(Timbre timbre, double phase)
{
  switch (timbre)
  {
    case Timbre::Square:
      return phase < 0.5 ? 1.0 : -1.0;
    case Timbre::Triangle:
      return phase < 0.5 ? 4.0 * phase - 1.0 : 3.0 - 4.0 * phase;
    case Timbre::Sine:
    default:
      return std::sin(2.0 * Pi * phase);
  }
}
} // namespace

ToneSynth::ToneSynth(double sampleRateHz)
  : RateHz(sampleRateHz)
{
}

void ToneSynth::SetState(const SoundState& state)
{
  if (state.Vessel != this->State.Vessel)
  {
    this->Vessel.Start(state.Vessel);
  }
  if (state.Margin != this->State.Margin)
  {
    this->Margin.Start(state.Margin);
  }
  this->State = state;
}

void ToneSynth::Player::Start(const Voice& voice)
{
  this->Sound = voice;
  this->BeepTimeS = 0.0;
}

float ToneSynth::Player::Next(double dtS)
{
  const Voice& v = this->Sound;
  double target = 0.0;
  double pitch = v.Silent() ? this->LastPitchHz : v.PitchHz; // a voice falling silent fades out in tune
  if (!v.Silent())
  {
    if (v.Continuous())
    {
      target = 1.0;
    }
    else
    {
      const double period = 1.0 / v.BeepsPerSecond;
      const double t = std::fmod(this->BeepTimeS, period);
      const double on = v.Duty * period;
      // Within the beep: ramps at both ends (a whole-period beep only at its start).
      target = t < on ? std::min({ 1.0, t / EdgeS, v.Duty >= 1.0 ? 1.0 : (on - t) / EdgeS }) : 0.0;
      pitch = v.AltPitchHz > 0.0 && t >= 0.5 * period ? v.AltPitchHz : v.PitchHz;
    }
  }
  // The amplitude follows its target within about an edge: a change of voice never clicks.
  target *= v.Silent() ? 0.0 : v.Gain;
  this->Level += (target - this->Level) * std::min(1.0, dtS / (0.25 * EdgeS));
  this->BeepTimeS += dtS;
  const double sample = this->Level > 1e-6 ? this->Level * Wave(v.Wave, this->OscillatorPhase) : 0.0;
  this->OscillatorPhase = std::fmod(this->OscillatorPhase + pitch * dtS, 1.0);
  this->LastPitchHz = pitch;
  return static_cast<float>(sample);
}

void ToneSynth::Render(float* samples, std::size_t count)
{
  const double dt = 1.0 / this->RateHz;
  for (std::size_t i = 0; i < count; ++i)
  {
    const double mixed = this->Vessel.Next(dt) + this->Margin.Next(dt);
    samples[i] = static_cast<float>(std::clamp(mixed, -1.0, 1.0));
  }
}
} // namespace vp
