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
/// (x_surface_mm twice).
void CheckFramesCsvColumns(const std::vector<std::string>& classes);
/// The header line, for these classes, with the whole surface's columns or without, and with the
/// haptic force's (haptic_force_n, haptic_x/y/z: the force and its unit direction, world) or without.
std::string FramesCsvHeader(const std::vector<std::string>& classes, bool surface, bool haptic = false);
/// One frame's line, the columns as the header's (the haptic ones when the frame has a force).
std::string FramesCsvRow(const TrackedFrame& frame, bool surface);
} // namespace vp

#endif
