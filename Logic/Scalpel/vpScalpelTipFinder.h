#ifndef vpScalpelTipFinder_h
#define vpScalpelTipFinder_h

#include <array>
#include <string>

class vtkPolyData;

namespace vp
{
/// Where the tip of an instrument model probably is, and why.
struct ScalpelTipEstimate
{
  std::array<double, 3> TipMm{};  ///< model coordinates
  std::array<double, 3> Axis{};   ///< unit, from the body towards the tip (the way the tool advances)
  std::array<double, 3> CentroidMm{}; ///< area-weighted centre of the surface
  double LengthMm = 0.0;          ///< extent along the principal axis
  double TipEndAreaMm2 = 0.0;     ///< surface area in the last 10% of the length at the tip end
  double OtherEndAreaMm2 = 0.0;   ///< the same at the opposite end
  double TipEndWidthMm = 0.0;     ///< RMS distance of that surface from the axis
  double OtherEndWidthMm = 0.0;
  /// True when the two ends are too alike to tell apart (areas within 20%): the choice is then a
  /// guess, and the caller should ask for the tip.
  bool Ambiguous = false;
  /// One line for the user: what was chosen and on what grounds.
  std::string Description;
};

/// Finds the tip of an elongated instrument: the narrower extreme of the model along its
/// principal axis (the axis of largest area-weighted spread of the surface). Instruments taper
/// to their working end and end in a cap or grip at the handle, so the end whose last 10% of
/// length holds less surface area is the tip (a spread measure fails on scalpels, whose flat
/// blade is as wide as the handle); the tip is the centre of the surface points within 0.25 mm
/// of that extreme. Throws vp::InputError(source, ...) for a model with no triangles or no length.
ScalpelTipEstimate FindScalpelTip(vtkPolyData* model, const std::string& source);
} // namespace vp

#endif
