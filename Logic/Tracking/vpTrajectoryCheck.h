#ifndef vpTrajectoryCheck_h
#define vpTrajectoryCheck_h

#include "vpTrackedFrame.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace vp
{
/// What a run's poses say about how they were read, against where the vessels are: a unit, a
/// frame or a time unit misread turns a trajectory through the liver into one that is "safe"
/// from start to end, without a word. Each warning is a likely misreading, never a correction.
struct TrajectoryWarning
{
  /// "no_pose_near_vessels", "metres", "micrometres", "mirrored" or "milliseconds".
  std::string Kind;
  /// One line, what was seen and what it suggests.
  std::string Text;
};

/// Fed a run's frames one at a time, in memory that does not grow with the run.
class TrajectoryCheck
{
public:
  /// vesselBounds: the box around every vessel (xmin, xmax, ...; LPS mm); rangeMm: how far the
  /// engine looks.
  TrajectoryCheck(const double vesselBounds[6], double rangeMm);
  void Add(const TrackedFrame& frame);
  /// The warnings, the most telling first (empty: nothing seen):
  ///  - no frame had a class within range (no_pose_near_vessels), and besides it
  ///  - most tips, times 1000, fall near the vessels (metres), or divided by 1000 (micrometres),
  ///    or with x and y negated (mirrored: RAS read as LPS), where as read none does; or, judged
  ///    by the vessels' own box, most fall inside it read so and none as read; metres also when
  ///    the trajectory spans under a thousandth of the vessels' extent and, times 1000, lies in
  ///    their box (vessels around the origin);
  ///  - the frames are more than 2 s apart at the median (milliseconds read as seconds).
  std::vector<TrajectoryWarning> Warnings() const;

private:
  /// Whether a tip falls in the box (xmin, xmax, ...).
  static bool InBox(const double box[6], const double tip[3]);
  double Box[6];      ///< the vessels' box grown by the range
  double Vessels[6];  ///< the vessels' own box
  double RangeMm;
  std::size_t Frames = 0;
  std::size_t FramesInRange = 0;
  /// Tips in the grown box, and in the vessels' own box: as read, times 1000, divided by 1000,
  /// mirrored. The own box tells a misreading even where the grown one holds the origin (vessels
  /// around it: metres read as mm fall at the origin, "near" them).
  std::array<std::size_t, 4> Near{};
  std::array<std::size_t, 4> Inside{};
  /// The tips' own box as read: the trajectory's extent.
  double Extent[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  double PreviousTimeS = 0.0;
  std::size_t LongIntervals = 0; ///< frames more than 2 s after the previous
};
} // namespace vp

#endif
