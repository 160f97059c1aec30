#include "vpLiveBenchmark.h"

#include "vpClock.h"
#include "vpIgtlLink.h"
#include "vpIgtlMessages.h"
#include "vpInputError.h"
#include "vpLivePoseSource.h"
#include "vpLiveResults.h"
#include "vpLiveResultsOutput.h"
#include "vpQuantile.h"
#include "vpSceneRequest.h"
#include "vpTrackingSession.h"
#include "vtkVesselProximityLogic.h"

#include "vpOscOutput.h"

#include <igtlClientSocket.h>
#include <lo/lo.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <thread>
#include <unistd.h>

namespace vp
{
namespace
{
using Json = BenchJson;

/// This process's resident memory now, in MB.
double ResidentMb()
{
  long pages = 0, resident = 0;
  std::ifstream("/proc/self/statm") >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

Json Quantiles(const std::vector<double>& values)
{
  if (values.empty())
  {
    return nullptr;
  }
  return { { "median", Quantile(values, 0.5) }, { "p95", Quantile(values, 0.95) }, { "max", Quantile(values, 1.0) } };
}

/// An OSC peer on loopback, liblo's own server thread: when each distance message arrived.
class OscListener
{
public:
  OscListener()
    : Server(lo_server_thread_new(nullptr, nullptr))
  {
    lo_server_thread_add_method(this->Server, "/vesselproximity/distance", nullptr, &OscListener::Heard, this);
    lo_server_thread_start(this->Server);
  }
  ~OscListener() { lo_server_thread_free(this->Server); }
  OscListener(const OscListener&) = delete;
  OscListener& operator=(const OscListener&) = delete;
  int GetPort() const { return lo_server_thread_get_port(this->Server); }
  /// Each message's distance and when it arrived (vp::NowMs), in order.
  std::vector<std::pair<float, double>> Taken()
  {
    std::lock_guard<std::mutex> hold(this->Lock);
    return this->Arrived;
  }

private:
  static int Heard(const char*, const char* types, lo_arg** argv, int argc, lo_message, void* self)
  {
    if (argc >= 2 && types[1] == 'f')
    {
      // liblo's argument may lie at any address (lo_arg is a union with 8-byte members): copied.
      float distance = 0.0f;
      std::memcpy(&distance, argv[1], sizeof distance);
      auto* listener = static_cast<OscListener*>(self);
      std::lock_guard<std::mutex> hold(listener->Lock);
      listener->Arrived.emplace_back(distance, NowMs());
    }
    return 0;
  }
  lo_server_thread Server;
  std::mutex Lock;
  std::vector<std::pair<float, double>> Arrived;
};

/// Each frame's distance and when its pose arrived, as the OSC output is told of it.
class PoseArrivals : public FrameOutput
{
public:
  explicit PoseArrivals(const LivePoseSource& source)
    : Source(source)
  {
  }
  void OnFrame(const TrackedFrame& frame) override { this->Frames.emplace_back(OscOutput::SignedDistanceOf(frame), this->Source.GetLastArrivalMs()); }
  /// Pose arrival to OSC message received, for each message: matched in order to the frame whose
  /// distance it carries (a frame a newer one replaced before it was sent has no message).
  std::vector<double> LatenciesMs(const std::vector<std::pair<float, double>>& received) const
  {
    std::vector<double> latencies;
    std::size_t f = 0;
    for (const auto& [distance, atMs] : received)
    {
      while (f < this->Frames.size() && this->Frames[f].first != distance)
      {
        ++f;
      }
      if (f < this->Frames.size())
      {
        latencies.push_back(atMs - this->Frames[f++].second);
      }
    }
    return latencies;
  }

private:
  const LivePoseSource& Source;
  std::vector<std::pair<float, double>> Frames;
};

/// One phase: the stream at rateHz for seconds, through a fresh session on the logic.
Json Phase(vtkVesselProximityLogic* logic, const std::vector<TrackedPose>& poses, double rateHz, double seconds)
{
  IgtlLinkSettings settings;
  settings.ListenPort = 0;
  settings.ToolName = "Scalpel";
  settings.ResultsTo = IgtlResultsTo::All; // the tracker here reads them back: the reply is measured
  IgtlLink link(settings);
  std::atomic<bool> stop{ false };
  std::atomic<std::size_t> sent{ 0 };
  // The tracker: connects, streams at its rate, and reads back (and drops) what it is sent.
  std::thread tracker([&] {
    auto socket = igtl::ClientSocket::New();
    if (socket->ConnectToServer("127.0.0.1", link.GetListenPort()) != 0)
    {
      return;
    }
    socket->SetReceiveTimeout(1);
    std::thread reader([&] {
      std::vector<char> sink(1 << 16);
      while (!stop)
      {
        socket->Receive(sink.data(), static_cast<int>(sink.size()), 0);
      }
    });
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; !stop; ++i)
    {
      const auto at = start + std::chrono::microseconds(static_cast<long long>(1e6 * static_cast<double>(i) / rateHz));
      if (at - start > std::chrono::microseconds(static_cast<long long>(1e6 * seconds)))
      {
        break;
      }
      std::this_thread::sleep_until(at);
      const std::string message = PackIgtlTransform("Scalpel", poses[i % poses.size()].ModelToWorld);
      socket->Send(message.data(), static_cast<int>(message.size()));
      ++sent;
    }
    stop = true;
    reader.join();
    socket->CloseSocket();
  });
  LivePoseSource source(link, "the bench's tracker", 1000.0, seconds + 0.3);
  TrackingSession session(logic);
  std::vector<double> frameMs;
  frameMs.reserve(static_cast<std::size_t>(rateHz * seconds) + 16);
  const double startMs = NowMs();
  double residentAt5s = 0.0;
  std::size_t penetrating = 0;
  LiveResultsOutput results(link, &source);
  session.AddOutput(&results);
  // The frames also go out as OSC, to a peer here: pose to OSC beside pose to OpenIGTLink.
  OscListener listener;
  OscOutput osc("the bench's OSC peer", "127.0.0.1", listener.GetPort(), Sonification::Default());
  PoseArrivals arrivals(source);
  session.AddOutput(&arrivals);
  session.AddOutput(&osc);
  session.Run(source, [&](const TrackedFrame& frame) {
    frameMs.push_back(frame.FrameMs);
    penetrating += std::any_of(frame.Penetrations.begin(), frame.Penetrations.end(),
      [](const Penetration& p) { return p.VolumeMm3 > 0.0 || p.DepthMm > 0.0; });
    if (residentAt5s == 0.0 && NowMs() - startMs >= 5000.0)
    {
      residentAt5s = ResidentMb();
    }
  });
  stop = true;
  tracker.join();
  const IgtlLinkCounts counts = link.GetCounts();
  Json out;
  out["rate_hz"] = rateHz;
  out["seconds"] = seconds;
  out["poses_sent"] = sent.load();
  out["poses_received"] = counts.Poses;
  out["frames"] = frameMs.size();
  out["penetrating_frames"] = penetrating;
  out["poses_dropped"] = counts.Dropped;
  out["rejected"] = counts.RejectedTotal();
  // What `live` reports, measured by the same output (vp::RunningQuantiles: at most 0.1% above).
  out["latency_ms"] = LiveLatencyJson(results.GetLatencyMs());
  std::this_thread::sleep_for(std::chrono::milliseconds(50)); // the last messages on their way
  const std::vector<double> oscMs = arrivals.LatenciesMs(listener.Taken());
  out["osc_latency_ms"] = Quantiles(oscMs); // pose arrival to the OSC peer's receipt
  out["osc_messages"] = oscMs.size();
  out["osc_failed"] = osc.GetCounts().Failed;
  out["frame_ms"] = Quantiles(frameMs); // the anchor: the same frames' compute, without the network
  out["resident_mb_after_5s"] = residentAt5s > 0.0 ? Json(residentAt5s) : Json(nullptr);
  out["resident_mb_end"] = ResidentMb();
  out["resident_growth_percent"] = residentAt5s > 0.0 ? Json(100.0 * (ResidentMb() - residentAt5s) / residentAt5s) : Json(nullptr);
  return out;
}
/// The same stream through another engine (the z-buffer), whole instrument and penetration as
/// in the first phase; a device that cannot be opened is said in the report.
Json EngineBesidePhase(SceneRequest request, const DistanceEngineSettings& engine, const std::vector<TrackedPose>& poses,
  const LiveBenchSettings& settings)
{
  std::fprintf(stderr, "bench: live through the %s engine at %g Hz for %g s\n", engine.Method.c_str(), settings.RateHz,
    settings.Seconds);
  request.Engine = engine;
  vtkSmartPointer<vtkVesselProximityLogic> logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  try
  {
    logic->OpenScene(request);
  }
  catch (const DeviceError& e)
  {
    return { { "unavailable", e.what() } };
  }
  Json out = Phase(logic, poses, settings.RateHz, settings.Seconds);
  out["device"] = logic->GetDistanceEngine()->GetDeviceDescription();
  return out;
}
} // namespace

BenchJson BenchLive(const std::vector<NamedMesh>& vessels, vtkScalpelModel* scalpel, const std::vector<TrackedPose>& poses,
  const LiveBenchSettings& settings)
{
  SceneRequest request;
  request.Vessels = vessels;
  request.Scalpel = scalpel;
  request.ComputeSurfaceDistance = true;
  vtkSmartPointer<vtkVesselProximityLogic> logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  logic->OpenScene(request);
  Json out;
  out["classes"] = vessels.size();
  out["engine"] = "exact, tip and whole instrument";
  std::fprintf(stderr, "bench: live at %g Hz for %g s\n", settings.RateHz, settings.Seconds);
  out["latency"] = Phase(logic, poses, settings.RateHz, settings.Seconds);
  request.Scalpel = logic->GetScalpel();
  if (settings.EngineBeside)
  {
    out[settings.EngineBeside->Method] = EngineBesidePhase(request, *settings.EngineBeside, poses, settings);
  }
  if (settings.TipOnlyBeside)
  {
    std::fprintf(stderr, "bench: live, the tip alone, at %g Hz for %g s\n", settings.RateHz, settings.Seconds);
    request.ComputeSurfaceDistance = false;
    request.ComputePenetration = false;
    vtkSmartPointer<vtkVesselProximityLogic> tipOnly = vtkSmartPointer<vtkVesselProximityLogic>::New();
    tipOnly->OpenScene(request);
    out["tip_only"] = Phase(tipOnly, poses, settings.RateHz, settings.Seconds);
  }
  if (settings.SustainedSeconds > 0.0)
  {
    std::fprintf(stderr, "bench: live sustained at %g Hz for %g s\n", settings.SustainedRateHz, settings.SustainedSeconds);
    out["sustained"] = Phase(logic, poses, settings.SustainedRateHz, settings.SustainedSeconds);
  }
  return out;
}
} // namespace vp
