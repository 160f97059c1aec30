#include "vpDemoPipeline.h"

#include "vpCommandSupport.h"
#include "vpDangerLevels.h"
#include "vpDistanceEngineSettings.h"
#include "vpDefaultScalpel.h"
#include "vpDemoTrajectory.h"
#include "vpInputError.h"
#include "vpLiverPhantom.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpTrackingSession.h"
#include "vpVesselModelSet.h"
#include "vpVirtualDisplay.h"
#include "vpVulkanContext.h"
#include "vtkScalpelModel.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselMeshWriter.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselProximityView.h"

#include <vtkCamera.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
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

/// The frames worth a picture, as the exact engine sees them: the first, the first at each
/// level on the way in, the closest approach to each vessel class, and the last.
std::vector<std::pair<int, std::string>> KeyFrames(vtkVesselProximityLogic* logic, const std::vector<TrackedPose>& poses)
{
  std::map<int, std::string> keys{ { 0, "start" }, { static_cast<int>(poses.size()) - 1, "end" } };
  std::set<DangerLevel> seen{ DangerLevel::Safe };
  std::map<std::string, std::pair<double, int>> closest; // signed: inside is negative
  logic->ResetTracking();
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    const TrackedFrame& f = logic->ProcessPose(poses[i]);
    if (seen.insert(f.Level).second)
    {
      keys.emplace(static_cast<int>(i), DangerLevelName(f.Level));
    }
    for (const ClassProximity& c : f.Proximity.Classes)
    {
      const double signedMm = c.Inside && *c.Inside ? -c.DistanceMm : c.DistanceMm;
      auto it = closest.find(c.ClassName);
      if (c.InRange && (it == closest.end() || signedMm < it->second.first))
      {
        closest[c.ClassName] = { signedMm, static_cast<int>(i) };
      }
    }
  }
  for (const auto& [name, entry] : closest)
  {
    keys.emplace(entry.second, "closest_" + name);
  }
  return { keys.begin(), keys.end() };
}

void RenderKeyFrames(DemoReport& report, const std::vector<TrackedPose>& poses)
{
  VirtualDisplay display;
  if (!display.Ensure())
  {
    report.ScreenshotProblem = display.GetProblem();
    std::cerr << "demo: no screenshots: " << report.ScreenshotProblem << "\n";
    return;
  }
  vtkSmartPointer<vtkVesselProximityLogic> logic = MakeDemoTipLogic(report);
  vtkNew<vtkVesselProximityView> view;
  view->SetOffScreen(true);
  view->SetSizePx(1280, 800);
  view->SetLogic(logic);
  if (report.ModelFiles.count("liver"))
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(report.ModelFiles.at("liver"));
    reader->Read();
    view->SetLiverSurface(reader->GetOutput());
  }
  // From anterior, turned a little to the patient's right and down from above: the scalpel
  // comes in at an angle, not end-on.
  vtkCamera* camera = view->GetRenderer()->GetActiveCamera();
  camera->Azimuth(-35);
  camera->Elevation(25);
  camera->OrthogonalizeViewUp();
  view->GetRenderer()->ResetCameraClippingRange();
  view->SetPoses(poses);

  const std::string folder = report.OutDir + "/screenshots";
  CreateOutputFolder(folder);
  std::size_t next = 0;
  const auto keys = KeyFrames(logic, poses);
  view->ShowPose(0); // back to the start: a new session, the plot cleared
  for (int i = 0; i < static_cast<int>(poses.size()) && next < keys.size(); ++i)
  {
    if (i > 0)
    {
      view->ShowPose(i);
    }
    if (i == keys[next].first)
    {
      char name[96];
      std::snprintf(name, sizeof(name), "/frame%04d_%s.png", i, keys[next].second.c_str());
      report.Screenshots.push_back(view->SaveScreenshot(folder + name));
      ++next;
    }
  }
}

