#include "vpHapticForce.h"

#include "vpInputError.h"
#include "vpTrackedFrame.h"

#include <algorithm>
#include <cmath>

namespace vp
{
void HapticSettings::Validate() const
{
  if (!(std::isfinite(this->StiffnessNPerMm) && this->StiffnessNPerMm >= 0.0))
  {
    throw ParameterError("HapticStiffnessNPerMm", "must be a stiffness in N/mm, 0 or more (0: none)");
  }
  if (!(std::isfinite(this->DampingNsPerMm) && this->DampingNsPerMm >= 0.0))
  {
    throw ParameterError("HapticDampingNsPerMm", "must be a damping in N·s/mm, 0 or more (0: none)");
  }
}

HapticForce::HapticForce(const HapticSettings& settings)
  : Settings(settings)
{
}

void HapticForce::Reset()
{
  this->HasPrevious = false;
  this->RateMmPerS = 0.0;
}

HapticSample HapticForce::Update(const TrackedFrame& frame)
{
  HapticSample sample;
  // The deepest penetration, and the direction out of it.
  int tipClass = -1;
  for (std::size_t c = 0; c < frame.Proximity.Classes.size(); ++c)
  {
    const ClassProximity& p = frame.Proximity.Classes[c];
    if (p.InRange && p.Inside && *p.Inside && p.DistanceMm > sample.DepthMm)
    {
      sample.DepthMm = p.DistanceMm;
      tipClass = static_cast<int>(c);
    }
  }
  bool alongAxis = false;
  for (const Penetration& p : frame.Penetrations)
  {
    if (p.Known && p.DepthMm > sample.DepthMm)
    {
      sample.DepthMm = p.DepthMm;
      alongAxis = true;
    }
  }
  double rawRate = 0.0;
  const double dt = frame.TimeS - this->PreviousTimeS;
  if (this->HasPrevious && dt > 0.0)
  {
    rawRate = (sample.DepthMm - this->PreviousDepthMm) / dt;
    const double blend = dt / (this->Settings.RateTimeConstantS + dt);
    this->RateMmPerS += blend * (rawRate - this->RateMmPerS);
    this->RateMmPerS = std::clamp(this->RateMmPerS, -this->Settings.MaxRateMmPerS, this->Settings.MaxRateMmPerS);
  }
  this->HasPrevious = true;
  this->PreviousDepthMm = sample.DepthMm;
  this->PreviousTimeS = frame.TimeS;
  sample.RateMmPerS = this->RateMmPerS;
  if (!(sample.DepthMm > 0.0))
  {
    return sample; // outside every vessel: no force, whatever the rate
  }
  sample.ForceN = std::max(0.0, this->Settings.StiffnessNPerMm * sample.DepthMm + this->Settings.DampingNsPerMm * this->RateMmPerS);
  double d[3] = { -frame.AxisWorld[0], -frame.AxisWorld[1], -frame.AxisWorld[2] };
  if (!alongAxis && tipClass >= 0)
  {
    const ClassProximity& p = frame.Proximity.Classes[static_cast<std::size_t>(tipClass)];
    for (int a = 0; a < 3; ++a)
    {
      d[a] = p.ClosestPoint[a] - frame.TipMm[a];
    }
  }
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int a = 0; a < 3 && n > 0.0; ++a)
  {
    sample.Direction[a] = d[a] / n;
  }
  if (!(n > 0.0))
  {
    sample.ForceN = 0.0; // no direction to push in (a tip exactly on the wall)
  }
  return sample;
}
} // namespace vp
