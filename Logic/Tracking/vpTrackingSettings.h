#ifndef vpTrackingSettings_h
#define vpTrackingSettings_h

#include "vpDangerLevels.h"
#include "vpHaptics.h"
#include "vpMarginLevels.h"

namespace vp
{
/// What the frame loop applies to every frame, never a reason to rebuild an engine. The defaults
/// here are the only ones: the tracking logic, the parameter set, the scene request and every
/// front end's help take them from this struct.
struct TrackingSettings
{
  /// Caution, warning and danger distances (10, 5, 2 mm); a tip inside a vessel is a breach.
  DangerThresholds Thresholds;
  /// A level is entered at once but left only this far beyond its threshold (0: no hysteresis):
  /// tracking noise of a tenth of a millimetre at a threshold would otherwise flicker the level.
  double HysteresisMm = 0.3;
  /// The time one frame may take: one refresh at 60 Hz (the paper's 40 ms is 25 Hz); 0: none.
  double FrameBudgetMs = 16.7;
  /// The contact force sent to a haptic device (off by default).
  HapticSettings Haptic;
  /// The resection margin around the tumours and its near band (5 mm each); used with tumours.
  MarginSettings Margin;
};
} // namespace vp

#endif
