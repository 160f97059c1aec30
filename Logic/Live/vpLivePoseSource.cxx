#include "vpLivePoseSource.h"

#include "vpClock.h"
#include "vpInputError.h"
#include "vpSignalHold.h"

namespace vp
{
namespace
{
/// How often Next() looks at the signals, the duration and the staleness while it waits.
constexpr double WaitSliceMs = 10.0;
} // namespace

LivePoseSource::LivePoseSource(IgtlLink& link, std::string name, double staleMs, double durationS)
  : Link(link)
  , Name(std::move(name))
  , StaleMs(staleMs)
  , DurationS(durationS)
  , StartMs(NowMs())
{
  if (!(staleMs > 0.0))
  {
    throw ParameterError("StaleMs", "expected a time in ms above 0");
  }
}

bool LivePoseSource::Next(TrackedPose& pose)
{
  while (true)
  {
    const Step step = this->Poll(pose, WaitSliceMs);
    if (step == Step::Ended)
    {
      return false;
    }
    if (step != Step::Nothing)
    {
      return true;
    }
  }
}

LivePoseSource::Step LivePoseSource::Poll(TrackedPose& pose, double waitMs)
{
  if (SignalHold::Pending() || (this->DurationS > 0.0 && NowMs() - this->StartMs >= 1000.0 * this->DurationS))
  {
    return Step::Ended;
  }
  double arrivalMs = 0.0;
  if (this->Link.WaitForPose(waitMs, pose, arrivalMs))
  {
    this->SeenAny = true;
    // A pose the tracker says it did not see (a status not OK) is a loss as it comes.
    this->Lost = pose.Lost;
    this->LastPoseMs = arrivalMs;
    this->LastPoseTimeS = pose.TimeS;
    this->LastArrivalMs = arrivalMs;
    ++this->Read;
    return pose.Lost ? Step::Lost : Step::Pose;
  }
  if (this->Idle)
  {
    this->Idle();
  }
  if (this->Ended && this->Ended())
  {
    return Step::Ended;
  }
  const double sinceMs = NowMs() - this->LastPoseMs;
  if (this->SeenAny && !this->Lost && sinceMs >= this->StaleMs)
  {
    this->Lost = true;
    pose = TrackedPose();
    pose.Lost = true;
    pose.TimeS = this->LastPoseTimeS + sinceMs / 1000.0;
    this->LastArrivalMs = NowMs();
    ++this->Read;
    return Step::Lost;
  }
  return Step::Nothing;
}
} // namespace vp
