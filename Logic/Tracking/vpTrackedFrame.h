#ifndef vpTrackedFrame_h
#define vpTrackedFrame_h

#include "vpDangerLevels.h"
#include "vpHaptics.h"
#include "vpProximityResult.h"
#include "vpTumourProximity.h"

#include <algorithm>
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
  double SourceClockS = 0.0; ///< the pose's own time stamp (TrackedPose::SourceClockS), 0: none
  double TipMm[3] = { 0, 0, 0 };   ///< world
  double AxisWorld[3] = { 0, 0, 1 };
  ProximityResult Proximity;       ///< per class: distance, closest point, inside, directional
  /// The exact engine's answer for the same tip, when the tracking logic checks its engine
  /// against one (vtkScalpelTrackingLogic::SetReferenceEngine); outside FrameMs.
  std::optional<ProximityResult> Exact;
  std::vector<DangerLevel> ClassLevels; ///< per class, the tip's level
  /// Per class, the whole instrument's level (vp::ClassifyInstrumentWithHysteresis); empty when
  /// the instrument is not measured.
  std::vector<DangerLevel> InstrumentClassLevels;
  DangerLevel TipLevel = DangerLevel::Safe; ///< the worst of ClassLevels
  int TipLevelClass = -1;                  ///< the class that set it, -1 when all are safe
  DangerLevel InstrumentLevel = DangerLevel::Safe; ///< the worst of InstrumentClassLevels
  int InstrumentLevelClass = -1;
  /// The frame's level: the worse of the tip's and the instrument's (the tip's when they are
  /// equal), the class that set it (-1 when safe) and which of the two did.
  DangerLevel Level = DangerLevel::Safe;
  int LevelClass = -1;
  DangerCause LevelCause = DangerCause::None;
  /// A class's level in this frame: the worse of the tip's and the instrument's.
  DangerLevel ClassLevel(std::size_t c) const
  {
    const DangerLevel tip = c < this->ClassLevels.size() ? this->ClassLevels[c] : DangerLevel::Safe;
    return c < this->InstrumentClassLevels.size() ? std::max(tip, this->InstrumentClassLevels[c]) : tip;
  }
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
  /// Whether the tip or the whole instrument sets it, and that one's distance to the class (0
  /// when none; for an instrument inside the class, 0).
  DangerCause Cause = DangerCause::None;
  double DistanceMm = 0.0;
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
