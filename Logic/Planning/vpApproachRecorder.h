#ifndef vpApproachRecorder_h
#define vpApproachRecorder_h

#include "vpApproachPlan.h"
#include "vpFrameOutput.h"

#include <vector>

namespace vp
{
/// What a planned approach keeps of its frames (an output of its vp::TrackingSession): per vessel
/// class the whole instrument's closest approach, the first pose that reaches it and the points,
/// the deepest penetration; per pose the danger level and the computing time; the tip's signed
/// distance to the target at the last pose.
class ApproachRecorder : public FrameOutput
{
public:
  void OnFrame(const TrackedFrame& frame) override;

  /// The classes of the frames, the steps' levels and the target's distance, into approach;
  /// rangeMm is the clearance when no class came within range.
  void Fill(PlannedApproach& approach, double rangeMm) const;
  const std::vector<double>& GetStepMs() const { return this->StepMs; }

private:
  std::vector<ClassApproach> Classes;
  std::vector<DangerLevel> Levels;
  std::vector<double> StepMs;
  std::optional<double> TipTargetSignedMm;
};
} // namespace vp

#endif
