#include "vpIgtlPoseStreamer.h"

#include "vpClock.h"
#include "vpIgtlMessages.h"
#include "vpSignalHold.h"

#include <chrono>
#include <thread>

namespace vp
{
IgtlLinkSettings IgtlPoseStreamer::Settings(int port, const std::string& deviceName, const std::string& host)
{
  IgtlLinkSettings settings;
  settings.ListenPort = port;
  settings.ListenHost = host;
  // A client's own poses of this name would be read too: harmless, and never used.
  settings.ToolName = deviceName;
  return settings;
}

IgtlPoseStreamer::IgtlPoseStreamer(int port, std::string deviceName, const std::string& host)
  : DeviceName(std::move(deviceName))
  , Link(Settings(port, this->DeviceName, host))
{
}

std::size_t IgtlPoseStreamer::Stream(PoseSource& poses, double speed, double waitForClientS, const std::atomic<bool>& stop,
  const std::function<void(std::size_t, std::size_t)>& progress)
{
  const auto ended = [&] { return stop.load() || SignalHold::Pending(); };
  for (const double until = NowMs() + 1000.0 * waitForClientS; this->Link.GetNumberOfPeers() == 0;)
  {
    if (ended() || NowMs() > until)
    {
      return 0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::size_t sent = 0;
  bool first = true;
  double firstTimeS = 0.0, startMs = 0.0, lastProgressMs = NowMs();
  for (TrackedPose pose; !ended() && poses.Next(pose);)
  {
    if (first)
    {
      first = false;
      firstTimeS = pose.TimeS;
      startMs = NowMs();
    }
    const double atMs = startMs + 1000.0 * (pose.TimeS - firstTimeS) / speed;
    while (!ended() && NowMs() < atMs)
    {
      std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(std::min(10.0, atMs - NowMs()) * 1000.0)));
    }
    if (pose.Lost)
    {
      continue; // a tracker that does not see its tool sends nothing
    }
    // Stamped when sent, as PlusServer stamps its poses.
    this->Link.Send(PackIgtlTransform(this->DeviceName, pose.ModelToWorld, IgtlStampedAt(IgtlWallClockS())));
    ++sent;
    if (progress && NowMs() - lastProgressMs > 1000.0)
    {
      lastProgressMs = NowMs();
      progress(poses.PosesRead(), poses.PosesExpected());
    }
  }
  return sent;
}
} // namespace vp
