#ifndef vpLiveResultsOutput_h
#define vpLiveResultsOutput_h

#include "vpFrameOutput.h"
#include "vpRunningQuantiles.h"

#include <optional>

namespace vp
{
class IgtlLink;
class LivePoseSource;

/// The live results as an output of the frame pipeline: each frame's messages (PackLiveFrame),
/// each change of level (PackLiveLevelChange) and each loss of tracking (PackLiveLost) sent to
/// every peer of the link as they happen, and, with the stream the poses came from, the latency
/// from a pose's arrival to its results sent (what summary.json's "latency_ms" reports).
class LiveResultsOutput : public FrameOutput
{
public:
  /// link: started, outliving this. poses: the stream the frames come from (null: the link's
  /// peers are told, no latency is measured and a loss says no time since the last pose).
  explicit LiveResultsOutput(IgtlLink& link, const LivePoseSource* poses = nullptr);

  void OnLevelChange(const DangerLevelChange& change) override;
  void OnMarginChange(const MarginLevelChange& change) override;
  void OnFrame(const TrackedFrame& frame) override;
  void OnLost(const TrackedPose& lost) override;

  /// Pose in -> results out, ms, per frame sent.
  const RunningQuantiles& GetLatencyMs() const { return this->LatencyMs; }

private:
  IgtlLink& Link;
  const LivePoseSource* Poses;
  RunningQuantiles LatencyMs;
  std::optional<bool> Tracking; ///< the state last said (STATUS); none said yet
};
} // namespace vp

#endif
