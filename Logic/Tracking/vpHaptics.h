#ifndef vpHaptics_h
#define vpHaptics_h

// The haptic force's settings and one frame's force: what a frame record and the tracking
// settings hold, apart from vp::HapticForce, which computes it from the frame.

namespace vp
{
/// A Kelvin–Voigt contact, as the method's authors fed a haptic device: F = k·depth + c·rate,
/// along the direction out of the vessel, where depth is how far the instrument is inside a vessel
/// and rate is how fast that grows. Off unless a stiffness or a damping is set.
struct HapticSettings
{
  /// k: newtons per millimetre of depth (0: none).
  double StiffnessNPerMm = 0.0;
  /// c: newton-seconds per millimetre (0: none).
  double DampingNsPerMm = 0.0;
  /// The rate is low-passed with this time constant (20 ms) and held within ±MaxRateMmPerS
  /// (200 mm/s, faster than a hand moves a CUSA), so that a depth that jumps between frames (a
  /// lost frame, a coarse one) gives no spike of force.
  double RateTimeConstantS = 0.02;
  double MaxRateMmPerS = 200.0;

  bool Enabled() const { return this->StiffnessNPerMm > 0.0 || this->DampingNsPerMm > 0.0; }
  bool operator==(const HapticSettings& o) const
  {
    return this->StiffnessNPerMm == o.StiffnessNPerMm && this->DampingNsPerMm == o.DampingNsPerMm &&
      this->RateTimeConstantS == o.RateTimeConstantS && this->MaxRateMmPerS == o.MaxRateMmPerS;
  }
  /// Throws ParameterError("HapticStiffnessNPerMm", "HapticDampingNsPerMm") for a negative or
  /// non-finite value.
  void Validate() const;
};

/// One frame's force on the instrument.
struct HapticSample
{
  double ForceN = 0.0;                 ///< 0 outside every vessel; never pulls inwards
  double Direction[3] = { 0, 0, 0 };   ///< unit, world (LPS), out of the vessel; 0 with no force
  double DepthMm = 0.0;                ///< the deepest penetration this frame
  double RateMmPerS = 0.0;             ///< its rate, filtered and bounded
};
} // namespace vp

#endif
