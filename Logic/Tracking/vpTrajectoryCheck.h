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
  ///    or with x and y negated (mirrored: RAS read as LPS);
  ///  - the frames are more than 2 s apart at the median (milliseconds read as seconds).
  std::vector<TrajectoryWarning> Warnings() const;

private:
  /// How many tips fall in the vessels' box grown by the range: as read, times 1000, divided by
  /// 1000, mirrored.
  bool NearVessels(const double tip[3]) const;
  double Box[6];
  double RangeMm;
  std::size_t Frames = 0;
  std::size_t FramesInRange = 0;
  std::array<std::size_t, 4> Near{};
  double PreviousTimeS = 0.0;
  std::size_t LongIntervals = 0; ///< frames more than 2 s after the previous
};
} // namespace vp

#endif
