#include "vpDemoPipeline.h"

#include "vpOutputFile.h"
#include "vpCommandSupport.h"
#include "vpDangerLevels.h"
#include "vpDefaultScalpel.h"
#include "vpDemoTrajectory.h"
#include "vpInputError.h"
#include "vpKeyFrameShots.h"
#include "vpKeyFrames.h"
#include "vpLiverPhantom.h"
#include "vpPoseFile.h"
#include "vpIgtlLink.h"
#include "vpIgtlPoseStreamer.h"
#include "vpLivePoseSource.h"
#include "vpLiveResultsOutput.h"
#include "vpLiveResults.h"
#include "vpTrackingRecorder.h"
#include "vpTrackingSession.h"
#include "vpVesselModelSet.h"
#include "vpVirtualDisplay.h"
#include "vtkScalpelModel.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <thread>
#include <cstdio>
#include <functional>
#include <iostream>
#include <set>

namespace vp
{
namespace
{
const char* const VesselClasses[] = { "portal_vein", "hepatic_artery", "hepatic_vein" };

class Stage
{
public:
  Stage(DemoReport& report, const char* name)
    : Report(report)
    , Name(name)
    , StartMs(NowMs())
  {
    std::cerr << "demo: " << name << "\n";
  }
  ~Stage() { this->Report.StageSeconds.emplace_back(this->Name, (NowMs() - this->StartMs) / 1000.0); }

private:
  DemoReport& Report;
  std::string Name;
  double StartMs;
};

SceneRequest DemoSceneRequest(const DemoReport& report, double frameBudgetMs);

/// Each frame's level, for the self-test's comparison with the exact engine.
class LevelRecord : public FrameOutput
{
public:
  explicit LevelRecord(std::vector<DangerLevel>& levels)
    : Levels(levels)
  {
  }
  void OnFrame(const TrackedFrame& frame) override { this->Levels.push_back(frame.Level); }

private:
  std::vector<DangerLevel>& Levels;
};

/// The frames worth a picture (vp::KeyFrameFinder), as the demo's tracking logic sees them.
std::vector<KeyFrame> DemoKeyFrames(vtkVesselProximityLogic* logic, const std::vector<TrackedPose>& poses)
{
  KeyFrameFinder finder;
  TrackingSession session(logic);
  PoseListSource source(poses, "the demo trajectory");
  session.AddOutput(&finder);
  session.Run(source);
  return finder.GetKeyFrames();
}

void RenderKeyFrames(const ModuleServices& module, DemoReport& report, const std::vector<TrackedPose>& poses, const std::string& folder)
{
  VirtualDisplay display;
  if (!display.Ensure())
  {
    report.ScreenshotProblem = display.GetProblem();
    std::cerr << "demo: no screenshots: " << report.ScreenshotProblem << "\n";
    return;
  }
  // The logic the track stage ran (the z-buffer checked by the exact engine, the whole
  // instrument): the pictures say what the run found, and which engine set each level.
  vtkSmartPointer<vtkVesselProximityLogic> logic = module.CreateLogic();
  logic->OpenScene(DemoSceneRequest(report, 0.0));
  KeyFrameShotRequest request;
  request.Logic = logic;
  request.Liver = report.Surfaces.count("liver") ? report.Surfaces.at("liver").GetPointer() : nullptr;
  request.Poses = poses;
  request.Keys = DemoKeyFrames(logic, poses);
  request.Folder = folder;
  for (const KeyFrameScreenshots::Shot& shot : RenderKeyFrameShots(module, request))
  {
    double range[2];
    shot.Picture->GetScalarRange(range);
    report.ScreenshotContrast.push_back(range[1] - range[0]);
    // Where the run puts it.
    report.Screenshots.push_back(report.OutDir + "/screenshots" + shot.File.substr(shot.File.rfind('/')));
  }
}

/// The demo's vessels as built, in memory, each naming the file the models stage wrote.
std::vector<NamedMesh> DemoVessels(const DemoReport& report)
{
  std::vector<NamedMesh> vessels;
  for (const char* c : VesselClasses)
  {
    vessels.push_back({ c, report.OutDir + "/models/" + c + ".stl", report.Surfaces.at(c), std::nullopt });
  }
  return vessels;
}

/// The demo's scene: the z-buffer engine answers, the exact engine checks every frame (the exact
/// engine alone without a Vulkan device), the whole instrument measured.
SceneRequest DemoSceneRequest(const DemoReport& report, double frameBudgetMs)
{
  SceneRequest request;
  request.Vessels = DemoVessels(report);
  request.Engine.Method = "auto";
  request.CompareWithExact = true; // when the z-buffer answers
  request.Tracking.FrameBudgetMs = frameBudgetMs;
  return request;
}

/// Both engines on every frame: the z-buffer engine answers, the exact engine checks; the exact
/// engine alone without a Vulkan device.
void TrackDemo(const ModuleServices& module, DemoReport& report, double frameBudgetMs, bool live, RunFolder& run,
  const std::vector<FrameOutput*>& outputs)
{
  vtkSmartPointer<vtkVesselProximityLogic> logic = module.CreateLogic();
  const OpenedScene scene = logic->OpenScene(DemoSceneRequest(report, frameBudgetMs));
  report.Method = logic->GetCompareWithExact() ? "both" : "exact";
  if (!scene.EngineNote.empty())
  {
    report.MethodNote = "no Vulkan device, exact engine only: " + scene.EngineNote;
    std::cerr << "demo: " << report.MethodNote << "\n";
  }
  LevelRecord levels(report.FrameLevels);
  TrackingRecorder recorder(logic, scene.Vessels);
  recorder.AddOutput(&levels);
  for (FrameOutput* output : outputs)
  {
    recorder.AddOutput(output);
  }
  if (!live)
  {
    PoseListSource poses(report.Trajectory.Poses, report.PosesFile);
    if (recorder.Run(poses, run))
    {
      report.Summary = recorder.GetReport();
    }
    return;
  }
  // The loop an operating room has, on loopback: a tracker server streams the trajectory at its
  // own times; the live path reads it, computes each frame and sends the results back.
  const std::string device = "ScalpelToPatient";
  IgtlPoseStreamer tracker(0, device);
  IgtlLinkSettings settings;
  settings.ConnectPort = tracker.GetPort();
  settings.ToolName = device;
  settings.Reading = SettlePoseReading(PoseReading());
  IgtlLink link(settings);
  std::atomic<bool> stop{ false };
  std::atomic<double> doneMs{ 0.0 };
  std::thread streaming([&] {
    PoseListSource trajectory(report.Trajectory.Poses, report.PosesFile);
    tracker.Stream(trajectory, 1.0, 10.0, stop);
    doneMs = NowMs();
  });
  LivePoseSource poses(link, "the demo's tracker on 127.0.0.1:" + std::to_string(tracker.GetPort()), 200.0);
  // The stream ends a moment after the tracker's last pose (its messages still on their way).
  poses.SetEndCondition([&] { return doneMs > 0.0 && NowMs() - doneMs > 200.0; });
  LiveResultsOutput results(link, &poses);
  recorder.AddOutput(&results);
  recorder.SetReportAddition([&](nlohmann::ordered_json& doc) {
    doc["latency_ms"] = LiveLatencyJson(results.GetLatencyMs());
    doc["link"] = LiveLinkJson(link.GetCounts());
  });
  const bool ran = recorder.Run(poses, run);
  stop = true;
  streaming.join();
  if (ran)
  {
    report.Summary = recorder.GetReport();
    report.Frames = recorder.GetSummary().GetNumberOfFrames();
  }
}
} // namespace

vtkSmartPointer<vtkVesselProximityLogic> MakeDemoTipLogic(const ModuleServices& module, const DemoReport& report)
{
  SceneRequest request;
  request.Vessels = DemoVessels(report);
  request.ComputeSurfaceDistance = false;
  vtkSmartPointer<vtkVesselProximityLogic> logic = module.CreateLogic();
  logic->OpenScene(request);
  return logic;
}

/// The phantom's DICOM series, read back and modelled as any patient's; the report keeps the
/// surfaces, the vessels name their files where they will be, and the models the series.
void BuildDemoModels(DemoReport& report, RunFolder& run)
{
  const std::string staged = run.Folder("dicom");
  VesselModelSet set = BuildVesselModels(
    { staged }, VesselModelParameters(), [](const std::string& line, double) { std::cerr << "models: " << line << "\n"; });
  const auto retarget = [&](std::string& path) {
    path = path.rfind(staged, 0) == 0 ? report.DicomFolder + path.substr(staged.size()) : path;
  };
  std::for_each(set.Inputs.begin(), set.Inputs.end(), retarget);
  for (LabelStructures& structures : set.Imports)
  {
    std::for_each(structures.begin(), structures.end(), [&](LabelStructure& s) { retarget(s.Source); });
  }
  WriteVesselModelFiles(set, run.Folder("models"));
  for (const VesselClassModel& m : set.Models)
  {
    report.Surfaces[m.Name] = m.Surface;
  }
  for (const char* c : VesselClasses)
  {
    if (!report.Surfaces.count(c))
    {
      throw InputError(report.DicomFolder, std::string("no model was built for ") + c);
    }
  }
}

DemoReport RunDemoPipeline(const ModuleServices& module, const std::string& outDir, bool screenshots, double frameBudgetMs, bool live,
  const std::vector<FrameOutput*>& outputs)
{
  DemoReport report;
  report.OutDir = outDir;
  report.DicomFolder = outDir + "/dicom";
  RunFolder run(outDir, "summary.json");
  run.Begin();
  // Noted before the track stage writes summary.json, which lists every entry of the run.
  const std::string shots = screenshots ? run.Folder("screenshots") : std::string();
  const std::vector<std::pair<const char*, std::function<void()>>> stages = {
    { "phantom: liver labelmap with three vessel trees, written as DICOM series",
      [&] {
        report.Phantom = MakeLiverPhantom();
        WriteLiverPhantomDicom(report.Phantom, run.Folder("dicom"));
      } },
    { "models: DICOM series -> vessel surface models", [&] { BuildDemoModels(report, run); } },
    { "scalpel and trajectory",
      [&] {
        WriteDefaultScalpel(run.Folder("scalpel"));
        report.PosesFile = outDir + "/poses.csv";
        report.Trajectory = DesignDemoTrajectory(report.Phantom);
        WriteFileAtomically(run.File("poses.csv"), FormatPoseCsv(report.Trajectory.Poses));
        report.Frames = static_cast<int>(report.Trajectory.Poses.size());
      } },
    { live ? "track live: the trajectory over OpenIGTLink (loopback) through the live path and back"
           : "track: every frame through the z-buffer engine, checked by the exact engine",
      [&] { TrackDemo(module, report, frameBudgetMs, live, run, outputs); } },
    { "screenshots of the key frames",
      screenshots ? std::function<void()>([&] { RenderKeyFrames(module, report, report.Trajectory.Poses, shots); }) : nullptr },
  };
  for (const auto& [name, work] : stages)
  {
    if (RunFolder::SignalPending())
    {
      return report; // the run folder is let go, then the signal acts: the previous run stays
    }
    if (!work)
    {
      continue; // no screenshots asked for
    }
    Stage stage(report, name);
    work();
  }
  if (RunFolder::SignalPending())
  {
    return report;
  }
  run.Commit();
  return report;
}
} // namespace vp
