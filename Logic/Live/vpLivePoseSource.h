#ifndef vpLivePoseSource_h
#define vpLivePoseSource_h

#include "vpIgtlLink.h"
#include "vpPoseFile.h"

#include <functional>
#include <string>

namespace vp
{
/// The poses of a live OpenIGTLink stream (vp::IgtlLink), one at a time, as a tracking session's
/// source: Next() returns the newest pose that arrived, and once the stream has carried a pose,
/// a lost pose when none came for StaleMs (once per loss: the session counts it and its front end
/// says "tracking lost"; the last distance is never computed again as if current). The stream
/// ends when a held signal comes (vp::SignalHold, Ctrl-C: a live session's normal end) or after
/// DurationS.
class LivePoseSource : public PoseSource
{
public:
  /// link: started, and outliving the source. staleMs > 0. durationS: 0 runs until a signal.
  LivePoseSource(IgtlLink& link, std::string name, double staleMs, double durationS = 0.0);

  bool Next(TrackedPose& pose) override;

  /// One step of Next() that waits at most waitMs, for a front end with a loop of its own (the
  /// viewer's timer): a pose, a loss (a pose the tracker said it did not see, each; a stream gone
  /// stale, once), nothing yet, or the end.
  enum class Step
  {
    Pose,
    Lost,
    Nothing,
    Ended,
  };
  Step Poll(TrackedPose& pose, double waitMs);
  std::size_t PosesRead() const override { return this->Read; }
  const std::string& GetName() const override { return this->Name; }
  bool EndsOnSignal() const override { return true; }
  const SettledReading* GetSettledReading() const override { return &this->Link.GetSettings().Reading; }

  /// When the pose Next() returned last arrived (vp::NowMs()); for a lost pose, when the loss
  /// was declared.
  double GetLastArrivalMs() const { return this->LastArrivalMs; }
  double GetStaleMs() const { return this->StaleMs; }
  /// Called while Next() waits, every 10 ms or so: a front end shows the link's events.
  void SetIdleCallback(std::function<void()> idle) { this->Idle = std::move(idle); }
  /// The stream also ends when this says so while no pose waits (a recording served to the end).
  void SetEndCondition(std::function<bool()> ended) { this->Ended = std::move(ended); }

private:
  IgtlLink& Link;
  std::string Name;
  double StaleMs;
  double DurationS;
  double StartMs;
  double LastPoseMs = 0.0;
  double LastPoseTimeS = 0.0;
  double LastArrivalMs = 0.0;
  bool SeenAny = false;
  bool Lost = false;
  std::size_t Read = 0;
  std::function<void()> Idle;
  std::function<bool()> Ended;
};
} // namespace vp

#endif
