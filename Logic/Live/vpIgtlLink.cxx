#include "vpIgtlLink.h"

#include "vpClock.h"
#include "vpIgtlMessages.h"
#include "vpInputError.h"

#include <igtlClientSocket.h>
#include <igtlServerSocket.h>

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cstring>

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

/// A TCP connection to host:port within timeoutMs: its descriptor, or -1.
int ConnectWithin(const std::string& host, int port, int timeoutMs)
{
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0)
  {
    return -1;
  }
  int connected = -1;
  for (addrinfo* a = found; a && connected < 0; a = a->ai_next)
  {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0)
    {
      continue;
    }
    const int flags = fcntl(fd, F_GETFL, 0);
    fcntl(fd, F_SETFL, flags | O_NONBLOCK);
    int result = ::connect(fd, a->ai_addr, a->ai_addrlen);
    if (result < 0 && errno == EINPROGRESS)
    {
      pollfd p{ fd, POLLOUT, 0 };
      int error = 0;
      socklen_t length = sizeof error;
      result = poll(&p, 1, timeoutMs) == 1 && getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) == 0 && error == 0 ? 0 : -1;
    }
    if (result == 0)
    {
      fcntl(fd, F_SETFL, flags);
      const int on = 1;
      setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on); // a pose is small and late is useless
      connected = fd;
    }
    else
    {
      ::close(fd);
    }
  }
  freeaddrinfo(found);
  return connected;
}

/// The characters an OpenIGTLink type name is made of; anything else is a stream out of step.
bool IsTypeName(const std::string& type)
{
  return !type.empty() &&
    std::all_of(type.begin(), type.end(), [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
}
} // namespace

struct IgtlLink::Peer
{
  igtl::Socket::Pointer Socket;
  std::string Name; ///< "127.0.0.1:18944" (a server) or "client 2"
  std::thread Reader;
  std::atomic<bool> Done{ false };
  /// A send failed (the peer took no more within the timeout, or part of a message went): the
  /// rest of that message can never be placed, so nothing more is sent to it; its poses are
  /// still read (a tracker server that never reads is still a tracker).
  std::atomic<bool> Deaf{ false };
  std::mutex SocketMutex;             ///< a send and the close never overlap
};

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
    auto server = igtl::ServerSocket::New();
    if (settings.ListenPort > 65535 || server->CreateServer(settings.ListenPort) < 0)
    {
      throw ParameterError("ListenPort", "cannot serve on port " + std::to_string(settings.ListenPort) + " (in use, or not a port)");
    }
    this->ListenPort = server->GetServerPort();
    server->Register(); // held by the shared_ptr below, released with it
    this->Server = std::shared_ptr<void>(server.GetPointer(), [](void* s) { static_cast<igtl::ServerSocket*>(s)->UnRegister(); });
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
  if (this->Server)
  {
    static_cast<igtl::ServerSocket*>(this->Server.get())->CloseSocket();
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
  double pauseMs = 100.0;
  bool said = false;
  while (!this->Stop)
  {
    const int descriptor = ConnectWithin(this->Settings.ConnectHost, this->Settings.ConnectPort, 1000);
    if (descriptor < 0)
    {
      if (!said)
      {
        this->Note("cannot connect to " + name + "; trying again, every 2 s at most");
        said = true;
      }
      for (const double until = NowMs() + pauseMs; !this->Stop && NowMs() < until;)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(PollMs));
      }
      pauseMs = std::min(2000.0, 2.0 * pauseMs);
      continue;
    }
    said = false;
    pauseMs = 100.0;
    auto socket = AdoptedSocket::New();
    socket->Adopt(descriptor);
    // A tracking-data server streams once asked (PLUS and the library's examples do so); asked
    // before the peer is listed, so that no frame's results are sent in the middle of the request.
    const std::string start = PackIgtlStartTracking(10);
    socket->Send(start.data(), static_cast<int>(start.size()));
    auto peer = std::make_shared<Peer>();
    peer->Socket = socket.GetPointer();
    peer->Name = name;
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Peers.push_back(peer);
      ++this->Counts.Connections;
    }
    this->Note("connected to " + name);
    this->ServePeer(*peer);
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Peers.erase(std::remove(this->Peers.begin(), this->Peers.end(), peer), this->Peers.end());
    }
    if (!this->Stop)
    {
      {
        std::lock_guard<std::mutex> lock(this->Mutex);
        ++this->Counts.ConnectionsLost;
      }
      this->Note("connection to " + name + " lost; reconnecting");
    }
  }
}

