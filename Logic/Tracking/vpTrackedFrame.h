#ifndef vpTrackedFrame_h
#define vpTrackedFrame_h

#include "vpDangerLevels.h"
#include "vpHapticForce.h"
#include "vpProximityResult.h"
#include "vpTumourProximity.h"

#include <optional>
#include <string>
#include <vector>

namespace vp
{
/// Everything known about one tracked frame.
struct TrackedFrame
{
  int Frame = 0;
  double TimeS = 0.0;
  double TipMm[3] = { 0, 0, 0 };   ///< world
  double AxisWorld[3] = { 0, 0, 1 };
  ProximityResult Proximity;       ///< per class: distance, closest point, inside, directional
  std::vector<DangerLevel> ClassLevels;
  DangerLevel Level = DangerLevel::Safe; ///< the worst over the classes
  int LevelClass = -1;             ///< the class that set Level, -1 when all are safe
  std::vector<SurfaceProximity> Surface; ///< per class; empty when not computed
  std::vector<Penetration> Penetrations; ///< per class: the instrument inside it; empty when not computed
  double FrameMs = 0.0;            ///< wall time of the distance queries of this frame
  /// Where FrameMs went: the tip's query, the whole instrument's distance, its penetration, the
  /// tumours' margins (ms; 0 for a part not computed).
  struct Parts
  {
    double TipMs = 0.0;
    double SurfaceMs = 0.0;
    double PenetrationMs = 0.0;
    double MarginMs = 0.0;
  } PartsMs;
  bool OverBudget = false;         ///< FrameMs exceeded the tracking logic's frame budget
  std::optional<HapticSample> Haptic; ///< with haptics on (TrackingSettings::Haptic)
  /// The tip and the whole instrument against each tumour, with the margin levels; with tumours.
  std::optional<TumourMargin> Tumour;
};

/// A change of the overall danger level between two frames.
struct DangerLevelChange
{
  int Frame = 0;
  double TimeS = 0.0;
  DangerLevel From = DangerLevel::Safe;
  DangerLevel To = DangerLevel::Safe;
  std::string ClassName; ///< the class that sets the new level (empty when it is safe)
  double DistanceMm = 0.0; ///< that class's distance, 0 when none
};

/// A change of the resection margin's level (the worst over the tumours) between two frames.
struct MarginLevelChange
{
  int Frame = 0;
  double TimeS = 0.0;
  MarginLevel From = MarginLevel::Clear;
  MarginLevel To = MarginLevel::Clear;
  std::string TumourId;  ///< the tumour that sets the new level
  double SignedMm = 0.0; ///< the tip's signed distance to it (negative inside)
};
} // namespace vp

#endif
