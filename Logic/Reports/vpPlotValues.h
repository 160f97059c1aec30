#ifndef vpPlotValues_h
#define vpPlotValues_h

#include "vpDistancePlot.h"
#include "vtkScalpelTrackingLogic.h"

#include <cstddef>
#include <string>

namespace vp
{
/// What the distance plots draw for class c of a frame, shared by the report (distance.png) and
/// the live plot, so both say the same: distances above zero, penetrations below.
/// The tip: its distance, minus it when the tip is inside; NaN (a gap) out of range.
double TipPlotValueMm(const TrackedFrame& frame, std::size_t c);
/// The whole instrument: minus its penetration depth when it is inside, else its distance; NaN
/// out of range or when the instrument was not measured.
double InstrumentPlotValueMm(const TrackedFrame& frame, std::size_t c);
/// The instrument's penetration volume in class c (mm3): 0 when it is not inside, not measured
/// or not known.
double InstrumentVolumeMm3(const TrackedFrame& frame, std::size_t c);
/// The instrument line's note at its deepest point (PlotSeries::DeepestNote): the largest
/// penetration volume over the frames the line shows, "up to 3.7 mm3 in"; empty when none. The
/// depth is the line itself, below zero.
std::string InstrumentVolumeNote(double largestVolumeMm3);
/// A distance as the screen shows it, in mm to `decimals` places: the value ("1.5") from an exact
/// engine, or, from one that answers within boundMm of the truth, the interval the truth lies in
/// ("1.1-1.9", never below 0), so that a bound is never read as an exact number.
std::string DistanceText(double distanceMm, double boundMm, int decimals = 1);
/// The instrument's line: the class's hue, lighter, beside the tip's.
Rgb InstrumentColour(const Rgb& classColour);
} // namespace vp

#endif
