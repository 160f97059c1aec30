#include "vpLiveResultsOutput.h"

#include "vpClock.h"
#include "vpIgtlLink.h"
#include "vpLivePoseSource.h"
#include "vpLiveResults.h"

namespace vp
{
LiveResultsOutput::LiveResultsOutput(IgtlLink& link, const LivePoseSource* poses)
  : Link(link)
  , Poses(poses)
{
}

void LiveResultsOutput::OnLevelChange(const DangerLevelChange& change)
{
  this->Link.Send(PackLiveLevelChange(change));
}

void LiveResultsOutput::OnMarginChange(const MarginLevelChange& change)
{
  this->Link.Send(PackLiveMarginChange(change));
}

void LiveResultsOutput::OnFrame(const TrackedFrame& frame)
{
  // The state said when it changes: tracking from the first frame and after each loss.
  this->Link.Send(this->Tracking.value_or(false) ? PackLiveFrame(frame) : PackLiveStatus(true) + PackLiveFrame(frame));
  this->Tracking = true;
  if (this->Poses)
  {
    this->LatencyMs.Add(NowMs() - this->Poses->GetLastArrivalMs());
  }
}

void LiveResultsOutput::OnLost(const TrackedPose& lost)
{
  // The loss is declared StaleMs after the last pose came: that much before it was declared.
  const double sinceMs = this->Poses ? NowMs() - this->Poses->GetLastArrivalMs() + this->Poses->GetStaleMs() : 0.0;
  this->Link.Send(this->Tracking.value_or(true) ? PackLiveStatus(false) + PackLiveLost(lost.TimeS, sinceMs) : PackLiveLost(lost.TimeS, sinceMs));
  this->Tracking = false;
}
} // namespace vp
