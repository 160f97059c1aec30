#include "vpIgtlLink.h"

#include "vpClock.h"
#include "vpIgtlMessages.h"
#include "vpInputError.h"

#include <igtlSocket.h>

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>

namespace vp
{
namespace
{
/// How long a read waits before it looks at the stop flag and the message's deadline.
constexpr int PollMs = 20;
/// How long a peer may take a frame's results before it is dropped.
constexpr int SendTimeoutMs = 20;

enum class ReadResult
{
  Ok,
  Closed,
  Stopped,
  Stalled,
};

/// An OpenIGTLink socket around a connection made here: the library's ClientSocket connects with
/// no time limit and prints its failures on stderr, which a link that retries every 2 s cannot.
class AdoptedSocket : public igtl::Socket
{
public:
  typedef AdoptedSocket Self;
  typedef igtl::Socket Superclass;
  typedef igtl::SmartPointer<Self> Pointer;
  typedef igtl::SmartPointer<const Self> ConstPointer;
  igtlTypeMacro(AdoptedSocket, igtl::Socket);
  igtlNewMacro(AdoptedSocket);
  void Adopt(int descriptor) { this->m_SocketDescriptor = descriptor; }

protected:
  AdoptedSocket() = default;
  ~AdoptedSocket() override = default;
};

/// The first TCP socket for host:port (getaddrinfo's order) that ready accepts (and keeps open):
/// its descriptor, or -1. flags: getaddrinfo's hints (AI_PASSIVE for a listener).
int FirstSocket(const std::string& host, int port, int flags, const std::function<bool(int, const addrinfo&)>& ready)
{
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = flags;
  addrinfo* found = nullptr;
  if (port < 0 || port > 65535 || getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0)
  {
    return -1;
  }
  int chosen = -1;
  for (addrinfo* a = found; a && chosen < 0; a = a->ai_next)
  {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd >= 0 && ready(fd, *a))
    {
      chosen = fd;
    }
    else if (fd >= 0)
    {
      ::close(fd);
    }
  }
  freeaddrinfo(found);
  return chosen;
}

/// A TCP connection to host:port within timeoutMs: its descriptor, or -1.
int ConnectWithin(const std::string& host, int port, int timeoutMs)
{
  return FirstSocket(host, port, 0, [timeoutMs](int fd, const addrinfo& a) {
    const int flags = fcntl(fd, F_GETFL, 0);
    fcntl(fd, F_SETFL, flags | O_NONBLOCK);
    int result = ::connect(fd, a.ai_addr, a.ai_addrlen);
    if (result < 0 && errno == EINPROGRESS)
    {
      pollfd p{ fd, POLLOUT, 0 };
      int error = 0;
      socklen_t length = sizeof error;
      result = poll(&p, 1, timeoutMs) == 1 && getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) == 0 && error == 0 ? 0 : -1;
    }
    if (result != 0)
    {
      return false;
    }
    fcntl(fd, F_SETFL, flags);
    const int on = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on); // a pose is small and late is useless
    return true;
  });
}

