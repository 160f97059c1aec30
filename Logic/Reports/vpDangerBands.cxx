#include "vpDangerBands.h"

#include <algorithm>

#include <limits>

namespace vp
{
std::vector<PlotBand> DangerBands(const DangerThresholds& t, double rangeMm, bool breachBelowZero)
{
  std::vector<PlotBand> bands;
  const double top = std::max(rangeMm, t.CautionMm);
  const double edges[5] = { 0.0, t.DangerMm, t.WarningMm, t.CautionMm, top };
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

Rgb PlotSeriesColour(const std::string& className, int classIndex)
{
  if (className == "portal_vein")
  {
    return { 0, 150, 200 };
  }
  if (className == "hepatic_artery")
  {
    return { 215, 60, 50 };
  }
  if (className == "hepatic_vein")
  {
    return { 110, 40, 180 };
  }
  static const Rgb palette[] = { { 40, 160, 60 }, { 230, 140, 20 }, { 120, 120, 0 }, { 200, 60, 160 } };
  const int n = static_cast<int>(sizeof(palette) / sizeof(palette[0]));
  return palette[((classIndex % n) + n) % n];
}
} // namespace vp
