#ifndef vpFrameOutput_h
#define vpFrameOutput_h

#include "vpPoseFile.h"
#include "vpTrackedFrame.h"

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace vp
{
/// One output of the frame pipeline (vp::TrackingSession::AddOutput): the run's report, the live
/// results to the peers, the key frames, a sound. The session tells each output, in the order
/// they were added, of every change of level a frame makes, then of the frame itself, of every
/// pose the tracker lost, and of the end of the run; always outside the frame's own time
/// (TrackedFrame::FrameMs), so that an output's work never counts as the engines'. A front end
/// chooses its outputs and wires nothing else: no observer, no loop of its own.
///
/// Every notification does nothing by default: an output overrides what it needs.
class FrameOutput
{
public:
  virtual ~FrameOutput() = default;

  /// The overall danger level changed in the frame about to be given to OnFrame.
  virtual void OnLevelChange(const DangerLevelChange&) {}
  /// The resection margin's level changed in the frame about to be given to OnFrame.
  virtual void OnMarginChange(const MarginLevelChange&) {}
  /// A computed frame, valid for the call.
  virtual void OnFrame(const TrackedFrame&) {}
  /// A pose the tracker did not see (TrackedPose::Lost): no frame, no distance.
  virtual void OnLost(const TrackedPose&) {}
  /// The source ended (or a held signal ended the run): nothing more comes.
  virtual void OnEnd() {}

  /// What the output has to say in the run's summary.json: its entry added to the "outputs"
  /// object under its name (nothing by default); and a line for the front end to say when
  /// something went wrong (messages not sent, a device lost; empty when all went well). Asked
  /// after OnEnd.
  virtual void Report(nlohmann::ordered_json& outputs) const { (void)outputs; }
  virtual std::string Problems() const { return std::string(); }

protected:
  FrameOutput() = default;
  FrameOutput(const FrameOutput&) = default;
  FrameOutput& operator=(const FrameOutput&) = default;
};
} // namespace vp

#endif
