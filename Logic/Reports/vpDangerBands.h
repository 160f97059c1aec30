#ifndef vpDangerBands_h
#define vpDangerBands_h

#include "vpDangerLevels.h"
#include "vpDistancePlot.h"

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// The plot's background: one band per danger level below the caution threshold and the safe
/// band above it, open-ended ("safe (> 10 mm)"), in the level's display colour, so that the axis
/// follows the data (AutomaticYMax: up to the data's largest value, never below the caution
/// threshold, so every threshold stays in view) rather than the engine's range: a run that stays
/// within 5 mm is no longer a flat line at the bottom of 0-55 mm. The same bands in the report
/// (distance.png) and in the viewer's live plot. With breachBelowZero, a breach band below 0 too,
/// for plots where a penetration is drawn as a negative distance.
std::vector<PlotBand> DangerBands(const DangerThresholds& thresholds, bool breachBelowZero = false);

/// A colour's bytes from VTK's 0..1 components (rounded), and VTK's components from its bytes.
Rgb ToRgb(const std::array<double, 3>& fraction);
std::array<double, 3> ToFraction(const Rgb& colour);

/// The display colour of a vessel class, the same in the scene, the readout and the plot: the
/// default label table's (as Slicer's colour tables give the anatomy: portal vein blue, hepatic
/// artery red, hepatic vein dark blue, liver tan); a class the table does not know takes a
/// palette colour by its index. The plot rims each line in black or white against its band.
Rgb ClassDisplayColour(const std::string& className, int classIndex);

/// The display colour of a tumour in the scene and the readout: a sap green, far (40 CIELAB units
/// or more) from every danger level's colour and every class of the default label table, so that
/// the tumour is never read as a vessel nor as a warning.
const Rgb TumourDisplayColour = { 96, 168, 64 };

/// The viewer's background behind the readout (the top of its gradient) and the colour a class's
/// readout line is written in there: its display colour lifted towards white until its WCAG
/// contrast against that background is at least 4.5 (the dark-blue hepatic veins' own colour is
/// 1.3 there).
const Rgb ViewBackgroundTop = { 64, 69, 92 };
const Rgb ViewBackgroundBottom = { 13, 15, 26 };
Rgb ReadoutTextColour(const Rgb& classColour);

/// CIE L*a*b* (D65) of an sRGB colour, and the CIE76 distance of two colours (about 2.3 is a just
/// noticeable difference; the levels keep 20 or more from every class colour).
std::array<double, 3> CieLab(const Rgb& colour);
double CieLabDistance(const Rgb& a, const Rgb& b);
} // namespace vp

#endif
