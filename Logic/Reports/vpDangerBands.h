#ifndef vpDangerBands_h
#define vpDangerBands_h

#include "vpDangerLevels.h"
#include "vpDistancePlot.h"

#include <string>
#include <vector>

namespace vp
{
/// The plot's background: one band per danger level below the caution threshold and the safe
/// band up to max(rangeMm, caution), in the level's display colour. The same bands in the report
/// (distance.png) and in the viewer's live plot. With breachBelowZero, a breach band below 0 too,
/// for plots where a penetration is drawn as a negative distance.
std::vector<PlotBand> DangerBands(const DangerThresholds& thresholds, double rangeMm, bool breachBelowZero = false);

/// The colour of a vessel class's plot line: a hue near the class's display colour (portal vein
/// cyan, hepatic artery red, hepatic vein violet), saturated enough to stand out on the
/// white-to-blue bands, which the dark-blue hepatic veins' own colour would not. Other classes
/// take a palette colour by their index.
Rgb PlotSeriesColour(const std::string& className, int classIndex);
} // namespace vp

#endif
