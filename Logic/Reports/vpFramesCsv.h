#ifndef vpFramesCsv_h
#define vpFramesCsv_h

#include "vtkScalpelTrackingLogic.h"

#include <string>
#include <vector>

namespace vp
{
/// frames.csv, the per-frame record of a tracking run (columns in README's "track"), written a
/// row at a time as the frames are computed. Lengths and coordinates to 4 decimals, times to 6,
/// an empty field where there is no value (out of range, not known), never a made-up 0.
/// Throws ParameterError("Vessels") when the class names would give two columns one name: a
/// class named "nearest" (nearest_mm), "danger" (danger_level), or "x" beside "x_surface"
/// (x_surface_mm twice), and with tumours, a class named "tumour" (tumour_mm) or "margin"
/// (margin_level): a class of those names is a class like any other without tumours.
void CheckFramesCsvColumns(const std::vector<std::string>& classes, bool tumour = false);
/// The header line, for these classes, with the whole surface's columns or without, with the
/// haptic force's (haptic_force_n, haptic_x/y/z: the force and its unit direction, world) or
/// without, and with the resection margin's or without: tumour_mm (the tip's signed distance,
/// negative inside), tumour_id, tumour_point_x/y/z, margin_level and tumour_surface_mm (the whole
/// instrument's, 0 where it touches), all of the tumour that sets the margin's level.
std::string FramesCsvHeader(const std::vector<std::string>& classes, bool surface, bool haptic = false, bool tumour = false);
/// One frame's line, the columns as the header's (the haptic ones when the frame has a force, the
/// margin's when it has tumours).
std::string FramesCsvRow(const TrackedFrame& frame, bool surface);
} // namespace vp

#endif
