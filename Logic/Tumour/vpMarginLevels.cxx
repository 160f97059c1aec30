#include "vpMarginLevels.h"

#include "vpInputError.h"

#include <cmath>

namespace vp
{
void MarginSettings::Validate(const std::string& source) const
{
  if (!(this->MarginMm >= 0.0 && this->MarginMm <= MaximumMm))
  {
    throw ParameterError(source, "the margin must be a distance from 0 to " + NumberText(MaximumMm) + " mm, got " +
      NumberText(this->MarginMm));
  }
  if (!(this->NearBandMm >= 0.0 && this->NearBandMm <= MaximumMm))
  {
    throw ParameterError(source, "the near band must be a distance from 0 to " + NumberText(MaximumMm) + " mm, got " +
      NumberText(this->NearBandMm));
  }
}

const char* MarginLevelName(MarginLevel level)
{
  switch (level)
  {
    case MarginLevel::Clear:
      return "clear";
    case MarginLevel::Near:
      return "near";
    case MarginLevel::Violated:
      return "violated";
    case MarginLevel::Inside:
      return "inside";
  }
  return "inside";
}

namespace
{
/// The distance at or beyond which a level is left (its upper edge), for the levels below Clear.
double UpperEdgeMm(MarginLevel level, const MarginSettings& s)
{
  switch (level)
  {
    case MarginLevel::Inside:
      return 0.0;
    case MarginLevel::Violated:
      return s.MarginMm;
    default:
      return s.MarginMm + s.NearBandMm;
  }
}
} // namespace

MarginLevel ClassifyMargin(
  double signedMm, bool insideUncertain, const MarginSettings& settings, MarginLevel previous, double hysteresisMm)
{
  MarginLevel level = MarginLevel::Clear;
  if (insideUncertain || !(signedMm >= 0.0)) // NaN: not known to be outside
  {
    level = MarginLevel::Inside;
  }
  else if (signedMm < settings.MarginMm)
  {
    level = MarginLevel::Violated;
  }
  else if (signedMm < settings.MarginMm + settings.NearBandMm)
  {
    level = MarginLevel::Near;
  }
  // Leaving a level for a less concerning one: only once the distance is hysteresisMm past the
  // edge; every level in between is then checked the same way.
  for (MarginLevel held = previous; held > level; held = static_cast<MarginLevel>(static_cast<int>(held) - 1))
  {
    if (signedMm < UpperEdgeMm(held, settings) + hysteresisMm)
    {
      return held;
    }
  }
  return level;
}
} // namespace vp