/// The characters an OpenIGTLink type name is made of; anything else is a stream out of step.
bool IsTypeName(const std::string& type)
{
  return !type.empty() &&
    std::all_of(type.begin(), type.end(), [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
}

/// A listening TCP socket on host:port (port 0: any free one): its descriptor, or -1. Our own
/// rather than the library's ServerSocket, which binds every interface.
int ListenOn(const std::string& host, int port)
{
  return FirstSocket(host, port, AI_PASSIVE | AI_NUMERICSERV, [](int fd, const addrinfo& a) {
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    return ::bind(fd, a.ai_addr, a.ai_addrlen) == 0 && ::listen(fd, 16) == 0;
  });
}

/// The port a listening socket was given.
int PortOf(int descriptor)
{
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (getsockname(descriptor, reinterpret_cast<sockaddr*>(&address), &length) != 0)
  {
    return -1;
  }
  return ntohs(address.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&address)->sin6_port
                                             : reinterpret_cast<sockaddr_in*>(&address)->sin_port);
}

/// The numeric address of a peer ("127.0.0.1").
std::string HostOf(const sockaddr_storage& address, socklen_t length)
{
  char host[NI_MAXHOST] = "";
  return getnameinfo(reinterpret_cast<const sockaddr*>(&address), length, host, sizeof host, nullptr, 0, NI_NUMERICHOST) == 0
    ? std::string(host)
    : std::string("?");
}

/// Reads a peer's messages through a buffer of what has arrived (one call takes all that waits: a
/// sender at 1 kHz is read in a few calls a frame, not two per message). A message's time runs
/// from its first byte: header and body must both arrive within the timeout however the sender
/// paces its bytes (a byte every few milliseconds cannot hold the connection), and when it began
/// is published for the listener choosing whom to close.
class MessageReader
{
public:
  MessageReader(igtl::Socket* socket, double timeoutMs, const std::atomic<bool>& stop, std::atomic<double>& begunMs)
    : Socket(socket)
    , TimeoutMs(timeoutMs)
    , Stop(stop)
    , BegunMs(begunMs)
  {
  }

  ReadResult Read(unsigned char* into, std::size_t count)
  {
    while (this->Arrived.size() - this->Used < count)
    {
      if (this->Stop)
      {
        return ReadResult::Stopped;
      }
      const int r = this->Socket->Receive(this->Chunk.data(), static_cast<int>(this->Chunk.size()), 0);
      if (r == 0)
      {
        return ReadResult::Closed;
      }
      if (r > 0)
      {
        if (this->BegunMs < 0.0)
        {
          this->BegunMs = NowMs();
        }
        this->Arrived.erase(this->Arrived.begin(), this->Arrived.begin() + static_cast<std::ptrdiff_t>(this->Used));
        this->Used = 0;
        this->Arrived.insert(this->Arrived.end(), this->Chunk.begin(), this->Chunk.begin() + r);
      }
      if (this->BegunMs >= 0.0 && NowMs() - this->BegunMs > this->TimeoutMs)
      {
        return ReadResult::Stalled;
      }
    }
    std::copy_n(this->Arrived.begin() + static_cast<std::ptrdiff_t>(this->Used), count, into);
    this->Used += count;
    return ReadResult::Ok;
  }

  /// A whole message was read: the next one's time starts with its first byte (now, if some of
  /// it came with this one's).
  void MessageDone() { this->BegunMs = this->Arrived.size() > this->Used ? NowMs() : -1.0; }

private:
  igtl::Socket* Socket;
  double TimeoutMs;
  const std::atomic<bool>& Stop;
  std::atomic<double>& BegunMs;
  std::vector<unsigned char> Arrived;
  std::size_t Used = 0;
  std::vector<unsigned char> Chunk = std::vector<unsigned char>(1u << 16);
};

/// Each message of a run of version-1 messages (as the packers make them) rewritten as version 2
/// for a peer that speaks it, with the time it is sent in its metadata (ReplyTime, UTC seconds):
/// the header carries the pose's own time stamp where the source gave one.
std::string ToIgtlVersion2Stream(const std::string& messages)
{
  char now[32];
  std::snprintf(now, sizeof now, "%.6f", IgtlWallClockS());
  const std::vector<IgtlMetadata> metadata = { { "ReplyTime", now, 3 } };
  std::string out;
  for (std::size_t at = 0; at + IgtlHeaderBytes <= messages.size();)
  {
    const IgtlHeader h = ParseIgtlHeader(reinterpret_cast<const unsigned char*>(messages.data() + at));
    const std::size_t size = IgtlHeaderBytes + static_cast<std::size_t>(h.BodyBytes);
    out += ToIgtlVersion2(messages.substr(at, size), metadata, 0);
    at += size;
  }
  return out;
}
} // namespace

