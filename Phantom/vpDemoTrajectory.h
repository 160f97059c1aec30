#ifndef vpDemoTrajectory_h
#define vpDemoTrajectory_h

#include "vpDangerLevels.h"
#include "vpLiverPhantom.h"
#include "vpPoseFile.h"

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// A moment of the demo path that the design aims at, for the self-test to assert.
struct DemoKeyPoint
{
  std::string Name; ///< "start", "breach", "withdrawn", "hepatic pass", "end"
  double TimeS = 0.0;
  std::array<double, 3> TipMm{};
  std::string ClassName;   ///< the class nearest the tip there
  double DistanceMm = 0.0; ///< analytic signed distance to that class's surface (negative inside)
  DangerLevel Level = DangerLevel::Safe;
};

/// The demo's scalpel path and what it was designed to do.
struct DemoTrajectory
{
  std::vector<TrackedPose> Poses;
  std::vector<DemoKeyPoint> KeyPoints;
  /// The world direction of the model's +z axis (out through the tip), the same in every pose:
  /// the instrument comes in from anterior-superior, tip first.
  std::array<double, 3> AxisDirection{};
  /// Mean radius of the portal-vein piece breached and of the hepatic-vein piece passed (mm).
  double TargetRadiusMm = 0.0;
  double PassRadiusMm = 0.0;
};

/// Designs the CUSA tip's path through the phantom from its analytic centrelines: it starts more
/// than 15 mm from every vessel, approaches a portal-vein branch of medium calibre (4.6-7.2 mm)
/// along the instrument's axis until the tip is 1 mm inside it (a breach), withdraws along the
/// same line to more than 10 mm, moves across to a hepatic-vein branch and sweeps past it at
/// 3.5 mm from its surface (warning), and ends more than 12 mm from every vessel. Danger levels of
/// the nearest vessel, in order (default thresholds): safe, caution, warning, danger, breach,
/// danger, warning, caution, safe, caution, warning, caution, safe. Every extremum of the
/// distance along the path, and every key point, stays at least 0.75 mm from every threshold, so
/// that a surface built from voxels (about half a voxel from the analytic one) gives the same
/// sequence.
///
/// Motion: straight legs with smooth (half-cosine) speed profiles, mean speeds of 6-8 mm/s and
/// peaks under 15 mm/s, 15-25 s in all; a short pause inside the vessel. The pose is the
/// model-to-world matrix of the CUSA handpiece (MakeCusaHandpiece: tip at the model origin, axis
/// +z), sampled at rateHz; its rotation never changes, so there are no flips. Deterministic.
/// Throws vp::InputError for a rate outside 1-1000 Hz, or when the phantom offers no path that
/// meets all of this (not the case for the default phantom).
DemoTrajectory DesignDemoTrajectory(const LiverPhantom& phantom, double rateHz = 50.0);

/// The poses of DesignDemoTrajectory.
std::vector<TrackedPose> MakeDemoTrajectory(const LiverPhantom& phantom, double rateHz = 50.0);

/// The levels the demo path visits by design, in order, repeats removed, from its first pose
/// (safe) to its last (safe): 13 entries.
std::vector<DangerLevel> DemoTrajectoryLevelSequence();

/// Signed analytic distance from a point to each vessel class of the phantom (its Centrelines),
/// and the nearest one; DangerLevel::Breach when that distance is negative.
struct AnalyticProximity
{
  std::string NearestClass;
  double NearestMm = 0.0;
  DangerLevel Level = DangerLevel::Safe;
};
AnalyticProximity AnalyticProximityAt(
  const LiverPhantom& phantom, const std::array<double, 3>& tipMm, const DangerThresholds& thresholds = {});
} // namespace vp

#endif
