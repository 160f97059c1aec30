#ifndef vpIgtlPoseStreamer_h
#define vpIgtlPoseStreamer_h

#include "vpIgtlLink.h"
#include "vpPoseFile.h"

#include <atomic>
#include <cstddef>
#include <functional>
#include <string>

namespace vp
{
/// A tracker server made of a recording, as PlusServer's saved-data source replays one: each
/// pose of a source is sent as a TRANSFORM named DeviceName to every client connected, at its own
/// time (from the first pose's), sped up by Speed; a lost frame is sent as nothing, as a tracker
/// that does not see its tool sends nothing. What the clients send back is read and ignored.
class IgtlPoseStreamer
{
public:
  /// Serves on host:port (0: any free one, GetPort()); host, this machine's loopback by default.
  /// Throws as IgtlLink, and std::invalid_argument for a device name the wire cannot carry.
  IgtlPoseStreamer(int port, std::string deviceName, const std::string& host = "127.0.0.1");
  int GetPort() const { return this->Link.GetListenPort(); }
  IgtlLink& GetLink() { return this->Link; }

  /// Waits up to waitForClientS for a first client, then streams every pose of the source; ends
  /// early when stop becomes true or a held signal comes (vp::SignalHold). onPose (may be empty)
  /// hears each pose sent and its index. Returns the poses sent; 0 when no client came.
  std::size_t Stream(PoseSource& poses, double speed, double waitForClientS, const std::atomic<bool>& stop,
    const std::function<void(std::size_t sent, std::size_t expected)>& progress = {});

private:
  static IgtlLinkSettings Settings(int port, const std::string& deviceName, const std::string& host);
  std::string DeviceName;
  IgtlLink Link;
};
} // namespace vp

#endif