struct IgtlLink::Peer
{
  igtl::Socket::Pointer Socket;
  int Descriptor = -1;
  std::string Name; ///< "127.0.0.1:18944" (a server) or "client 2"
  std::string Host; ///< the client's address ("127.0.0.1"); the server's host name
  bool IsServer = false; ///< the server connected to (the --igtl tracker), not a client
  double ConnectedMs = 0.0;
  std::atomic<double> MessageBegunMs{ -1.0 }; ///< when the message being read began; -1: none
  std::atomic<bool> Closing{ false };          ///< shut down by the listener to serve another
  std::thread Reader;
  std::atomic<bool> Done{ false };
  /// A send failed (the peer took no more within the timeout, or part of a message went): the
  /// rest of that message can never be placed, so nothing more is sent to it; its poses are
  /// still read (a tracker server that never reads is still a tracker).
  std::atomic<bool> Deaf{ false };
  std::mutex SocketMutex;             ///< a send and the close never overlap
  /// The header version it speaks: 1 until it sends a version-2 message, then answered in 2.
  std::atomic<unsigned> Version{ 1 };
  std::atomic<std::size_t> Messages{ 0 }; ///< whole messages read from it
};

void IgtlLink::SayVersion2(Peer& peer)
{
  // What 3D Slicer sends on connecting "to tell the server we can support v2 messages": a
  // version-2 STATUS (code 0, metadata dummy=dummy). PlusServer then speaks version 2 to us, and
  // marks a tool it does not see (TransformStatus) instead of sending its identity as a pose. Sent
  // once the server has spoken: a version-1 server waiting to be asked (the library's examples)
  // would lose its stream on a version-2 message.
  IgtlPacking packing;
  packing.Version = 2;
  packing.Metadata = { { "dummy", "dummy", 3 } };
  IgtlStatus hello;
  hello.Code = 0;
  this->SendAside(peer, PackIgtlStatus("", hello, packing));
}

void IgtlLink::SendAside(Peer& peer, const std::string& message)
{
  std::unique_lock<std::mutex> lock(peer.SocketMutex);
  if (peer.Done || peer.Deaf || peer.Socket->Send(message.data(), static_cast<int>(message.size())) == 1)
  {
    return;
  }
  // Part of a message may have gone: nothing more can be placed after it.
  peer.Deaf = true;
  lock.unlock();
  {
    std::lock_guard<std::mutex> counts(this->Mutex);
    ++this->Counts.SendFailures;
  }
  this->Note(peer.Name + " took no more messages: none are sent to it from now on (its poses are still read)");
}

void IgtlLink::AskWhenSilent(Peer& peer)
{
  const double until = peer.ConnectedMs + this->Settings.StartRequestAfterMs;
  while (!this->Stop && !peer.Done && peer.Messages == 0 && NowMs() < until)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(PollMs));
  }
  if (this->Stop || peer.Done || peer.Messages > 0)
  {
    return;
  }
  this->SendAside(peer, PackIgtlStartTracking(10));
}

std::size_t IgtlLinkCounts::RejectedTotal() const
{
  std::size_t total = 0;
  for (const auto& [reason, count] : this->Rejected)
  {
    total += count;
  }
  return total;
}

IgtlLink::IgtlLink(const IgtlLinkSettings& settings)
  : Settings(settings)
  , StartMs(NowMs())
{
  if (settings.ToolName.empty())
  {
    throw ParameterError("ToolName", "name the tool whose pose the stream carries (a TRANSFORM device or a tracking element)");
  }
  if (settings.ListenPort >= 0)
  {
    this->ListenDescriptor = ListenOn(settings.ListenHost, settings.ListenPort);
    if (this->ListenDescriptor < 0)
    {
      throw ParameterError("ListenPort", "cannot serve on " + settings.ListenHost + ":" + std::to_string(settings.ListenPort) +
        " (in use, not a port, or not an address of this machine)");
    }
    this->ListenPort = PortOf(this->ListenDescriptor);
    this->Acceptor = std::thread([this] { this->AcceptLoop(); });
  }
  if (settings.ConnectPort > 0)
  {
    this->Connector = std::thread([this] { this->ConnectLoop(); });
  }
}

