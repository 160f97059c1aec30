#ifndef vpIgtlLink_h
#define vpIgtlLink_h

#include "vpIgtlMessages.h"
#include "vpPoseFile.h"
#include "vpPoseReading.h"

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vp
{
/// Which peers the results go to.
enum class IgtlResultsTo
{
  Listeners, ///< the clients that connected to ListenPort (3D Slicer): never the tracker
  Tracker,   ///< the server connected to alone
  All,       ///< both
};

/// Where the link meets its peers and what it takes from them.
struct IgtlLinkSettings
{
  /// ConnectHost and ConnectPort: a server to connect to (a tracker's, PlusServer), as Slicer
  /// connects to PLUS; reconnected with a growing pause (0.1 s to 2 s) whenever it is lost. A
  /// server that sends nothing within StartRequestAfterMs of the connection is a tracking-data
  /// server waiting to be asked (the library's examples): it is asked then (STT_TDATA, STT_QTDATA,
  /// every 10 ms); one that streams at once (PlusServer) is never asked. ConnectPort 0: none.
  std::string ConnectHost = "127.0.0.1";
  int ConnectPort = 0;
  double StartRequestAfterMs = 500.0;
  /// Which peers the results go to: by default the clients of ListenPort, never the tracker (a
  /// PlusServer logs a warning for each message type it does not know).
  IgtlResultsTo ResultsTo = IgtlResultsTo::Listeners;
  /// ListenPort: a port to serve on, for clients (Slicer, a tracker client) to connect to;
  /// -1: none; 0: any free port (GetListenPort()). ListenHost: the address served on, this
  /// machine's loopback by default (only its own programs reach it); the operating room's network
  /// address, or 0.0.0.0 for every interface, when Slicer runs on another machine.
  int ListenPort = -1;
  std::string ListenHost = "127.0.0.1";
  /// One source steers the scalpel: the server connected to (ConnectPort) when there is one;
  /// else the first client from PoseFromHost (any address when empty) that sends the tool's
  /// pose, until it disconnects. The tool's poses from any other peer are refused and counted.
  std::string PoseFromHost;
  /// ToolName: the TRANSFORM device, or the QTDATA/TDATA element, that carries the tool's pose
  /// ("StylusToTracker").
  std::string ToolName;
  /// How the numbers are read (SettlePoseReading): frame, units, registration.
  SettledReading Reading;
  /// MaxBodyBytes: a body larger than this is a size field that lies: counted, and the connection
  /// closed (the stream cannot be followed past it). 1 MiB by default (a TDATA of a hundred tools
  /// is 7 kB).
  std::uint64_t MaxBodyBytes = 1u << 20;
  /// MessageTimeoutMs: a message must arrive whole within this from its first byte, however its
  /// sender paces it, or the connection is closed as stalled. 1000 by default.
  double MessageTimeoutMs = 1000.0;
  /// MaxClients: clients served at once. One more closes a client that takes no results, else the
  /// slowest sender (a message arriving longest), else of those with no message begun the one
  /// that reads least (most bytes queued for it), then the newest; never the tracker nor the peer
  /// that steers (with none else, the newcomer is turned away).
  /// 8 by default.
  int MaxClients = 8;
};

/// What a link saw, since it started.
struct IgtlLinkCounts
{
  std::size_t Messages = 0; ///< whole messages read
  std::size_t Poses = 0;    ///< the tool's poses taken from them
  std::size_t NotSeen = 0;  ///< of those, the tracker said it did not see the tool (a status not OK): lost poses
  std::size_t Version2Peers = 0; ///< peers that spoke header version 2, answered in it
  std::size_t Dropped = 0;  ///< poses replaced by a newer one before they were computed
  std::map<std::string, std::size_t> Rejected; ///< malformed or implausible, by reason
  std::map<std::string, std::size_t> Ignored;  ///< other types and tools, by which
  std::size_t Connections = 0;
  std::size_t ConnectionsLost = 0;
  std::size_t SendFailures = 0; ///< peers sent no more results because they took none
  std::size_t RejectedTotal() const;
};

/// OpenIGTLink (Debian's library, header versions 1 and 2) both ways, as PLUS and 3D Slicer speak
/// it; a peer that sends version 2 is answered in version 2 from then on, as PlusServer does: the tool's poses
/// in from a server it connects to and from the clients it serves, results out to all of them.
/// Each connection is read by a thread of its own; the newest pose waits in a mailbox of one
/// (WaitForPose), so a sender faster than the frames loses its older poses (counted), never
/// queues them. A malformed message is skipped and counted; one that cannot be followed (a size
/// that lies, one not whole within its time, bytes that are no header) closes its connection,
/// which a server connected to is reconnected, after a pause that grows while connections do not
/// hold. Nothing here blocks a caller for longer than it asks.
class IgtlLink
{
public:
  /// Starts listening and connecting. Throws ParameterError("ListenPort") when the port cannot
  /// be served on, ParameterError("ToolName") when none is given.
  explicit IgtlLink(const IgtlLinkSettings& settings);
  ~IgtlLink();
  IgtlLink(const IgtlLink&) = delete;
  IgtlLink& operator=(const IgtlLink&) = delete;

  /// Waits up to timeoutMs for a pose newer than the last taken: true with it (its TimeS: seconds
  /// since the link started, at its arrival) and its arrival (vp::NowMs()).
  bool WaitForPose(double timeoutMs, TrackedPose& pose, double& arrivalMs);
  /// Writes packed messages to every peer connected now; a peer that cannot take them within
  /// 20 ms (a tracker server that never reads) is sent nothing more (counted, said), never waited
  /// for again; its poses are still read.
  void Send(const std::string& packed);

  IgtlLinkCounts GetCounts() const;
  /// What happened since the last call, a line each ("connected to 127.0.0.1:18944", "skipped a
  /// message from ...: bad CRC (counted from now on)"), for the front end to show.
  std::vector<std::string> TakeEvents();
  const IgtlLinkSettings& GetSettings() const { return this->Settings; }
  /// The port served on (the one chosen when ListenPort was 0); -1 when not listening.
  int GetListenPort() const { return this->ListenPort; }
  std::size_t GetNumberOfPeers() const;

private:
  struct Peer;
  void ConnectLoop();
  void AcceptLoop();
  void ReadLoop(Peer& peer);
  /// Reads the peer's messages until it closes, stalls, sends what cannot be followed or the link
  /// stops.
  void ServePeer(Peer& peer);
  /// Asks a server that has sent nothing within StartRequestAfterMs for tracking data.
  void AskWhenSilent(Peer& peer);
  /// Tells a server that spoke version 1 that we speak version 2, as 3D Slicer does.
  void SayVersion2(Peer& peer);
  /// A message to one peer outside the results (a request, the version): a send that fails
  /// leaves it deaf, counted and said, as for the results.
  void SendAside(Peer& peer, const std::string& message);
  /// One whole message of the peer: the tool's pose taken when the peer steers, else counted.
  void Take(Peer& peer, const unsigned char* header, const std::vector<unsigned char>& body);
  /// Whether the peer's poses steer the scalpel (see IgtlLinkSettings::PoseFromHost); under Mutex.
  bool MaySteer(const Peer& peer);
  /// The client to close when one more arrives and all slots are taken, or null; under Mutex.
  std::shared_ptr<Peer> ChooseEvictee(double nowMs) const;
  /// Joins and forgets the readers of peers that have ended.
  void Prune();
  void Note(const std::string& event);
  void Count(std::map<std::string, std::size_t> IgtlLinkCounts::*which, const std::string& reason, const std::string& from);

  IgtlLinkSettings Settings;
  double StartMs = 0.0;
  int ListenPort = -1;
  std::atomic<bool> Stop{ false };
  mutable std::mutex Mutex; // guards everything below
  std::condition_variable PoseArrived;
  std::vector<std::shared_ptr<Peer>> Peers; // connected now or being read to the end
  IgtlLinkCounts Counts;
  std::vector<std::string> Events;
  TrackedPose Newest;
  double NewestArrivalMs = 0.0;
  bool Fresh = false;
  int ListenDescriptor = -1;
  std::string PoseSource; // the peer whose poses steer, once one has
  std::thread Connector, Acceptor;
};
} // namespace vp

#endif
