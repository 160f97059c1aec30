// vesselproximity live: the tracking session on a live OpenIGTLink stream (PLUS, a tracker, 3D
// Slicer), its results sent back to every peer as Slicer reads them, and recorded like track's.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpFrameHeadline.h"
#include "vpFramesCsv.h"
#include "vpIgtlLink.h"
#include "vpInputError.h"
#include "vpLivePoseSource.h"
#include "vpLiveOptions.h"
#include "vpOutputOptions.h"
#include "vpLiveResults.h"
#include "vpLiveResultsOutput.h"
#include "vpPoseFile.h"
#include "vpRunFolder.h"
#include "vpRunningQuantiles.h"
#include "vpSignalHold.h"
#include "vpTrackingOptions.h"
#include "vpTrackingRecorder.h"
#include "vpTrackingSession.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>

namespace vp
{
namespace
{
/// A session without a single pose: said in one line with what did come.
void ThrowWhenNoPoseCame(IgtlLink& link)
{
  const IgtlLinkCounts counts = link.GetCounts();
  if (counts.Poses > 0)
  {
    return;
  }
  if (SignalHold::Pending())
  {
    // The held signal ends the process as it unwinds, before any error line: said here.
    std::fprintf(stderr, "live: ended by a signal before any pose of %s came (%zu message(s), %zu connection(s)); nothing written\n",
      link.GetSettings().ToolName.c_str(), counts.Messages, counts.Connections);
  }
  std::size_t ignored = 0;
  for (const auto& [which, count] : counts.Ignored)
  {
    ignored += count;
  }
  const IgtlLinkSettings& s = link.GetSettings();
  throw InputError(s.ConnectPort > 0 ? s.ConnectHost + ":" + std::to_string(s.ConnectPort) : "port " + std::to_string(link.GetListenPort()),
    "no pose of " + s.ToolName + " came (" + std::to_string(counts.Messages) + " message(s): " +
      std::to_string(counts.RejectedTotal()) + " rejected, " + std::to_string(ignored) + " of other types or tools; " +
      std::to_string(counts.Connections) + " connection(s))");
}

} // namespace

cli::ModuleDescription DescribeLiveCommand()
{
  using cli::ParameterType;
  std::vector<cli::Parameter> stream = LiveStreamOptions(true, true);
  stream.push_back(OutputFolderOption("The run's folder: frames.csv (flushed every second), summary.json, distance.png."));
  return cli::ModuleDescription::Subcommand("vesselproximity live",
    "track a live OpenIGTLink stream (PLUS, a tracker, 3D Slicer) and send the results back",
    "Takes the scalpel's pose from a live OpenIGTLink stream, computes each frame as track does and sends it back to "
    "every peer: a STRING " +
      std::string(live::FrameDevice) + " (the frame as JSON, or {\"state\": \"lost\"}), a POINT " + live::PointsDevice +
      " (the tip and each class's closest point, RAS) and, on each change of level, a STRING " + live::LevelDevice +
      ". Runs until Ctrl-C (or --duration-s); with -o, the run's frames.csv, summary.json and distance.png.",
    {
      { "Inputs", "", { VesselsOption().SetRequired(), RepairSwitch() } },
      { "Stream", "", stream },
      { "Scalpel", "", ScalpelOptions() },
      EngineOptions(EngineMethodNames(OfferedForTracking)),
      TrackingOptions(),
      OutputOptions(OutputForLive),
    });
}

namespace
{
/// What the run reads: never written over, by its folder or its outputs.
std::vector<std::string> LiveInputs(const cli::ParsedArguments& args, const SceneRequest& request)
{
  std::vector<std::string> inputs = SceneInputFiles(request);
  inputs.push_back(args.GetString("registration"));
  return inputs;
}

/// Each class sent to Slicer under a device name of its own, or the run refused before it starts.
void RefuseDeviceNameClash(const SceneRequest& request)
{
  std::vector<std::string> classes;
  for (const NamedMesh& vessel : request.Vessels)
  {
    classes.push_back(vessel.ClassName);
  }
  const std::string clash = LiveDeviceNameClash(classes);
  if (!clash.empty())
  {
    throw InputError("--vessels", clash);
  }
}

/// The run's folder for -o, its inputs noted; null without -o.
std::unique_ptr<RunFolder> LiveRunFolder(const cli::ParsedArguments& args, const SceneRequest& request)
{
  const std::string outDir = args.GetString("output");
  if (outDir.empty())
  {
    return nullptr;
  }
  auto run = std::make_unique<RunFolder>(outDir, "summary.json");
  run->KeepIfKilled(); // a crash keeps the rows flushed so far (interrupted-*/ after the next run)
  run->SetInputs(LiveInputs(args, request));
  return run;
}

/// The stream opened once the scene is built (no pose waits on a build), and said.
std::unique_ptr<IgtlLink> OpenLiveStream(const IgtlLinkSettings& link)
{
  auto stream = std::make_unique<IgtlLink>(link);
  if (stream->GetListenPort() >= 0)
  {
    std::cerr << "live: listening on port " << stream->GetListenPort() << "\n";
  }
  if (link.ConnectPort > 0)
  {
    std::cerr << "live: connecting to " << link.ConnectHost << ":" << link.ConnectPort << "\n";
  }
  std::cerr << "live: waiting for " << link.ToolName << "; Ctrl-C ends the session\n";
  return stream;
}

/// What the terminal shows as the stream runs: the link's events, a status line a second, each
/// loss of tracking.
class LiveStatus : public FrameOutput
{
public:
  LiveStatus(IgtlLink& stream, const LiveResultsOutput& results, double staleMs)
    : Stream(stream)
    , Results(results)
    , StaleMs(staleMs)
  {
  }
  void OnFrame(const TrackedFrame& frame) override
  {
    PrintLinkEvents("live", this->Stream);
    if (NowMs() - this->LastStatusMs > 1000.0)
    {
      this->LastStatusMs = NowMs();
      std::fprintf(stderr, "live: frame %d, %s, latency p95 %.3f ms, %zu peer(s)\n", frame.Frame, FrameHeadline(frame).c_str(),
        this->Results.GetLatencyMs().Quantile(0.95), this->Stream.GetNumberOfPeers());
    }
  }
  void OnLost(const TrackedPose&) override
  {
    std::cerr << "live: tracking lost: no pose of " << this->Stream.GetSettings().ToolName << " for "
              << static_cast<int>(this->StaleMs) << " ms\n";
  }

private:
  IgtlLink& Stream;
  const LiveResultsOutput& Results;
  double StaleMs;
  double LastStatusMs = NowMs();
};

/// The session's closing lines on stdout (outDir: the run's folder as given, empty without -o).
void PrintLiveEnd(IgtlLink& stream, std::size_t frames, std::size_t lostPoses, const RunningQuantiles& latency,
  const std::string& frameTimes, const std::string& outDir)
{
  PrintLinkEvents("live", stream);
  const IgtlLinkCounts counts = stream.GetCounts();
  const int signal = SignalHold::Answer(); // the session ended as asked: the signal is not raised again
  std::printf("%zu frames; %zu message(s), %zu pose(s) of %s, %zu dropped (a newer one came first), %zu rejected, "
              "%zu tracking loss(es)%s\n",
    frames, counts.Messages, counts.Poses, stream.GetSettings().ToolName.c_str(), counts.Dropped, counts.RejectedTotal(),
    lostPoses, signal ? " (ended by a signal)" : "");
  for (const auto& [reason, count] : counts.Rejected)
  {
    std::printf("  rejected %zu: %s\n", count, reason.c_str());
  }
  if (latency.Count() > 0)
  {
    std::printf("  latency pose in -> results out: median %.4f ms, p95 %.4f ms, max %.4f ms\n", latency.Quantile(0.5),
      latency.Quantile(0.95), latency.Quantile(1.0));
  }
  if (frames > 0)
  {
    std::printf("  %s\n", frameTimes.c_str());
  }
  if (!outDir.empty())
  {
    std::printf("wrote %s/frames.csv, summary.json, distance.png\n", outDir.c_str());
  }
}

/// The run recorded into its folder (frames.csv, summary.json with the latency and the link's
/// counts, distance.png): frames and lost poses.
std::pair<std::size_t, std::size_t> RecordLive(vtkVesselProximityLogic* proximity, const OpenedScene& scene, double loadMs,
  LivePoseSource& poses, IgtlLink& stream, const std::vector<FrameOutput*>& outputs, const LiveResultsOutput& results,
  RunFolder& run)
{
  TrackingRecorder recorder(proximity, scene.Vessels);
  recorder.SetLoadAndBuildMs(loadMs);
  for (FrameOutput* output : outputs)
  {
    recorder.AddOutput(output);
  }
  recorder.SetReportAddition([&](nlohmann::ordered_json& doc) {
    doc["latency_ms"] = LiveLatencyJson(results.GetLatencyMs());
    doc["stale_ms"] = poses.GetStaleMs();
    doc["link"] = LiveLinkJson(stream.GetCounts());
  });
  try
  {
    recorder.Run(poses, run);
  }
  catch (const InputError&)
  {
    ThrowWhenNoPoseCame(stream);
    throw;
  }
  run.Commit();
  return { static_cast<std::size_t>(recorder.GetSummary().GetNumberOfFrames()),
    recorder.GetReport().value("poses_lost", std::size_t(0)) };
}
} // namespace

int RunLiveCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  // Ctrl-C is the session's end, not its interruption: held from here, answered at the end.
  SignalHold hold;
  const IgtlLinkSettings link = ParseLiveStream(args);
  const double staleMs = ParseStaleMs(args);
  const double durationS = ParseDurationS(args);
  const double start = NowMs();
  const SceneRequest request = ParseRecordedSceneRequest(args);
  RefuseDeviceNameClash(request);
  ChosenOutputs chosen(args, OutputForLive, "live", LiveInputs(args, request));
  std::unique_ptr<RunFolder> run = LiveRunFolder(args, request);
  vtkSmartPointer<vtkVesselProximityLogic> proximity = module.CreateLogic();
  OpenedScene scene;
  {
    StageProgress progress("live", proximity); // a window or a stream waits on these: say what they are
    scene = proximity->OpenScene(request);
  }
  ReportOpenedScene("live", proximity, scene, request.ScalpelFile);

