#include "vpDangerBands.h"

#include "vpVesselLabelTable.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vp
{
std::vector<PlotBand> DangerBands(const DangerThresholds& t, bool breachBelowZero)
{
  std::vector<PlotBand> bands;
  const double edges[5] = { 0.0, t.DangerMm, t.WarningMm, t.CautionMm, std::numeric_limits<double>::infinity() };
  for (int l = 0; l < 4; ++l)
  {
    const auto level = static_cast<DangerLevel>(3 - l);
    bands.push_back({ edges[l], edges[l + 1], DangerLevelColour(level), DangerLevelName(level) });
  }
  if (breachBelowZero)
  {
    bands.push_back({ -std::numeric_limits<double>::infinity(), 0.0, DangerLevelColour(DangerLevel::Breach),
      DangerLevelName(DangerLevel::Breach) });
  }
  return bands;
}

Rgb ToRgb(const std::array<double, 3>& fraction)
{
  return { static_cast<unsigned char>(std::lround(255 * fraction[0])), static_cast<unsigned char>(std::lround(255 * fraction[1])),
    static_cast<unsigned char>(std::lround(255 * fraction[2])) };
}

std::array<double, 3> ToFraction(const Rgb& colour)
{
  return { colour[0] / 255.0, colour[1] / 255.0, colour[2] / 255.0 };
}

Rgb ClassDisplayColour(const std::string& className, int classIndex)
{
  static const VesselLabelTable table = VesselLabelTable::Default();
  const auto& classes = table.Classes();
  if (std::find(classes.begin(), classes.end(), className) != classes.end())
  {
    return ToRgb(table.Color(className));
  }
  static const Rgb palette[] = { { 40, 160, 60 }, { 120, 120, 0 }, { 0, 160, 140 }, { 150, 90, 40 } };
  const int n = static_cast<int>(sizeof(palette) / sizeof(palette[0]));
  return palette[((classIndex % n) + n) % n];
}

Rgb ReadoutTextColour(const Rgb& classColour)
{
  for (int step = 0; step <= 20; ++step)
  {
    const double t = step / 20.0;
    Rgb lifted;
    for (int k = 0; k < 3; ++k)
    {
      lifted[k] = static_cast<unsigned char>(std::lround(classColour[k] + t * (255 - classColour[k])));
    }
    if (ContrastRatio(lifted, ViewBackgroundTop) >= 4.5)
    {
      return lifted;
    }
  }
  return { 255, 255, 255 };
}

std::array<double, 3> CieLab(const Rgb& colour)
{
  double linear[3];
  for (int k = 0; k < 3; ++k)
  {
    const double v = colour[k] / 255.0;
    linear[k] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double xyz[3] = { (0.4124564 * linear[0] + 0.3575761 * linear[1] + 0.1804375 * linear[2]) / 0.95047,
    0.2126729 * linear[0] + 0.7151522 * linear[1] + 0.0721750 * linear[2],
    (0.0193339 * linear[0] + 0.1191920 * linear[1] + 0.9503041 * linear[2]) / 1.08883 };
  double f[3];
  for (int k = 0; k < 3; ++k)
  {
    f[k] = xyz[k] > 216.0 / 24389.0 ? std::cbrt(xyz[k]) : (24389.0 / 27.0 * xyz[k] + 16.0) / 116.0;
  }
  return { 116.0 * f[1] - 16.0, 500.0 * (f[0] - f[1]), 200.0 * (f[1] - f[2]) };
}

double CieLabDistance(const Rgb& a, const Rgb& b)
{
  const std::array<double, 3> x = CieLab(a), y = CieLab(b);
  return std::sqrt((x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]));
}
} // namespace vp
