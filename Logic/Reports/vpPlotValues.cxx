#include "vpPlotValues.h"

#include <limits>

namespace vp
{
double TipPlotValueMm(const TrackedFrame& frame, std::size_t c)
{
  if (c >= frame.Proximity.Classes.size() || !frame.Proximity.Classes[c].InRange)
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const ClassProximity& p = frame.Proximity.Classes[c];
  return p.Inside.value_or(false) ? -p.DistanceMm : p.DistanceMm;
}

double InstrumentPlotValueMm(const TrackedFrame& frame, std::size_t c)
{
  if (c < frame.Penetrations.size() && frame.Penetrations[c].Known && frame.Penetrations[c].DepthMm > 0.0)
  {
    return -frame.Penetrations[c].DepthMm;
  }
  if (c < frame.Surface.size() && frame.Surface[c].InRange)
  {
    return frame.Surface[c].DistanceMm;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

Rgb InstrumentColour(const Rgb& c)
{
  auto lighter = [](unsigned char v) { return static_cast<unsigned char>((v + 2 * 255) / 3); };
  return { lighter(c[0]), lighter(c[1]), lighter(c[2]) };
}
} // namespace vp
