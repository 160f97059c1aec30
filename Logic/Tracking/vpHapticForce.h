#ifndef vpHapticForce_h
#define vpHapticForce_h

#include "vpHaptics.h"

namespace vp
{
struct TrackedFrame;

/// The force frame after frame. The depth is the deepest of the instrument's penetrations (the
/// whole surface, where computed) and the tip's own depth inside a class; the direction is from
/// the tip to the wall when the tip is the part inside that class, else back along the
/// instrument's axis (withdrawing it takes it out).
class HapticForce
{
public:
  explicit HapticForce(const HapticSettings& settings = {});
  /// Forgets the previous frame (a new session, a lost tracking).
  void Reset();
  HapticSample Update(const TrackedFrame& frame);
  const HapticSettings& GetSettings() const { return this->Settings; }

private:
  HapticSettings Settings;
  bool HasPrevious = false;
  double PreviousDepthMm = 0.0;
  double PreviousTimeS = 0.0;
  double RateMmPerS = 0.0;
};
} // namespace vp

#endif