void IgtlLink::AcceptLoop()
{
  auto* server = static_cast<igtl::ServerSocket*>(this->Server.get());
  int clients = 0;
  while (!this->Stop)
  {
    this->Prune();
    igtl::ClientSocket::Pointer socket = server->WaitForConnection(100);
    if (socket.IsNull())
    {
      continue;
    }
    std::lock_guard<std::mutex> lock(this->Mutex);
    const auto connected = std::count_if(this->Peers.begin(), this->Peers.end(), [](const auto& p) { return !p->Done; });
    if (connected >= this->Settings.MaxClients)
    {
      socket->CloseSocket();
      this->Events.push_back("turned a client away: " + std::to_string(this->Settings.MaxClients) + " are served already");
      continue;
    }
    auto peer = std::make_shared<Peer>();
    peer->Socket = socket.GetPointer();
    peer->Name = "client " + std::to_string(++clients);
    ++this->Counts.Connections;
    this->Events.push_back(peer->Name + " connected on port " + std::to_string(this->ListenPort));
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
  // Reads count bytes through a buffer of what has arrived (one call takes all that waits: a
  // sender at 1 kHz is read in a few calls a frame, not two per message); a message begun must
  // end within the timeout.
  std::vector<unsigned char> arrived;
  std::size_t used = 0;
  std::vector<unsigned char> chunk(1u << 16);
  auto read = [&](unsigned char* into, std::size_t count, bool begun) {
    double startMs = NowMs();
    while (arrived.size() - used < count)
    {
      if (this->Stop)
      {
        return ReadResult::Stopped;
      }
      const int r = socket->Receive(chunk.data(), static_cast<int>(chunk.size()), 0);
      if (r == 0)
      {
        return ReadResult::Closed;
      }
      if (r < 0)
      {
        if ((begun || arrived.size() > used) && NowMs() - startMs > this->Settings.MessageTimeoutMs)
        {
          return ReadResult::Stalled;
        }
        continue;
      }
      if (!begun && arrived.size() == used)
      {
        startMs = NowMs(); // the message's time runs from its first byte
      }
      if (used > 0)
      {
        arrived.erase(arrived.begin(), arrived.begin() + static_cast<std::ptrdiff_t>(used));
        used = 0;
      }
      arrived.insert(arrived.end(), chunk.begin(), chunk.begin() + r);
    }
    std::copy_n(arrived.begin() + static_cast<std::ptrdiff_t>(used), count, into);
    used += count;
    return ReadResult::Ok;
  };
  unsigned char header[IgtlHeaderBytes];
  std::vector<unsigned char> body;
  while (true)
  {
    ReadResult r = read(header, IgtlHeaderBytes, false);
    if (r == ReadResult::Stalled)
    {
      this->Count(&IgtlLinkCounts::Rejected, "a message that stopped midway", peer.Name);
    }
    if (r != ReadResult::Ok)
    {
      break;
    }
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
    body.resize(static_cast<std::size_t>(h.BodyBytes));
    r = body.empty() ? ReadResult::Ok : read(body.data(), body.size(), true);
    if (r == ReadResult::Stalled)
    {
      this->Count(&IgtlLinkCounts::Rejected, "a message that stopped midway", peer.Name);
    }
    if (r != ReadResult::Ok)
    {
      break;
    }
    const double arrivalMs = NowMs();
    IgtlPoseMessage m = DecodeIgtlPose(header, body, this->Settings.ToolName, this->Settings.Reading);
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      ++this->Counts.Messages;
    }
    if (m.What == IgtlPoseMessage::Verdict::Rejected)
    {
      this->Count(&IgtlLinkCounts::Rejected, m.Reason, peer.Name);
      continue;
    }
    if (m.What == IgtlPoseMessage::Verdict::Ignored)
    {
      this->Count(&IgtlLinkCounts::Ignored, m.Reason, peer.Name);
      continue;
    }
    m.Pose.TimeS = (arrivalMs - this->StartMs) / 1000.0;
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      ++this->Counts.Poses;
      if (this->Fresh)
      {
        ++this->Counts.Dropped; // the one waiting was never computed: the newer one replaces it
      }
      this->Newest = m.Pose;
      this->NewestArrivalMs = arrivalMs;
      this->Fresh = true;
    }
    this->PoseArrived.notify_one();
  }
  std::lock_guard<std::mutex> lock(peer.SocketMutex);
  socket->CloseSocket();
  peer.Done = true;
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
    for (const auto& peer : this->Peers)
    {
      if (!peer->Done && !peer->Deaf)
      {
        peers.push_back(peer);
      }
    }
  }
  for (const auto& peer : peers)
  {
    std::unique_lock<std::mutex> socketLock(peer->SocketMutex);
    if (peer->Done)
    {
      continue;
    }
    const bool sent = peer->Socket->Send(packed.data(), static_cast<int>(packed.size())) == 1;
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