IgtlLink::~IgtlLink()
{
  this->Stop = true;
  this->PoseArrived.notify_all();
  if (this->Connector.joinable())
  {
    this->Connector.join();
  }
  if (this->Acceptor.joinable())
  {
    this->Acceptor.join();
  }
  std::vector<std::shared_ptr<Peer>> peers;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    peers.swap(this->Peers);
  }
  for (const auto& peer : peers)
  {
    if (peer->Reader.joinable())
    {
      peer->Reader.join();
    }
  }
  if (this->ListenDescriptor >= 0)
  {
    ::close(this->ListenDescriptor);
  }
}

void IgtlLink::Note(const std::string& event)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (this->Events.size() < 1000) // a front end that never looks does not make memory grow
  {
    this->Events.push_back(event);
  }
}

void IgtlLink::Count(std::map<std::string, std::size_t> IgtlLinkCounts::*which, const std::string& reason, const std::string& from)
{
  bool first = false;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    auto& counts = this->Counts.*which;
    // A sender of arbitrary type names cannot make the map grow without end.
    const std::string key = counts.size() < 64 || counts.count(reason) ? reason : std::string("other");
    first = counts[key]++ == 0;
  }
  if (first && which == &IgtlLinkCounts::Rejected)
  {
    this->Note("skipped a message from " + from + ": " + reason + " (such messages are counted from now on)");
  }
}

void IgtlLink::ConnectLoop()
{
  const std::string name = this->Settings.ConnectHost + ":" + std::to_string(this->Settings.ConnectPort);
  // After any loss or refusal the pause grows from 0.1 s to 2 s; only a connection that held (a
  // whole message, or a second's life) starts it over. Each state is said once, not each attempt.
  double pauseMs = 100.0;
  enum class State { Starting, Refused, Flapping, Held } said = State::Starting;
  const auto pause = [&] {
    for (const double until = NowMs() + pauseMs; !this->Stop && NowMs() < until;)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(PollMs));
    }
    pauseMs = std::min(2000.0, 2.0 * pauseMs);
  };
  while (!this->Stop)
  {
    const int descriptor = ConnectWithin(this->Settings.ConnectHost, this->Settings.ConnectPort, 1000);
    if (descriptor < 0)
    {
      if (said != State::Refused)
      {
        this->Note("cannot connect to " + name + "; trying again, every 2 s at most");
        said = State::Refused;
      }
      pause();
      continue;
    }
    auto socket = AdoptedSocket::New();
    socket->Adopt(descriptor);
    auto peer = std::make_shared<Peer>();
    peer->Socket = socket.GetPointer();
    peer->Descriptor = descriptor;
    peer->Name = name;
    peer->Host = this->Settings.ConnectHost;
    peer->IsServer = true;
    peer->ConnectedMs = NowMs();
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Peers.push_back(peer);
      ++this->Counts.Connections;
    }
    if (said != State::Flapping)
    {
      this->Note("connected to " + name);
    }
    const std::size_t messagesBefore = this->GetCounts().Messages;
    std::thread asker([this, peer] { this->AskWhenSilent(*peer); });
    this->ServePeer(*peer);
    asker.join();
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Peers.erase(std::remove(this->Peers.begin(), this->Peers.end(), peer), this->Peers.end());
      if (!this->Stop)
      {
        ++this->Counts.ConnectionsLost;
      }
    }
    if (this->Stop)
    {
      break;
    }
    const bool held = this->GetCounts().Messages > messagesBefore || NowMs() - peer->ConnectedMs >= 1000.0;
    if (held)
    {
      pauseMs = 100.0;
      this->Note("connection to " + name + " lost; reconnecting");
      said = State::Held;
    }
    else if (said != State::Flapping)
    {
      this->Note(name + " closed the connection at once; trying again with a growing pause, up to 2 s (said again when one holds)");
      said = State::Flapping;
    }
    pause();
  }
}

