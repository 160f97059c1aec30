#include "vpPlotValues.h"

#include <algorithm>
#include <cstdio>
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

double InstrumentVolumeMm3(const TrackedFrame& frame, std::size_t c)
{
  return c < frame.Penetrations.size() && frame.Penetrations[c].Known ? frame.Penetrations[c].VolumeMm3 : 0.0;
}

std::string InstrumentVolumeNote(double largestVolumeMm3)
{
  if (!(largestVolumeMm3 > 0.0))
  {
    return std::string();
  }
  char note[48];
  std::snprintf(note, sizeof note, largestVolumeMm3 < 10.0 ? "up to %.1f mm^3 in" : "up to %.0f mm^3 in", largestVolumeMm3);
  return note;
}

std::string DistanceText(double distanceMm, double boundMm, int decimals)
{
  char text[64];
  if (boundMm > 0)
  {
    std::snprintf(text, sizeof text, "%.*f-%.*f", decimals, std::max(0.0, distanceMm - boundMm), decimals, distanceMm + boundMm);
  }
  else
  {
    std::snprintf(text, sizeof text, "%.*f", decimals, distanceMm);
  }
  return text;
}

Rgb InstrumentColour(const Rgb& c)
{
  auto lighter = [](unsigned char v) { return static_cast<unsigned char>((v + 2 * 255) / 3); };
  return { lighter(c[0]), lighter(c[1]), lighter(c[2]) };
}
} // namespace vp
