#include "vpDangerLevels.h"

#include "vpInputError.h"

#include <algorithm>
#include <cmath>

namespace vp
{
void DangerThresholds::Validate(const std::string& source) const
{
  const bool finite = std::isfinite(this->CautionMm) && std::isfinite(this->WarningMm) && std::isfinite(this->DangerMm);
  if (!finite || !(this->CautionMm > this->WarningMm && this->WarningMm > this->DangerMm && this->DangerMm > 0))
  {
    throw InputError(source, "danger thresholds must fall: caution > warning > danger > 0 mm (got " +
        NumberText(this->CautionMm) + ", " + NumberText(this->WarningMm) + ", " + NumberText(this->DangerMm) + ")");
  }
}

const char* DangerLevelName(DangerLevel level)
{
  switch (level)
  {
    case DangerLevel::Safe:
      return "safe";
    case DangerLevel::Caution:
      return "caution";
    case DangerLevel::Warning:
      return "warning";
    case DangerLevel::Danger:
      return "danger";
    case DangerLevel::Breach:
      return "breach";
  }
  return "unknown";
}

std::array<unsigned char, 3> DangerLevelColour(DangerLevel level)
{
  switch (level)
  {
    case DangerLevel::Safe:
      return { 255, 255, 255 };
    case DangerLevel::Caution:
      return { 190, 190, 190 }; // 23 CIELAB units below white (200 was 19)
    case DangerLevel::Warning:
      return { 120, 120, 120 };
    case DangerLevel::Danger:
      return { 255, 220, 0 };
    case DangerLevel::Breach:
      return { 255, 0, 255 };
  }
  return { 0, 0, 0 };
}

DangerLevel ClassifyDistance(double distanceMm, const DangerThresholds& thresholds)
{
  if (distanceMm <= thresholds.DangerMm)
  {
    return DangerLevel::Danger;
  }
  if (distanceMm <= thresholds.WarningMm)
  {
    return DangerLevel::Warning;
  }
  if (distanceMm <= thresholds.CautionMm)
  {
    return DangerLevel::Caution;
  }
  return DangerLevel::Safe;
}

DangerLevel ClassifyDanger(const ClassProximity& proximity, double errorBoundMm, const DangerThresholds& thresholds)
{
  // Inside, or not certain that it is outside (the votes on a defective surface disagreed),
  // whatever the distance: a tip deeper than the range is still a breach.
  if (proximity.Inside.value_or(false) || proximity.InsideUncertain)
  {
    return DangerLevel::Breach;
  }
  if (!proximity.InRange)
  {
    return DangerLevel::Safe;
  }
  // An approximate engine's "outside" cannot be trusted near a wall: the z-buffer decides inside
  // at its pixel centre, up to half a pixel diagonal from the tip, so a tip that close to a wall
  // may be on either side, and its reported distance is then at most that plus its bound. Within
  // twice the bound (more than that sum) it is taken as inside: breach-or-danger is breach.
  if (errorBoundMm > 0.0 && proximity.DistanceMm <= 2.0 * errorBoundMm)
  {
    return DangerLevel::Breach;
  }
  return ClassifyDistance(proximity.DistanceMm - errorBoundMm, thresholds);
}

DangerLevel ClassifyDangerWithHysteresis(const ClassProximity& proximity, double errorBoundMm,
  const DangerThresholds& thresholds, DangerLevel previous, double hysteresisMm)
{
  const DangerLevel now = ClassifyDanger(proximity, errorBoundMm, thresholds);
  if (now >= previous || !(hysteresisMm > 0.0) || !proximity.InRange)
  {
    return now; // in, or no hysteresis, or gone out of range (beyond the caution threshold)
  }
  // Leaving: the level held is the one the thresholds raised by the hysteresis give, never above
  // the previous level and never below the level now.
  const DangerThresholds raised{ thresholds.CautionMm + hysteresisMm, thresholds.WarningMm + hysteresisMm,
    thresholds.DangerMm + hysteresisMm };
  DangerLevel held = ClassifyDanger(proximity, errorBoundMm, raised);
  if (previous == DangerLevel::Breach && proximity.DistanceMm - errorBoundMm <= hysteresisMm)
  {
    held = DangerLevel::Breach;
  }
  return std::max(now, std::min(previous, held));
}

DangerLevel ClassifyInstrumentWithHysteresis(const SurfaceProximity& surface, const Penetration* penetration,
  const DangerThresholds& thresholds, DangerLevel previous, double hysteresisMm)
{
  // The instrument as a tip would be: inside when any of it is, its distance the surfaces'. An
  // approximate surface distance is already the low end of where the truth lies (the truth is
  // between it and it plus its bound), so it is graded as it is: taking the bound off again read
  // the demo's instrument 2.9 mm away (bound 1.5) as a breach.
  ClassProximity asTip;
  asTip.InRange = surface.InRange;
  asTip.DistanceMm = surface.DistanceMm;
  if (penetration)
  {
    asTip.Inside = penetration->Known && (penetration->VolumeMm3 > 0.0 || penetration->DepthMm > 0.0);
    asTip.InsideUncertain = !penetration->Known && surface.InRange && surface.DistanceMm <= 0.0;
  }
  return ClassifyDangerWithHysteresis(asTip, 0.0, thresholds, previous, hysteresisMm);
}

const char* DangerCauseName(DangerCause cause)
{
  switch (cause)
  {
    case DangerCause::None:
      return "";
    case DangerCause::Tip:
      return "tip";
    case DangerCause::Instrument:
      return "instrument";
  }
  return "";
}
} // namespace vp
