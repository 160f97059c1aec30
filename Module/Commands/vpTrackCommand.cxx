// vesselproximity track: a recorded stream of scalpel poses replayed against the vessels, with the
// per-frame record (frames.csv), the run's summary (summary.json) and its plot (distance.png).
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpDangerLevels.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpTrackingOptions.h"
#include "vpTrackingSession.h"
#include "vtkScalpelPenetration.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"

#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{
const char* Usage =
  "usage: vesselproximity track --vessels CLASS=FILE[,CLASS=FILE...] --scalpel FILE.stl --poses FILE\n"
  "         [--tip X,Y,Z] [--axis X,Y,Z] [--method exact|zbuffer|both] [--danger-mm C,W,D]\n"
  "         [--no-surface] [--frame-budget-ms MS] [--hysteresis-mm MM] [--repair] [engine options] -o OUTDIR\n"
  "  Replays tracked scalpel poses (model-to-world; CSV `time,m00..m33` or `time,x,y,z,qw,qx,qy,qz`,\n"
  "  or JSON) and writes OUTDIR/frames.csv (one row per pose), summary.json and distance.png.\n"
  "  The tip and axis (model coordinates): --tip/--axis, else FILE.json beside the model\n"
  "  ({\"tip_mm\": [x,y,z], \"axis\": [x,y,z]}), else found automatically (reported).\n"
  "  --danger-mm: caution, warning and danger thresholds (default 10,5,2 mm); a tip inside a\n"
  "    vessel is a breach. The level uses distance minus the engine's error bound.\n"
  "  --hysteresis-mm: a level is entered at once but left only when the distance exceeds its\n"
  "    threshold by this much (default 0.3; 0: none), so tracking noise does not flicker it.\n"
  "  --repair: merge coincident points, drop duplicated triangles and fins, fill holes up to\n"
  "    30 mm and make the winding consistent before building (no point moves), saying per class\n"
  "    on stderr what changed; an open surface's inside is otherwise a vote of five rays.\n"
  "  --no-surface: skip the whole-instrument distance (the closest approach of any point of the\n"
  "    scalpel surface, computed exactly beside the tip's).\n"
  "  --frame-budget-ms: the time one frame may take (default 16.7, 60 Hz; 0: no budget); the\n"
  "    frames over it are counted in summary.json and on the terminal.\n";

/// The module logic over the vessels and the scalpel, built: the engine, and beside it the exact
/// engine when --method both's check or the whole surface needs one.
void BuildLogic(vtkVesselProximityLogic* proximity, const std::vector<NamedMesh>& meshes, vtkScalpelModel* scalpel)
{
  proximity->SetScalpel(scalpel);
  for (const auto& m : meshes)
  {
    proximity->AddVessel(m.ClassName, m.Mesh);
  }
  proximity->Build();
  proximity->GetTrackingLogic()->ValidateSettings();
}

Arguments ParseTrackArguments(const std::vector<std::string>& argv)
{
  std::set<std::string> options = EngineValueOptions();
  options.insert({ "--vessels", "--scalpel", "--poses", "--tip", "--axis", "--danger-mm", "--frame-budget-ms", "--hysteresis-mm", "-o" });
  Arguments args(argv, options, { "--no-surface", "--repair" });
  if (!args.Positional().empty())
  {
    throw InputError(args.Positional()[0], "unexpected argument (see vesselproximity track --help)");
  }
  for (const char* required : { "--vessels", "--scalpel", "--poses", "-o" })
  {
    if (!args.Has(required))
    {
      throw InputError(required, "is required (see vesselproximity track --help)");
    }
  }
  const std::string method = args.Get("--method", "exact");
  if (method != "exact" && method != "zbuffer" && method != "both")
  {
    throw InputError("--method", "expected exact, zbuffer or both for tracking, got '" + method + "'");
  }
  return args;
}

/// Said once everything is built and checked: a line before a refusal would make its one line two.
void ReportBuiltScene(vtkVesselProximityLogic* proximity, const std::vector<NamedMesh>& meshes, const std::string& scalpelFile)
{
  std::cerr << "track: " << proximity->GetScalpel()->GetTipSource() << "\n";
  ReportSurfaceDefects("track", proximity->GetDistanceEngine(), meshes);
  vtkScalpelPenetration* penetration = proximity->GetTrackingLogic()->GetPenetration();
  if (penetration && !penetration->IsToolClosed())
  {
    std::cerr << "track: " << scalpelFile
              << ": the surface is not closed, so the instrument's penetration depth and volume cannot be known (left empty)\n";
  }
}

