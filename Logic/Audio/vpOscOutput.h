#ifndef vpOscOutput_h
#define vpOscOutput_h

#include "vpFrameOutput.h"
#include "vpSonification.h"

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace vp
{
/// The frames as OpenSoundControl messages over UDP (liblo), in the habits of SlicerIGT's
/// SoundControl: a patch (Resources/Audio/VesselProximity.pd) or any OSC peer plays them.
///
/// | address | types | when | values |
/// |---|---|---|---|
/// | /vesselproximity/distance | s f f | each frame | nearest class, the tip's signed distance (mm, negative inside), the whole instrument's (mm; left out when not measured) |
/// | /vesselproximity/level | f s s s | on change and once a second | the worst level (0 safe to 4 breach), its name, its cause (tip, instrument, none), its class |
/// | /vesselproximity/margin | f s f | each frame with tumours | the margin level (0 clear to 3 inside), the worst tumour, the tip's signed distance to it (mm) |
/// | /vesselproximity/state | s | on change and once a second | "tracking" or "lost" |
/// | /vesselproximity/sound/vessel, /vesselproximity/sound/margin | f f f f f f | on change and once a second | the voice to play (vp::Sonification): pitch Hz, second pitch Hz, beeps per second (0 continuous), duty, timbre (0 sine, 1 square, 2 triangle), gain |
///
/// Sending never delays a frame: the frame's messages go into a bounded queue a thread of the
/// output's own sends from; a frame's distance replaces one not sent yet (the newest wins), a
/// change is never replaced, and when the queue is full the oldest message is dropped and counted.
class OscOutput : public FrameOutput
{
public:
  /// host and port (1 to 65535) of the receiver. Throws InputError(source, ...) when the host
  /// cannot be resolved.
  OscOutput(const std::string& source, const std::string& host, int port, Sonification sound);
  ~OscOutput() override;
  OscOutput(const OscOutput&) = delete;
  OscOutput& operator=(const OscOutput&) = delete;

  /// The tip's distance /vesselproximity/distance sends for a frame: the nearest class's, negative
  /// inside (0 when no class is in range).
  static float SignedDistanceOf(const TrackedFrame& frame);

  void OnFrame(const TrackedFrame& frame) override;
  void OnLost(const TrackedPose& pose) override;
  void OnEnd() override;

  struct Counts
  {
    std::size_t Sent = 0;
    std::size_t Failed = 0;   ///< liblo could not send (no route, the peer's port closed)
    std::size_t Dropped = 0;  ///< the queue was full
    std::size_t Replaced = 0; ///< a frame's distance replaced by a newer one before it went out
  };
  Counts GetCounts() const;
  /// The sending time of the last message of each frame, for the latency it adds (vp::NowMs).
  double GetLastSentMs() const;
  void Report(nlohmann::ordered_json& outputs) const override;
  std::string Problems() const override;

  /// One OSC message as queued: its address, its arguments in order.
  struct Message
  {
    std::string Address;
    std::string Types; ///< 'f' and 's', one per argument
    std::vector<float> Floats;
    std::vector<std::string> Strings;
    bool Replaceable = false; ///< a frame's distance or margin: the newest wins
  };

private:
  void Queue(Message message);
  /// Whether the state is due again (once a second, for a patch started late).
  bool RepeatDue(double timeS) const;
  void QueueState(double timeS, bool lost, const SoundState& sound, bool force);
  void Send();

  std::string Source;
  std::string Where; ///< host:port, for what is said
  Sonification Sound;
  void* Address = nullptr; ///< lo_address
  mutable std::mutex Lock;
  std::condition_variable Wake;
  std::deque<Message> Pending;
  bool Stopping = false;
  bool Sending = false; ///< a message taken from the queue is on its way
  Counts Count;
  double LastSentMs = 0.0;
  std::thread Sender;
  // The frame thread's own: what was said last, and when the state was last repeated.
  std::optional<SoundState> LastSound;
  std::optional<bool> LastLost;
  DangerLevel LastLevel = DangerLevel::Safe;
  double LastRepeatS = -1e300;
};
} // namespace vp

#endif