/// Both engines on every frame: the z-buffer engine answers, the exact engine checks; the exact
/// engine alone without a Vulkan device.
void TrackDemo(DemoReport& report, const std::vector<NamedMesh>& vessels, double frameBudgetMs)
{
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  DistanceEngineSettings settings;
  settings.Method = "zbuffer";
  report.Method = "both";
  try
  {
    logic->SetDistanceEngine(MakeDistanceEngine(settings));
  }
  catch (const DeviceError& e)
  {
    report.Method = "exact";
    report.MethodNote = std::string("no Vulkan device, exact engine only: ") + e.what();
    std::cerr << "demo: " << report.MethodNote << "\n";
    settings.Method = "exact";
    logic->SetDistanceEngine(MakeDistanceEngine(settings));
  }
  logic->SetCompareWithExact(report.Method == "both");
  logic->SetScalpel(MakeDefaultScalpel());
  for (const NamedMesh& m : vessels)
  {
    logic->AddVessel(m.ClassName, m.Mesh);
  }
  logic->Build();
  logic->GetParameters()->SetFrameBudgetMs(frameBudgetMs);
  logic->GetTrackingLogic()->ValidateSettings();
  RunFolder run(report.OutDir, "summary.json");
  TrackingSession session(logic, vessels);
  PoseListSource poses(report.Trajectory.Poses, report.PosesFile);
  if (!session.Run(poses, run))
  {
    throw InputError(report.OutDir, "interrupted");
  }
  report.Summary = session.GetReport();
}
} // namespace

vtkSmartPointer<vtkVesselProximityLogic> MakeDemoTipLogic(const DemoReport& report)
{
  auto logic = vtkSmartPointer<vtkVesselProximityLogic>::New();
  for (const char* c : VesselClasses)
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(report.ModelFiles.at(c));
    reader->Read();
    logic->AddVessel(c, reader->GetOutput());
  }
  logic->SetScalpel(MakeDefaultScalpel());
  logic->SetComputeSurfaceDistance(false);
  return logic;
}

DemoReport RunDemoPipeline(const std::string& outDir, bool screenshots, double frameBudgetMs)
{
  DemoReport report;
  report.OutDir = outDir;
  CreateOutputFolder(outDir);
  report.DicomFolder = outDir + "/dicom";
  LiverPhantom& phantom = report.Phantom;
  {
    Stage stage(report, "phantom: liver labelmap with three vessel trees, written as DICOM series");
    phantom = MakeLiverPhantom();
    WriteLiverPhantomDicom(phantom, report.DicomFolder);
  }
  std::vector<NamedMesh> vessels;
  {
    Stage stage(report, "models: DICOM series -> vessel surface models");
    RunFolder run(outDir + "/models", "models.json");
    const VesselModelSet set = BuildVesselModels(
      { report.DicomFolder }, VesselModelParameters(), [](const std::string& line) { std::cerr << "models: " << line << "\n"; });
    WriteVesselModels(set, run);
    for (const VesselClassModel& m : set.Models)
    {
      report.ModelFiles[m.ClassName] = run.Target() + "/" + m.ClassName + ".stl";
    }
    for (const char* c : VesselClasses)
    {
      const auto model = std::find_if(
        set.Models.begin(), set.Models.end(), [&](const VesselClassModel& m) { return m.ClassName == c; });
      if (model == set.Models.end())
      {
        throw InputError(report.DicomFolder, std::string("no model was built for ") + c);
      }
      vessels.push_back({ c, report.ModelFiles[c], model->Surface, std::nullopt });
    }
  }
  {
    Stage stage(report, "scalpel and trajectory");
    report.ScalpelFile = WriteDefaultScalpel(outDir + "/scalpel");
    report.PosesFile = outDir + "/poses.csv";
    report.Trajectory = DesignDemoTrajectory(phantom);
    WriteFileAtomically(report.PosesFile, FormatPoseCsv(report.Trajectory.Poses));
    report.Frames = static_cast<int>(report.Trajectory.Poses.size());
  }
  {
    Stage stage(report, "track: every frame through the z-buffer engine, checked by the exact engine");
    TrackDemo(report, vessels, frameBudgetMs);
  }
  if (screenshots)
  {
    Stage stage(report, "screenshots of the key frames");
    RenderKeyFrames(report, report.Trajectory.Poses);
  }
  return report;
}
} // namespace vp
