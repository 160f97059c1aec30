#include "vpTrackingSession.h"

#include "vpClock.h"
#include "vpRunFolder.h"
#include "vtkVesselProximityLogic.h"

namespace vp
{
TrackingSession::TrackingSession(vtkVesselProximityLogic* logic)
  : Logic(logic)
{
  this->Restart();
}

void TrackingSession::SetProgress(std::function<void(std::size_t, std::size_t)> progress)
{
  this->Progress = std::move(progress);
}

void TrackingSession::Restart()
{
  this->Logic->ResetTracking();
  this->Frames = 0;
  this->Lost = 0;
}

const TrackedFrame& TrackingSession::Process(const TrackedPose& pose)
{
  const TrackedFrame& frame = this->Logic->ProcessPose(pose);
  ++this->Frames;
  return frame;
}

bool TrackingSession::Run(PoseSource& poses, const std::function<void(const TrackedFrame&)>& onFrame,
  const std::function<void(const TrackedPose&)>& onLost)
{
  double lastReport = NowMs();
  for (TrackedPose pose; poses.Next(pose);)
  {
    if (RunFolder::SignalPending() && !poses.EndsOnSignal())
    {
      return false;
    }
    if (pose.Lost)
    {
      this->FirstLostTimeS = this->Lost++ == 0 ? pose.TimeS : this->FirstLostTimeS;
      if (onLost)
      {
        onLost(pose);
      }
      continue;
    }
    const TrackedFrame& frame = this->Process(pose);
    if (onFrame)
    {
      onFrame(frame);
    }
    if (this->Progress && NowMs() - lastReport > 1000.0)
    {
      lastReport = NowMs();
      this->Progress(poses.PosesRead(), poses.PosesExpected());
    }
  }
  return true;
}
} // namespace vp
