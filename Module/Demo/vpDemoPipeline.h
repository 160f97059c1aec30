#ifndef vpDemoPipeline_h
#define vpDemoPipeline_h

#include "vpDangerLevels.h"
#include "vpFrameOutput.h"
#include "vpModuleServices.h"
#include "vpDemoTrajectory.h"

#include "vtkVesselProximityLogic.h"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// What the demo produced, for its terminal table and for the self-test's assertions.
struct DemoReport
{
  std::string OutDir;
  std::vector<std::pair<std::string, double>> StageSeconds; ///< in the order they ran
  std::string DicomFolder;                                  ///< one series per structure
  std::map<std::string, vtkSmartPointer<vtkPolyData>> Surfaces; ///< class -> the model as built
  std::string PosesFile;
  LiverPhantom Phantom;     ///< as generated (its analytic centrelines included)
  DemoTrajectory Trajectory; ///< the designed path and its key points
  std::string Method; ///< "both" (z-buffer checked by exact) or "exact" without a Vulkan device
  std::string MethodNote;
  int Frames = 0;
  /// The level of every frame the track stage computed, as its frames.csv records it (heard from
  /// the tracking logic's FrameProcessedEvent, so the self-test need not read the file back).
  std::vector<DangerLevel> FrameLevels;
  nlohmann::ordered_json Summary; ///< the track stage's summary.json
  std::vector<std::string> Screenshots;
  /// Per screenshot, the spread of its pixel values (0: a blank picture).
  std::vector<double> ScreenshotContrast;
  std::string ScreenshotProblem; ///< why there are none, when there are none
};

/// The demo's pipeline, end to end, into outDir: the procedural liver phantom written as DICOM
/// series; vessel models built from those series (vp::BuildVesselModels, into models/); the
/// built-in CUSA handpiece; the demo trajectory, also written as a pose file; a tracking session
/// with both engines on every frame (frames.csv, summary.json, distance.png); screenshots of the key frames rendered
/// off-screen (a virtual display is started when there is none). Progress goes to stderr. Throws vp::InputError when something cannot be written.
/// frameBudgetMs goes to the track stage (--frame-budget-ms). live: the track stage takes the
/// trajectory from a tracker server on loopback, over OpenIGTLink, through the live path, and
/// sends the results back (its summary adds the latency). The module creates the logic of every
/// stage and the overlays of the screenshots.
DemoReport RunDemoPipeline(const ModuleServices& module, const std::string& outDir, bool screenshots,
  double frameBudgetMs = TrackingSettings().FrameBudgetMs, bool live = false, const std::vector<FrameOutput*>& outputs = {});

/// The module's logic over the demo's built vessel models and scalpel, with the exact engine and
/// the tip only (the whole surface off): the levels the self-test checks against the design's.
vtkSmartPointer<vtkVesselProximityLogic> MakeDemoTipLogic(const ModuleServices& module, const DemoReport& report);

/// The demo's terminal table: stage times, each class's closest approach, the level changes,
/// the engines' agreement and where the outputs are.
void PrintDemoTable(const DemoReport& report);
} // namespace vp

#endif
