#ifndef vpDangerLevels_h
#define vpDangerLevels_h

#include "vpProximityResult.h"

#include <array>
#include <string>

namespace vp
{
/// How close the instrument is to a vessel, in the order of rising danger.
enum class DangerLevel
{
  Safe = 0, ///< beyond CautionMm, or out of range
  Caution,  ///< within CautionMm
  Warning,  ///< within WarningMm
  Danger,   ///< within DangerMm
  Breach    ///< inside the vessel
};
constexpr int NumberOfDangerLevels = 5;

/// Distance thresholds of the levels, in mm. The defaults bracket the ~5 mm accuracy surgeons
/// asked of the paper's method: caution at 10 mm, warning at 5, danger at 2.
struct DangerThresholds
{
  double CautionMm = 10.0;
  double WarningMm = 5.0;
  double DangerMm = 2.0;

  /// Throws vp::InputError(source, ...) unless CautionMm > WarningMm > DangerMm > 0, all finite.
  void Validate(const std::string& source) const;
};

/// "safe", "caution", "warning", "danger", "breach": the names files and events use.
const char* DangerLevelName(DangerLevel level);
/// The scalpel's colour at each level: the paper's white -> light gray -> dark gray, then yellow
/// for danger and magenta for a breach. The paper's blue danger and red breach were the hepatic
/// veins' blue and the artery's red (CIELAB distances 15 and 13): "the tool is in danger" read
/// as "the tool is over a vein". Every level is at least 40 CIELAB units from every class colour
/// of the default label table (DisplayColours test).
std::array<unsigned char, 3> DangerLevelColour(DangerLevel level);

/// The level of one class's answer. Conservative for approximate engines: the distance less the
/// engine's error bound decides, so the level may overstate the danger but never understate it;
/// and an answer within twice the bound of a wall is a breach, since such an engine cannot tell
/// that close which side of the wall the tip is on (the exact engine, bound 0, always can). An
/// answer whose inside is uncertain (the votes on a defective surface disagreed) is a breach.
DangerLevel ClassifyDanger(const ClassProximity& proximity, double errorBoundMm, const DangerThresholds& thresholds);
/// The level of one class's answer given its level in the frame before, with hysteresis on the way
/// out only: a more dangerous level is entered at once (no breach is ever delayed); a level is left
/// only when the distance exceeds that level's threshold by hysteresisMm (for a breach, the wall:
/// the tip must be hysteresisMm outside). Tracking noise at a threshold then changes the level once
/// in and once out instead of at every frame. hysteresisMm 0 is ClassifyDanger.
DangerLevel ClassifyDangerWithHysteresis(const ClassProximity& proximity, double errorBoundMm,
  const DangerThresholds& thresholds, DangerLevel previous, double hysteresisMm);
/// The level of the whole instrument against one class, graded by the same thresholds as the tip:
/// its surface distance as reported (an approximate one is already the low end of its interval:
/// vp::SurfaceProximity::ErrorBoundMm), any penetration a breach (and one that could not be
/// decided, an open surface, a breach when the surfaces touch or cross), with the hysteresis of
/// ClassifyDangerWithHysteresis on the way out. penetration: null when it was not computed.
DangerLevel ClassifyInstrumentWithHysteresis(const SurfaceProximity& surface, const Penetration* penetration,
  const DangerThresholds& thresholds, DangerLevel previous, double hysteresisMm);
/// What set a frame's level: the tip, or the whole instrument where it is worse than the tip.
enum class DangerCause
{
  None = 0, ///< safe
  Tip,
  Instrument
};
/// "", "tip", "instrument".
const char* DangerCauseName(DangerCause cause);
/// The level of a distance alone (no inside/outside knowledge): Breach is never returned.
DangerLevel ClassifyDistance(double distanceMm, const DangerThresholds& thresholds);
} // namespace vp

#endif