std::shared_ptr<IgtlLink::Peer> IgtlLink::ChooseEvictee(double nowMs) const
{
  // First a client that takes no results (Deaf), then the slowest: the one whose message has been
  // arriving longest (a sender that drips bytes; a well-behaved one is mid-message for
  // microseconds). Else, of those with no message begun, the one that reads least, then the
  // newest. Never the tracker nor the peer whose poses steer the scalpel.
  std::shared_ptr<Peer> deaf, slowest, newestIdle;
  int idleUnread = -1; // bytes queued for newestIdle
  for (const auto& p : this->Peers)
  {
    if (p->Done || p->Closing || p->IsServer || p->Name == this->PoseSource)
    {
      continue;
    }
    const double begun = p->MessageBegunMs;
    if (p->Deaf && !deaf)
    {
      deaf = p;
    }
    if (begun >= 0.0 && begun < nowMs && (!slowest || begun < slowest->MessageBegunMs))
    {
      slowest = p;
    }
    if (begun >= 0.0)
    {
      continue;
    }
    // Among idle ones, the one that reads least of what is sent (the most bytes waiting in its
    // socket: a peer that holds a slot without reading), then the newest.
    int queued = 0;
    queued = ::ioctl(p->Descriptor, TIOCOUTQ, &queued) == 0 ? queued : 0;
    if (!newestIdle || queued > idleUnread || (queued == idleUnread && p->ConnectedMs > newestIdle->ConnectedMs))
    {
      newestIdle = p;
      idleUnread = queued;
    }
  }
  return deaf ? deaf : slowest ? slowest : newestIdle;
}

void IgtlLink::AcceptLoop()
{
  int clients = 0;
  while (!this->Stop)
  {
    this->Prune();
    pollfd waiting{ this->ListenDescriptor, POLLIN, 0 };
    if (poll(&waiting, 1, 100) != 1)
    {
      continue;
    }
    sockaddr_storage address{};
    socklen_t length = sizeof address;
    const int descriptor = accept4(this->ListenDescriptor, reinterpret_cast<sockaddr*>(&address), &length, SOCK_CLOEXEC);
    if (descriptor < 0)
    {
      continue;
    }
    const int on = 1;
    setsockopt(descriptor, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
    std::lock_guard<std::mutex> lock(this->Mutex);
    const auto connected = std::count_if(this->Peers.begin(), this->Peers.end(), [](const auto& p) { return !p->Done && !p->Closing; });
    if (connected >= this->Settings.MaxClients)
    {
      const std::shared_ptr<Peer> evicted = this->ChooseEvictee(NowMs());
      if (!evicted)
      {
        ::close(descriptor);
        this->Events.push_back("turned a client away: " + std::to_string(this->Settings.MaxClients) + " are served already");
        continue;
      }
      {
        // Under its socket's lock, not yet closed by its reader: the descriptor is still its own.
        std::lock_guard<std::mutex> socketLock(evicted->SocketMutex);
        evicted->Closing = true;
        if (!evicted->Done)
        {
          ::shutdown(evicted->Descriptor, SHUT_RDWR); // its reader sees the end and closes it
        }
      }
      this->Events.push_back("closed " + evicted->Name +
        (evicted->Deaf ? " (it took no results)" : evicted->MessageBegunMs >= 0.0 ? " (the slowest sender)" : " (the newest idle)") +
        " to serve a new client: " + std::to_string(this->Settings.MaxClients) + " at most");
    }
    auto socket = AdoptedSocket::New();
    socket->Adopt(descriptor);
    auto peer = std::make_shared<Peer>();
    peer->Socket = socket.GetPointer();
    peer->Descriptor = descriptor;
    peer->Name = "client " + std::to_string(++clients);
    peer->Host = HostOf(address, length);
    peer->ConnectedMs = NowMs();
    ++this->Counts.Connections;
    this->Events.push_back(peer->Name + " connected on port " + std::to_string(this->ListenPort) + " from " + peer->Host);
    this->Peers.push_back(peer);
    peer->Reader = std::thread([this, p = peer.get()] { this->ReadLoop(*p); });
  }
}

void IgtlLink::Prune()
{
  std::vector<std::shared_ptr<Peer>> ended;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (auto it = this->Peers.begin(); it != this->Peers.end();)
    {
      if ((*it)->Done && (*it)->Reader.joinable())
      {
        ended.push_back(*it);
        it = this->Peers.erase(it);
      }
      else
      {
        ++it;
      }
    }
  }
  for (const auto& peer : ended)
  {
    peer->Reader.join();
  }
}

