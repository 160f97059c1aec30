#include "vpTrackingSession.h"

#include "vpClock.h"
#include "vpRunFolder.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"

#include <vtkCallbackCommand.h>

namespace vp
{
TrackingSession::TrackingSession(vtkVesselProximityLogic* logic)
  : Logic(logic)
{
  this->OnChange->SetClientData(&this->PendingChanges);
  this->OnChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<DangerLevelChange>*>(client)->push_back(*static_cast<DangerLevelChange*>(call));
  });
  this->OnMarginChange->SetClientData(&this->PendingMarginChanges);
  this->OnMarginChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<MarginLevelChange>*>(client)->push_back(*static_cast<MarginLevelChange*>(call));
  });
  vtkScalpelTrackingLogic* tracking = logic->GetTrackingLogic();
  this->ObserverTags[0] = tracking->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, this->OnChange);
  this->ObserverTags[1] = tracking->AddObserver(vtkScalpelTrackingLogic::MarginLevelChangedEvent, this->OnMarginChange);
  this->Restart();
}

TrackingSession::~TrackingSession()
{
  vtkScalpelTrackingLogic* tracking = this->Logic->GetTrackingLogic();
  tracking->RemoveObserver(this->ObserverTags[0]);
  tracking->RemoveObserver(this->ObserverTags[1]);
}

void TrackingSession::AddOutput(FrameOutput* output)
{
  if (output)
  {
    this->Outputs.push_back(output);
  }
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
  this->PendingChanges.clear();
  this->PendingMarginChanges.clear();
  const TrackedFrame& frame = this->Logic->ProcessPose(pose);
  ++this->Frames;
  this->Deliver(frame);
  return frame;
}

void TrackingSession::ProcessLost(const TrackedPose& pose)
{
  this->FirstLostTimeS = this->Lost++ == 0 ? pose.TimeS : this->FirstLostTimeS;
  for (FrameOutput* output : this->Outputs)
  {
    output->OnLost(pose);
  }
}

void TrackingSession::Deliver(const TrackedFrame& frame)
{
  for (FrameOutput* output : this->Outputs)
  {
    for (const DangerLevelChange& change : this->PendingChanges)
    {
      output->OnLevelChange(change);
    }
    for (const MarginLevelChange& change : this->PendingMarginChanges)
    {
      output->OnMarginChange(change);
    }
    output->OnFrame(frame);
  }
}

bool TrackingSession::Run(PoseSource& poses, const std::function<void(const TrackedFrame&)>& onFrame,
  const std::function<void(const TrackedPose&)>& onLost)
{
  const auto end = [this] {
    for (FrameOutput* output : this->Outputs)
    {
      output->OnEnd();
    }
  };
  double lastReport = NowMs();
  for (TrackedPose pose; poses.Next(pose);)
  {
    if (RunFolder::SignalPending() && !poses.EndsOnSignal())
    {
      end();
      return false;
    }
    if (pose.Lost)
    {
      this->ProcessLost(pose);
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
  end();
  return true;
}
} // namespace vp