void PrintSummary(const TrackingSession& session, vtkVesselProximityLogic* proximity, const std::string& outDir)
{
  const TrackingSummary& summary = session.GetSummary();
  vtkVesselDistanceEngine* engine = proximity->GetDistanceEngine();
  const bool surface = proximity->GetComputeSurfaceDistance();
  const double budgetMs = proximity->GetTrackingLogic()->GetFrameBudgetMs();
  const std::vector<std::string>& classes = summary.GetClassNames();
  const std::size_t frameCount = static_cast<std::size_t>(summary.GetNumberOfFrames());
  std::printf("%zu frames over %.2f s, method %s on %s, error bound %.3f mm\n", frameCount, summary.GetDurationS(),
    engine->GetMethodName(), engine->GetDeviceDescription().c_str(), engine->GetErrorBoundMm());
  std::printf("  %-16s %16s %10s %20s\n", "class", "tip minimum mm", "at time", surface ? "whole surface mm" : "");
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const ClassMinimum& m = summary.GetTipMinimum()[c];
    const ClassMinimum& s = summary.GetSurfaceMinimum()[c];
    std::printf("  %-16s %16s %10s %20s\n", classes[c].c_str(),
      m.Seen ? (FixedText(m.DistanceMm, "%.3f") + (m.Inside ? " inside" : "")).c_str() : "out of range",
      m.Seen ? FixedText(m.TimeS, "%.3f").c_str() : "", surface ? (s.Seen ? FixedText(s.DistanceMm, "%.3f").c_str() : "out of range") : "");
  }
  std::printf("  time at each level:");
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    std::printf(" %s %.2f s", DangerLevelName(static_cast<DangerLevel>(l)), summary.GetTimeInLevelS()[l]);
  }
  std::printf("\n  %zu level change(s), worst level %s\n", summary.GetChanges().size(), DangerLevelName(summary.GetWorstLevel()));
  std::printf("  frame median %.4f ms, p95 %.4f ms, max %.4f ms; %s\n", summary.GetFrameMsQuantile(0.5),
    summary.GetFrameMsQuantile(0.95), summary.GetFrameMsQuantile(1.0),
    budgetMs > 0 ? (std::to_string(summary.GetFramesOverBudget()) + " of " + std::to_string(frameCount) +
                     " frames over the " + FixedText(budgetMs, "%g") + " ms budget")
                     .c_str()
                 : "no frame budget");
  if (const auto& check = session.GetComparison())
  {
    std::printf("  against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n",
      check->MaxAbsDifferenceMm, check->OutsideBound);
  }
  std::printf("wrote %s/frames.csv, summary.json, distance.png\n", outDir.c_str());
}
} // namespace

int RunTrackCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage << EngineOptionsUsage({ "exact", "zbuffer", "both" });
    return 0;
  }
  const Arguments args = ParseTrackArguments(argv);
  const std::string method = args.Get("--method", "exact");
  const ScalpelTipDefinition tip = ParseTipDefinition(args);
  const std::string outDir = args.Get("-o");
  RunFolder run(outDir, "summary.json");

  // Everything that can be refused is read before any computing: poses first, they are cheap.
  // They are read through once to be checked and counted, and again, a pose at a time, as the
  // frames are computed: an hour of tracking never has to fit in memory.
  const double start = NowMs();
  const std::string posesFile = args.Get("--poses");
  const std::size_t poseCount = PoseStream::CountPoses(posesFile);
  vtkSmartPointer<vtkVesselProximityLogic> proximity = ConfigureTrackingLogic(args, method);
  auto meshes = LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels"));
  if (args.Has("--repair"))
  {
    RepairVesselMeshes(meshes);
  }
  auto scalpel = LoadScalpel(args.Get("--scalpel"), tip);
  BuildLogic(proximity, meshes, scalpel);
  ReportBuiltScene(proximity, meshes, args.Get("--scalpel"));
  TrackingSession session(proximity, meshes);
  session.SetLoadAndBuildMs(NowMs() - start);
  session.SetProgress([](std::size_t done, std::size_t expected) {
    std::fprintf(stderr, "track: frame %zu of %zu (%.0f%%)\n", done, expected, 100.0 * done / expected);
  });
  PoseStream poses(posesFile, poseCount);
  if (!session.Run(poses, run))
  {
    return 1; // the RunFolder removes what was written, then the signal acts
  }
  run.Commit(); // the folder holds this run whole, or the previous one as it was
  if (session.GetComparison() && session.GetComparison()->OutsideBound > 0)
  {
    std::cerr << "vesselproximity: warning: " << session.GetComparison()->OutsideBound
              << " answer(s) of the z-buffer engine outside its error bound of "
              << proximity->GetDistanceEngine()->GetErrorBoundMm() << " mm\n";
  }
  PrintSummary(session, proximity, outDir);
  return 0;
}
} // namespace vp