void IgtlLink::ReadLoop(Peer& peer)
{
  this->ServePeer(peer);
  if (!this->Stop)
  {
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      ++this->Counts.ConnectionsLost;
    }
    this->Note(peer.Name + " disconnected");
  }
}

void IgtlLink::ServePeer(Peer& peer)
{
  igtl::Socket* socket = peer.Socket;
  socket->SetReceiveTimeout(PollMs);
  socket->SetSendTimeout(SendTimeoutMs);
  MessageReader reader(socket, this->Settings.MessageTimeoutMs, this->Stop, peer.MessageBegunMs);
  unsigned char header[IgtlHeaderBytes];
  std::vector<unsigned char> body;
  ReadResult r = ReadResult::Ok;
  while ((r = reader.Read(header, IgtlHeaderBytes)) == ReadResult::Ok)
  {
    const IgtlHeader h = ParseIgtlHeader(header);
    if (!IsTypeName(h.Type) || h.Version == 0 || h.Version > 3)
    {
      this->Count(&IgtlLinkCounts::Rejected, "bytes that are no OpenIGTLink header", peer.Name);
      break; // where the next message begins cannot be known
    }
    if (h.BodyBytes > this->Settings.MaxBodyBytes)
    {
      this->Count(&IgtlLinkCounts::Rejected, "a body size beyond the limit", peer.Name);
      break;
    }
    if (h.Version >= 2 && peer.Version.exchange(2) < 2)
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      ++this->Counts.Version2Peers;
    }
    body.resize(static_cast<std::size_t>(h.BodyBytes));
    r = body.empty() ? ReadResult::Ok : reader.Read(body.data(), body.size());
    if (r != ReadResult::Ok)
    {
      break;
    }
    reader.MessageDone();
    if (++peer.Messages == 1 && peer.IsServer && h.Version < 2)
    {
      this->SayVersion2(peer);
    }
    this->Take(peer, header, body);
  }
  if (r == ReadResult::Stalled)
  {
    this->Count(&IgtlLinkCounts::Rejected, "a message that did not arrive whole within its time", peer.Name);
  }
  std::lock_guard<std::mutex> lock(peer.SocketMutex);
  socket->CloseSocket();
  peer.Done = true;
}

void IgtlLink::Take(Peer& peer, const unsigned char* header, const std::vector<unsigned char>& body)
{
  const double arrivalMs = NowMs();
  IgtlPoseMessage m = DecodeIgtlPose(header, body, this->Settings.ToolName, this->Settings.Reading);
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    ++this->Counts.Messages;
  }
  if (m.What == IgtlPoseMessage::Verdict::Rejected)
  {
    this->Count(&IgtlLinkCounts::Rejected, m.Reason, peer.Name);
    return;
  }
  if (m.What == IgtlPoseMessage::Verdict::Ignored)
  {
    this->Count(&IgtlLinkCounts::Ignored, m.Reason, peer.Name);
    return;
  }
  m.Pose.TimeS = (arrivalMs - this->StartMs) / 1000.0;
  bool steers = false;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    steers = this->MaySteer(peer);
    if (steers)
    {
      ++this->Counts.Poses;
      this->Counts.NotSeen += m.Pose.Lost ? 1 : 0;
      if (this->Fresh)
      {
        ++this->Counts.Dropped; // the one waiting was never computed: the newer one replaces it
      }
      this->Newest = m.Pose;
      this->NewestArrivalMs = arrivalMs;
      this->Fresh = true;
    }
  }
  if (!steers)
  {
    this->Count(&IgtlLinkCounts::Rejected, "a pose of " + this->Settings.ToolName + " from a peer that does not steer it", peer.Name);
    return;
  }
  this->PoseArrived.notify_one();
}

