#ifndef vpApproachPlan_h
#define vpApproachPlan_h

#include "vpDangerLevels.h"
#include "vpMarginLevels.h"
#include "vpPoseFile.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace vp
{
/// What a planned approach is asked: the target and where the instrument comes from, in the
/// logic's names (a front end reports a vp::ParameterError under its own option's name: TargetName,
/// EntryMm, DirectionLps, StepMm, MarginMm, SearchDeg, SearchStepDeg, StandOffMm). LPS mm.
///
/// The instrument moves in a straight line along the approach direction, its axis on it, tip
/// first: from the entry to where the line first meets the target's surface and MarginMm beyond,
/// a pose every StepMm (the last pose exactly at the end).
struct ApproachPlanRequest
{
  /// The target's surface (LPS mm, closed) and its name for reports.
  vtkSmartPointer<vtkPolyData> Target;
  std::string TargetName;
  /// The point the approach aims at: the centre of the target's enclosed volume when unset.
  std::optional<std::array<double, 3>> TargetCentreMm;
  /// Exactly one of the two: the entry (the direction is then from it to the target's centre), or
  /// the direction itself (need not be unit; the line then passes through the target's centre and
  /// the entry lies StandOffMm back from where it meets the target's surface).
  std::optional<std::array<double, 3>> EntryMm;
  std::optional<std::array<double, 3>> DirectionLps;
  /// With a direction: how far back from the target's surface the entry lies. Unset: the way out
  /// of LiverBoundsMm (and 10 mm more) when given, else DefaultStandOffMm.
  std::optional<double> StandOffMm;
  std::optional<std::array<double, 6>> LiverBoundsMm;
  double StepMm = 1.0;
  double MarginMm = MarginSettings().MarginMm; ///< the resection margin's default: the tip ends as deep as track's margin
  /// The cone searched for a safer approach: directions within SearchDeg of the asked one, on rings
  /// SearchStepDeg apart (and as far apart around each ring), every one aimed at the target's centre
  /// from as far back as the asked one. 0: no search.
  double SearchDeg = 0.0;
  double SearchStepDeg = 5.0;
  /// The time between two poses of the plan (s).
  double TimeStepS = 0.1;

  static constexpr double DefaultStandOffMm = 60.0;
  static constexpr double MaximumMarginMm = MarginSettings::MaximumMm;
  static constexpr double MaximumSearchDeg = 60.0;
  static constexpr int MaximumSteps = 100000;
};

/// The whole instrument's closest approach to one vessel class along an approach.
struct ClassApproach
{
  std::string ClassName;
  /// False when the class was never within the engine's range: the rest is then meaningless.
  bool InRange = false;
  double ClosestMm = 0.0; ///< the smallest whole-instrument surface distance (0: touching or inside)
  int Step = -1;          ///< the first pose (0 = the entry) at which it is reached (within 1 µm)
  double TimeS = 0.0;
  double PointMm[3] = { 0, 0, 0 };       ///< the closest vessel point at that pose
  double PointOnToolMm[3] = { 0, 0, 0 }; ///< and the instrument's
  double PenetrationDepthMm = 0.0;       ///< the deepest the instrument went into the class (0: never)
};

/// One straight approach, computed.
struct PlannedApproach
{
  std::array<double, 3> EntryMm{};
  std::array<double, 3> Direction{};     ///< unit
  std::array<double, 3> SurfacePointMm{}; ///< where the line first meets the target's surface
  std::array<double, 3> EndMm{};          ///< MarginMm past it: the tip's last position
  double AngleFromAskedDeg = 0.0;
  /// Per pose: time, x, y, z, qw, qx, qy, qz as the plan's pose file writes them, and the pose each
  /// makes, read as a pose file's row is read (vp::MakeTrackedPose): replayed, the same frames.
  std::vector<std::array<double, 8>> PoseValues;
  std::vector<TrackedPose> Poses;
  std::vector<ClassApproach> Classes; ///< the scene's vessel classes, in its order
  /// The smallest whole-instrument distance over every class and pose (the engine's range when no
  /// class came within it), and the class that set it (empty then).
  double ClearanceMm = 0.0;
  std::string ClearanceClass;
  /// Per pose: the frame's danger level (the worse of the tip's and the instrument's).
  std::vector<DangerLevel> StepLevels;
  /// The tip's signed distance to the target at the last pose (negative inside), when measured.
  std::optional<double> TipTargetSignedMm;
};

/// The plan: the asked approach, and with a search, the safest of the cone (the asked one when no
/// other is safer).
struct ApproachPlan
{
  std::string TargetName;
  std::array<double, 3> TargetCentreMm{};
  double StepMm = 1.0;
  double MarginMm = MarginSettings().MarginMm;
  double TimeStepS = 0.1;
  double RangeMm = 0.0; ///< the engine's range: classes further are out of range
  PlannedApproach Asked;
  std::optional<PlannedApproach> Safest;
  double SearchDeg = 0.0;
  double SearchStepDeg = 0.0;
  int DirectionsSearched = 0; ///< besides the asked one
  int DirectionsMissing = 0;  ///< of those, the ones whose line missed the target
  /// Every pose's computing time (ms: the frame's, as track measures it), the asked approach's
  /// and the search's.
  std::vector<double> StepMs;
};
} // namespace vp

#endif