  std::unique_ptr<IgtlLink> stream = OpenLiveStream(link);
  const std::string name = link.ConnectPort > 0 ? link.ConnectHost + ":" + std::to_string(link.ConnectPort)
                                                : "port " + std::to_string(stream->GetListenPort());
  LivePoseSource poses(*stream, name, staleMs, durationS);
  poses.SetIdleCallback([&stream] { PrintLinkEvents("live", *stream); });
  LiveResultsOutput results(*stream, &poses);
  LiveStatus status(*stream, results, staleMs);
  TrackingSummary frameTimes; // the frames' own times and those over the budget, said at the end
  std::vector<FrameOutput*> outputs = { &results, &status, &frameTimes };
  outputs.insert(outputs.end(), chosen.Get().begin(), chosen.Get().end());
  std::size_t frames = 0, lostPoses = 0;
  if (run)
  {
    std::tie(frames, lostPoses) = RecordLive(proximity, scene, NowMs() - start, poses, *stream, outputs, results, *run);
  }
  else
  {
    TrackingSession session(proximity);
    for (FrameOutput* output : outputs)
    {
      session.AddOutput(output);
    }
    session.Run(poses);
    if (session.GetNumberOfFrames() == 0)
    {
      ThrowWhenNoPoseCame(*stream);
    }
    frames = session.GetNumberOfFrames();
    lostPoses = session.GetNumberOfLostPoses();
  }
  chosen.SayProblems();
  PrintLiveEnd(*stream, frames, lostPoses, results.GetLatencyMs(),
    FrameTimesText(frameTimes, proximity->GetTrackingLogic()->GetFrameBudgetMs()), run ? args.GetString("output") : std::string());
  return 0;
}
} // namespace vp