bool IgtlLink::MaySteer(const Peer& peer)
{
  // One source steers: the tracker connected to; without one, the peer from the address named
  // (PoseFromHost), else the first client that sends the tool's pose, until it goes.
  if (this->Settings.ConnectPort > 0)
  {
    return peer.IsServer;
  }
  if (!this->Settings.PoseFromHost.empty() && peer.Host != this->Settings.PoseFromHost)
  {
    return false;
  }
  const bool sourceGone = std::none_of(this->Peers.begin(), this->Peers.end(),
    [&](const auto& p) { return p->Name == this->PoseSource && !p->Done; });
  if (this->PoseSource.empty() || sourceGone)
  {
    if (this->PoseSource != peer.Name)
    {
      this->Events.push_back(peer.Name + " (" + peer.Host + ") steers the scalpel: its poses of " + this->Settings.ToolName +
        " are taken, any other peer's refused");
    }
    this->PoseSource = peer.Name;
  }
  return this->PoseSource == peer.Name;
}

bool IgtlLink::WaitForPose(double timeoutMs, TrackedPose& pose, double& arrivalMs)
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(static_cast<long long>(std::max(0.0, timeoutMs) * 1000.0));
  if (!this->PoseArrived.wait_until(lock, until, [this] { return this->Fresh || this->Stop.load(); }) || !this->Fresh)
  {
    return false;
  }
  pose = this->Newest;
  arrivalMs = this->NewestArrivalMs;
  this->Fresh = false;
  return true;
}

void IgtlLink::Send(const std::string& packed)
{
  std::vector<std::shared_ptr<Peer>> peers;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    const IgtlResultsTo to = this->Settings.ResultsTo;
    for (const auto& peer : this->Peers)
    {
      const bool asked = peer->IsServer ? to != IgtlResultsTo::Listeners : to != IgtlResultsTo::Tracker;
      if (asked && !peer->Done && !peer->Deaf)
      {
        peers.push_back(peer);
      }
    }
  }
  std::string inVersion2; // made once, for the peers that speak it
  for (const auto& peer : peers)
  {
    const bool version2 = peer->Version >= 2; // read once: its reader may raise it meanwhile
    if (version2 && inVersion2.empty())
    {
      inVersion2 = ToIgtlVersion2Stream(packed);
    }
    const std::string& bytes = version2 ? inVersion2 : packed;
    std::unique_lock<std::mutex> socketLock(peer->SocketMutex);
    if (peer->Done)
    {
      continue;
    }
    const bool sent = peer->Socket->Send(bytes.data(), static_cast<int>(bytes.size())) == 1;
    socketLock.unlock();
    if (!sent)
    {
      peer->Deaf = true;
      {
        std::lock_guard<std::mutex> lock(this->Mutex);
        ++this->Counts.SendFailures;
      }
      this->Note(peer->Name + " took no more results within " + std::to_string(SendTimeoutMs) +
        " ms: none are sent to it from now on (its poses are still read)");
    }
  }
}

IgtlLinkCounts IgtlLink::GetCounts() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Counts;
}

std::vector<std::string> IgtlLink::TakeEvents()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  std::vector<std::string> events;
  events.swap(this->Events);
  return events;
}

std::size_t IgtlLink::GetNumberOfPeers() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return static_cast<std::size_t>(std::count_if(this->Peers.begin(), this->Peers.end(), [](const auto& p) { return !p->Done; }));
}
} // namespace vp
