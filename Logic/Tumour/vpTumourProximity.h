#ifndef vpTumourProximity_h
#define vpTumourProximity_h

#include "vpMarginLevels.h"

#include <string>
#include <vector>

namespace vp
{
/// The tip (and the whole instrument) against one tumour.
struct TumourProximity
{
  std::string Id;
  /// Signed distance from the tip to the tumour's surface, exact: negative inside. Always known,
  /// however far the tumour.
  double SignedMm = 0.0;
  double ClosestPoint[3] = { 0, 0, 0 }; ///< on the tumour's surface, world
  /// The tumour's surface is not closed and the votes on inside disagreed: the level is Inside.
  bool InsideUncertain = false;
  /// The closest approach of the whole instrument surface (0 where it touches or crosses the
  /// tumour's); false when the instrument was not measured or is farther than its range.
  bool SurfaceKnown = false;
  double SurfaceMm = 0.0;
  MarginLevel Level = MarginLevel::Clear; ///< the tip's, with the tracking hysteresis
};

/// The tip against every tumour in one frame.
struct TumourMargin
{
  std::vector<TumourProximity> Tumours;
  /// The tumour whose level is the most concerning, the nearer among equals; -1 with no tumour.
  int Worst = -1;
  MarginLevel Level = MarginLevel::Clear; ///< the worst tumour's
};
} // namespace vp

#endif
