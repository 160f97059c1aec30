// vesselproximity selftest: the module self-test, as Slicer modules carry one. Runs the demo's
// pipeline end to end and asserts what must hold of its results.
#include "vpArguments.h"
#include "vpCommands.h"
#include "vpDangerLevels.h"
#include "vpDemoPipeline.h"
#include "vpDemoTrajectory.h"
#include "vpInputError.h"
#include "vpPoseFile.h"
#include "vpTrackingSession.h"
#include "vtkVesselProximityLogic.h"

#include <vtkCellArray.h>
#include <vtkImageData.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

namespace vp
{
namespace
{
class Checks
{
public:
  void Check(const std::string& name, bool ok, const std::string& detail)
  {
    std::printf("%s  %s: %s\n", ok ? "PASS" : "FAIL", name.c_str(), detail.c_str());
    std::fflush(stdout);
    this->Failed += ok ? 0 : 1;
  }
  void Skip(const std::string& name, const std::string& why) { std::printf("SKIP  %s: %s\n", name.c_str(), why.c_str()); }
  int Failed = 0;
};

/// Edges used by other than exactly two triangles: 0 for a closed, manifold surface.
long long OpenEdges(vtkPolyData* mesh)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> uses;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = mesh->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 0; k < n; ++k)
    {
      vtkIdType a = ids[k], b = ids[(k + 1) % n];
      ++uses[{ std::min(a, b), std::max(a, b) }];
    }
  }
  long long open = 0;
  for (const auto& [edge, count] : uses)
  {
    open += count != 2 ? 1 : 0;
  }
  return open;
}

std::string Text(double value)
{
  return FixedText(value, "%.3f");
}

/// Each frame's level and each change of it, as a run's output hears them.
class LevelRecord : public FrameOutput
{
public:
  std::vector<DangerLevel> Levels, Changes;
  void OnLevelChange(const DangerLevelChange& change) override { this->Changes.push_back(change.To); }
  void OnFrame(const TrackedFrame& frame) override { this->Levels.push_back(frame.Level); }
};

/// The exact engine's level at every frame and its changes, computed here, independently of the
/// track command's run.
std::vector<DangerLevel> ExactLevels(const ModuleServices& module, const DemoReport& report, std::vector<DangerLevel>& changes)
{
  vtkSmartPointer<vtkVesselProximityLogic> logic = MakeDemoTipLogic(module, report);
  LevelRecord record;
  TrackingSession session(logic);
  session.AddOutput(&record);
  PoseListSource poses(report.Trajectory.Poses, report.PosesFile); // the poses the track stage ran
  session.Run(poses);
  changes = record.Changes;
  return record.Levels;
}

std::string Names(const std::vector<DangerLevel>& levels)
{
  std::string out;
  for (DangerLevel l : levels)
  {
    out += (out.empty() ? "" : " ") + std::string(DangerLevelName(l));
  }
  return out;
}

/// Every model as built (and written): closed, and more than a token of triangles.
void CheckModels(const DemoReport& report, Checks& checks)
{
  for (const auto& [name, surface] : report.Surfaces)
  {
    const long long open = OpenEdges(surface);
    checks.Check("model " + name, open == 0 && surface->GetNumberOfPolys() > 100,
      std::to_string(surface->GetNumberOfPolys()) + " triangles, " + std::to_string(open) + " open edges");
  }
}

/// The level changes of the exact engine on the built models against those of the analytic design
/// the phantom was drawn from: the surfaces built from its voxels must tell the same story.
void CheckLevelOrder(const DemoReport& report, const std::vector<DangerLevel>& changes, Checks& checks)
{
  std::vector<DangerLevel> expected;
  DangerLevel previous = DangerLevel::Safe;
  for (const TrackedPose& pose : report.Trajectory.Poses)
  {
    const auto& m = pose.ModelToWorld; // the tip is the model's origin
    const DangerLevel level = AnalyticProximityAt(report.Phantom, { m[3], m[7], m[11] }).Level;
    if (level != previous)
    {
      expected.push_back(level);
      previous = level;
    }
  }
  checks.Check("level order", changes == expected && expected.size() >= 8,
    "exact engine on the built models [" + Names(changes) + "], analytic design [" + Names(expected) + "]");
}

/// The z-buffer's answers within their bound of the exact ones, and the contract's consequence for
/// the surgeon: its level (frames.csv) never below the exact level.
void CheckEngines(const DemoReport& report, const nlohmann::json& summary, const std::vector<DangerLevel>& exactLevels,
  Checks& checks)
{
  if (report.Method != "both")
  {
    checks.Skip("engines agree", report.MethodNote);
    return;
  }
  const auto& comparison = summary.at("comparison");
  const double bound = summary.at("error_bound_mm").get<double>();
  const double worst = comparison.at("max_abs_difference_mm").get<double>();
  checks.Check("engines agree", comparison.at("outside_bound").get<int>() == 0 && worst <= bound + 1e-9,
    "largest |z-buffer - exact| " + Text(worst) + " mm within the bound " + Text(bound) + " mm, " +
      std::to_string(comparison.at("outside_bound").get<int>()) + " answers outside it");
  int understated = 0, overstated = 0;
  for (std::size_t i = 0; i < report.FrameLevels.size() && i < exactLevels.size(); ++i)
  {
    const int z = static_cast<int>(report.FrameLevels[i]), e = static_cast<int>(exactLevels[i]);
    understated += z < e ? 1 : 0;
    overstated += z > e ? 1 : 0;
  }
  checks.Check("danger never understated", understated == 0,
    std::to_string(understated) + " frames below the exact level, " + std::to_string(overstated) +
      " above it (allowed: the bound is subtracted)");
}

