#ifndef vpMarginLevels_h
#define vpMarginLevels_h

#include <string>

namespace vp
{
/// Where the tip stands against a tumour's resection margin, in the order of rising concern.
enum class MarginLevel
{
  Clear = 0, ///< beyond the margin and its near band
  Near,      ///< within NearBandMm outside the margin
  Violated,  ///< within the margin: the cut would leave less healthy tissue than planned
  Inside     ///< in the tumour (or it cannot be told: the votes on a defective surface disagreed)
};
constexpr int NumberOfMarginLevels = 4;

/// The resection margin around every tumour, in mm. Defaults: the 5 mm margin hepatic surgeons
/// commonly plan for a metastasis, and a near band as wide again (the front ends keep the band
/// equal to the margin unless told otherwise), so the display warns a margin's width before the
/// margin is reached.
struct MarginSettings
{
  double MarginMm = 5.0;
  double NearBandMm = 5.0;
  /// The widest margin or band taken (mm): a liver resection's margin is 0-20 mm; a number
  /// beyond this is a unit or a typing error, not a plan.
  static constexpr double MaximumMm = 50.0;

  /// Throws vp::ParameterError(source, ...) unless both are finite and within 0..MaximumMm.
  void Validate(const std::string& source) const;
};

/// "clear", "near", "violated", "inside": the names files and events use.
const char* MarginLevelName(MarginLevel level);

/// The level of a tip signedMm from a tumour's surface (negative inside), given its level in the
/// frame before: a more concerning level is entered at once, a level is left only when the
/// distance exceeds that level's upper edge by hysteresisMm (for Inside, the surface: the tip
/// must be hysteresisMm outside), as vp::ClassifyDangerWithHysteresis does for the vessels. An
/// uncertain inside is Inside. hysteresisMm 0: the level of the distance alone.
MarginLevel ClassifyMargin(
  double signedMm, bool insideUncertain, const MarginSettings& settings, MarginLevel previous, double hysteresisMm);
} // namespace vp

#endif
