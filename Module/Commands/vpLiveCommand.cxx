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
#include "vpLiveResults.h"
#include "vpPoseFile.h"
#include "vpRunFolder.h"
#include "vpRunningQuantiles.h"
#include "vpSignalHold.h"
#include "vpTrackingOptions.h"
#include "vpTrackingRecorder.h"
#include "vpTrackingSession.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

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
      EngineOptions({ "exact", "zbuffer", "both" }),
      TrackingOptions(),
    });
}

int RunLiveCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  // Ctrl-C is the session's end, not its interruption: held from here, answered at the end.
  SignalHold hold;
  const IgtlLinkSettings link = ParseLiveStream(args);
  const double staleMs = ParseStaleMs(args);
  const double durationS = ParseDurationS(args);

  const double start = NowMs();
  SceneRequest request = ParseSceneRequest(args);
  request.RepairVessels = args.GetBoolean("repair");
  std::vector<std::string> classes;
  for (const NamedMesh& vessel : request.Vessels)
  {
    classes.push_back(vessel.ClassName);
  }
  CheckFramesCsvColumns(classes, !request.Tumours.empty());
  std::unique_ptr<RunFolder> run;
  const std::string outDir = args.GetString("output");
  if (!outDir.empty())
  {
    run = std::make_unique<RunFolder>(outDir, "summary.json");
    run->KeepIfKilled(); // a crash keeps the rows flushed so far (interrupted-*/ after the next run)
    std::vector<std::string> inputs = { request.ScalpelFile };
    for (const NamedMesh& vessel : request.Vessels)
    {
      inputs.push_back(vessel.FileName);
    }
    if (args.IsSet("registration"))
    {
      inputs.push_back(args.GetString("registration"));
    }
    run->SetInputs(inputs);
  }
  vtkSmartPointer<vtkVesselProximityLogic> proximity = module.CreateLogic();
  OpenedScene scene;
  {
    StageProgress progress("live", proximity); // a window or a stream waits on these: say what they are
    scene = proximity->OpenScene(request);
  }
  ReportOpenedScene("live", proximity, scene, request.ScalpelFile);

  // The scene is built before the stream is opened: no pose waits on a build.
  IgtlLink stream(link);
  const std::string name = link.ConnectPort > 0 ? link.ConnectHost + ":" + std::to_string(link.ConnectPort)
                                                : "port " + std::to_string(stream.GetListenPort());
  if (stream.GetListenPort() >= 0)
  {
    std::cerr << "live: listening on port " << stream.GetListenPort() << "\n";
  }
  if (link.ConnectPort > 0)
  {
    std::cerr << "live: connecting to " << link.ConnectHost << ":" << link.ConnectPort << "\n";
  }
  std::cerr << "live: waiting for " << link.ToolName << "; Ctrl-C ends the session\n";
  LivePoseSource poses(stream, name, staleMs, durationS);
  poses.SetIdleCallback([&stream] { PrintLinkEvents("live", stream); });

  // Each change of level goes to the peers when it happens, as the logic announces it.
  vtkNew<vtkCallbackCommand> onChange;
  onChange->SetClientData(&stream);
  onChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<IgtlLink*>(client)->Send(PackLiveLevelChange(*static_cast<DangerLevelChange*>(call)));
  });
  vtkScalpelTrackingLogic* tracking = proximity->GetTrackingLogic();
  const unsigned long observer = tracking->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, onChange);

  RunningQuantiles latency;
  TrackingSummary summary; // without -o; the recorder keeps its own
  double lastStatusMs = NowMs();
  const auto onFrame = [&](const TrackedFrame& frame) {
    stream.Send(PackLiveFrame(frame));
    latency.Add(NowMs() - poses.GetLastArrivalMs()); // pose in -> results out
    if (!run)
    {
      summary.Add(frame);
    }
    PrintLinkEvents("live", stream);
    if (NowMs() - lastStatusMs > 1000.0)
    {
      lastStatusMs = NowMs();
      std::fprintf(stderr, "live: frame %d, %s, latency p95 %.3f ms, %zu peer(s)\n", frame.Frame, FrameHeadline(frame).c_str(),
        latency.Quantile(0.95), stream.GetNumberOfPeers());
    }
  };
  const auto onLost = [&](const TrackedPose& lost) {
    const double sinceMs = NowMs() - poses.GetLastArrivalMs() + poses.GetStaleMs();
    stream.Send(PackLiveLost(lost.TimeS, sinceMs));
    std::cerr << "live: tracking lost: no pose of " << link.ToolName << " for " << static_cast<int>(staleMs) << " ms\n";
  };
  nlohmann::ordered_json report;
  std::size_t frames = 0;
  std::size_t lostPoses = 0;
  if (run)
  {
    TrackingRecorder recorder(proximity, scene.Vessels);
    recorder.SetLoadAndBuildMs(NowMs() - start);
    recorder.SetFrameObserver(onFrame);
    recorder.SetLostObserver(onLost);
    recorder.SetReportAddition([&](nlohmann::ordered_json& doc) {
      doc["latency_ms"] = LiveLatencyJson(latency);
      doc["stale_ms"] = staleMs;
      doc["link"] = LiveLinkJson(stream.GetCounts());
    });
    try
    {
      recorder.Run(poses, *run);
    }
    catch (const InputError&)
    {
      ThrowWhenNoPoseCame(stream);
      throw;
    }
    run->Commit();
    report = recorder.GetReport();
    frames = static_cast<std::size_t>(recorder.GetSummary().GetNumberOfFrames());
    lostPoses = report.value("poses_lost", std::size_t(0));
  }
  else
  {
    TrackingSession session(proximity);
    session.Run(poses, onFrame, onLost);
    if (session.GetNumberOfFrames() == 0)
    {
      ThrowWhenNoPoseCame(stream);
    }
    frames = session.GetNumberOfFrames();
    lostPoses = session.GetNumberOfLostPoses();
  }
  tracking->RemoveObserver(observer);
  PrintLinkEvents("live", stream);
  const IgtlLinkCounts counts = stream.GetCounts();
  const int signal = SignalHold::Answer(); // the session ended as asked: the signal is not raised again
  std::printf("%zu frames; %zu message(s), %zu pose(s) of %s, %zu dropped (a newer one came first), %zu rejected, "
              "%zu tracking loss(es)%s\n",
    frames, counts.Messages, counts.Poses, link.ToolName.c_str(), counts.Dropped, counts.RejectedTotal(), lostPoses,
    signal ? " (ended by a signal)" : "");
  for (const auto& [reason, count] : counts.Rejected)
  {
    std::printf("  rejected %zu: %s\n", count, reason.c_str());
  }
  if (latency.Count() > 0)
  {
    std::printf("  latency pose in -> results out: median %.4f ms, p95 %.4f ms, max %.4f ms\n", latency.Quantile(0.5),
      latency.Quantile(0.95), latency.Quantile(1.0));
  }
  if (run)
  {
    std::printf("wrote %s/frames.csv, summary.json, distance.png\n", outDir.c_str());
  }
  return 0;
}
} // namespace vp