void CheckTimeAtEveryLevel(const nlohmann::json& summary, Checks& checks)
{
  const auto& time = summary.at("time_in_level");
  std::string times;
  bool everyLevel = true;
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    const double s = time.at(DangerLevelName(static_cast<DangerLevel>(l))).at("time_s").get<double>();
    everyLevel = everyLevel && s > 0;
    times += std::string(times.empty() ? "" : ", ") + DangerLevelName(static_cast<DangerLevel>(l)) + " " + Text(s) + " s";
  }
  checks.Check("time at every level", everyLevel, times);
}

/// Every file and folder summary.json lists is in the run's folder, not empty.
void CheckFilesListed(const DemoReport& report, Checks& checks)
{
  int missing = 0;
  std::string first;
  for (const auto& entry : report.Summary.at("files"))
  {
    const std::filesystem::path path = std::filesystem::path(report.OutDir) / entry.get<std::string>();
    std::error_code ec;
    const bool there = std::filesystem::is_directory(path, ec) ? !std::filesystem::is_empty(path, ec)
                                                                 : std::filesystem::file_size(path, ec) > 0 && !ec;
    missing += there ? 0 : 1;
    first = first.empty() && !there ? path.string() : first;
  }
  checks.Check("files", missing == 0,
    std::to_string(report.Summary.at("files").size()) + " listed in summary.json" + (missing ? ", missing: " + first : ", all there"));
}

/// distance.png is there, and no screenshot is blank.
void CheckPictures(const DemoReport& report, bool screenshotsWanted, Checks& checks)
{
  std::error_code ec;
  const auto plotBytes = std::filesystem::file_size(report.OutDir + "/distance.png", ec);
  checks.Check("distance.png", !ec && plotBytes > 10000, ec ? ec.message() : std::to_string(plotBytes) + " bytes");
  if (screenshotsWanted && report.Screenshots.empty())
  {
    checks.Check("screenshots", false, report.ScreenshotProblem);
    return;
  }
  if (report.Screenshots.empty())
  {
    return;
  }
  int blank = 0;
  for (double contrast : report.ScreenshotContrast)
  {
    blank += contrast < 50 ? 1 : 0;
  }
  checks.Check("screenshots", blank == 0,
    std::to_string(report.Screenshots.size()) + " key frames, " + std::to_string(blank) + " blank");
}
} // namespace

cli::ModuleDescription DescribeSelfTestCommand()
{
  return cli::ModuleDescription::Subcommand("vesselproximity selftest", "the module self-test: the demo's pipeline end to end with assertions",
    "Runs the demo's pipeline and checks it: models exist and are closed, both engines agree within the error bound, "
    "the z-buffer never understates the danger, the danger levels change in the expected order, the reports and "
    "screenshots are there. Prints PASS or FAIL per check; exit 0 when all pass.",
    { { "Options", "",
      { OutputFolderOption("Where the run goes (default: a temporary folder, removed on success)."),
        Switch("no-screenshots", "Skip the screenshots.") } } });
}

namespace
{
/// The system's temporary folder, as TMPDIR names it; a TMPDIR that is no folder is said so.
std::string TemporaryFolder()
{
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::temp_directory_path(ec);
  if (ec)
  {
    const char* tmpdir = std::getenv("TMPDIR");
    throw InputError(std::string("TMPDIR ") + (tmpdir ? tmpdir : ""),
      "is not a folder (" + ec.message() + "): set TMPDIR to one, or give -o");
  }
  return folder.string();
}
} // namespace

int RunSelfTestCommand(const cli::ParsedArguments& args, const ModuleServices& module)
{
  const bool temporary = !args.IsSet("output");
  const std::string outDir = temporary
    ? (std::filesystem::path(TemporaryFolder()) / ("vesselproximity-selftest-" + std::to_string(getpid()))).string()
    : args.GetString("output");
  const DemoReport report = RunDemoPipeline(module, outDir, !args.GetBoolean("noScreenshots"));
  // The checks read what the run returned, typed; of its files they check only that each is there.
  const nlohmann::json summary(report.Summary);
  PrintDemoTable(report);
  std::printf("\nself-test:\n");
  Checks checks;
  CheckModels(report, checks);
  CheckFilesListed(report, checks);
  const int frames = summary.at("frames").get<int>();
  checks.Check("frames", frames == report.Frames && report.FrameLevels.size() == static_cast<std::size_t>(frames),
    std::to_string(frames) + " in summary.json, " + std::to_string(report.FrameLevels.size()) + " computed, " +
      std::to_string(report.Frames) + " poses");
  std::vector<DangerLevel> changes;
  const std::vector<DangerLevel> exactLevels = ExactLevels(module, report, changes);
  CheckLevelOrder(report, changes, checks);
  CheckEngines(report, summary, exactLevels, checks);
  CheckTimeAtEveryLevel(summary, checks);
  CheckPictures(report, !args.GetBoolean("noScreenshots"), checks);

  std::printf("%s: %d check(s) failed\n", checks.Failed ? "SELF-TEST FAILED" : "self-test passed", checks.Failed);
  std::error_code ec;
  if (temporary && !checks.Failed)
  {
    std::filesystem::remove_all(outDir, ec);
  }
  else
  {
    std::printf("outputs kept in %s\n", outDir.c_str());
  }
  return checks.Failed ? 1 : 0;
}
} // namespace vp
