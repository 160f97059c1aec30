// vesselproximity track: a recorded stream of scalpel poses replayed against the vessels, with the
// per-frame record (frames.csv), the run's summary (summary.json) and its plot (distance.png).
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpDangerBands.h"
#include "vpDangerLevels.h"
#include "vpDistancePlotRecorder.h"
#include "vpFramesCsv.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpScalpelLoader.h"
#include "vpTrackingOptions.h"
#include "vpTrackingSummary.h"
#include "vtkScalpelTrackingLogic.h"
#include "vtkVesselProximityLogic.h"
#include "vtkVesselMeshWriter.h"

#include <vtkCallbackCommand.h>
#include <vtkNew.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sys/resource.h>
#include <filesystem>
#include <iostream>
#include <limits>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

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

Json MinimumJson(const ClassMinimum& m)
{
  if (!m.Seen)
  {
    return nullptr;
  }
  return { { "distance_mm", m.DistanceMm }, { "error_bound_mm", m.ErrorBoundMm }, { "inside", m.Inside }, { "frame", m.Frame },
    { "time", m.TimeS }, { "point", { m.PointMm[0], m.PointMm[1], m.PointMm[2] } } };
}

Json SummaryJson(const TrackingSummary& s, vtkScalpelTrackingLogic* logic, vtkVesselDistanceEngine* engine,
  const std::vector<NamedMesh>& meshes, const std::string& posesFile, bool surface, const Json& comparison)
{
  Json out;
  out["poses"] = posesFile;
  out["frames"] = s.GetNumberOfFrames();
  out["duration_s"] = s.GetDurationS();
  out["method"] = engine->GetMethodName();
  out["device"] = engine->GetDeviceDescription();
  out["range_mm"] = engine->GetRangeMm();
  out["error_bound_mm"] = engine->GetErrorBoundMm();
  out["surfaces"] = SurfacesJson(engine, meshes);
  vtkScalpelModel* scalpel = logic->GetScalpel();
  out["scalpel"] = { { "tip_mm", { scalpel->GetTipMm()[0], scalpel->GetTipMm()[1], scalpel->GetTipMm()[2] } },
    { "axis", { scalpel->GetAxis()[0], scalpel->GetAxis()[1], scalpel->GetAxis()[2] } },
    { "tip_source", scalpel->GetTipSource() } };
  const DangerThresholds& t = logic->GetDangerThresholds();
  out["danger_thresholds_mm"] = { { "caution", t.CautionMm }, { "warning", t.WarningMm }, { "danger", t.DangerMm } };
  out["hysteresis_mm"] = logic->GetHysteresisMm();
  Json classes = Json::object();
  for (std::size_t c = 0; c < s.GetClassNames().size(); ++c)
  {
    Json entry;
    entry["tip_minimum"] = MinimumJson(s.GetTipMinimum()[c]);
    entry["frames_inside_uncertain"] = s.GetFramesInsideUncertain()[c];
    if (surface)
    {
      entry["surface_minimum"] = MinimumJson(s.GetSurfaceMinimum()[c]);
      if (c < s.GetPenetrationMaximum().size())
      {
        const ClassPenetration& p = s.GetPenetrationMaximum()[c];
        entry["penetration_maximum"] = !p.Known ? Json(nullptr)
                                                : Json{ { "depth_mm", p.DepthMm }, { "depth_bound_mm", p.DepthBoundMm },
                                                    { "depth_frame", p.DepthFrame }, { "volume_mm3", p.VolumeMm3 },
                                                    { "volume_bound_mm3", p.VolumeBoundMm3 }, { "volume_frame", p.VolumeFrame },
                                                    { "frames_inside", p.FramesInside } };
      }
    }
    classes[s.GetClassNames()[c]] = entry;
  }
  out["classes"] = classes;
  Json levels = Json::object();
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    levels[DangerLevelName(static_cast<DangerLevel>(l))] = { { "time_s", s.GetTimeInLevelS()[l] },
      { "frames", s.GetFramesInLevel()[l] } };
  }
  out["time_in_level"] = levels;
  out["worst_level"] = DangerLevelName(s.GetWorstLevel());
  Json events = Json::array();
  for (const DangerLevelChange& e : s.GetChanges())
  {
    events.push_back({ { "frame", e.Frame }, { "time", e.TimeS }, { "from", DangerLevelName(e.From) },
      { "to", DangerLevelName(e.To) }, { "class", e.ClassName.empty() ? Json(nullptr) : Json(e.ClassName) },
      { "distance_mm", e.ClassName.empty() ? Json(nullptr) : Json(e.DistanceMm) } });
  }
  out["level_changes"] = events;
  out["frame_ms"] = { { "median", s.GetFrameMsQuantile(0.5) }, { "p95", s.GetFrameMsQuantile(0.95) },
    { "max", s.GetFrameMsQuantile(1.0) }, { "budget", logic->GetFrameBudgetMs() } };
  out["frames_over_budget"] = s.GetFramesOverBudget();
  out["timing_ms"] = { { "frame_median", s.GetFrameMsQuantile(0.5) }, { "frame_p95", s.GetFrameMsQuantile(0.95) },
    { "frame_max", s.GetFrameMsQuantile(1.0) } };
  if (!comparison.is_null())
  {
    out["comparison"] = comparison;
  }
  return out;
}

} // namespace

int RunTrackCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage << EngineOptionsUsage({ "exact", "zbuffer", "both" });
    return 0;
  }
  std::set<std::string> options = EngineValueOptions();
  options.insert({ "--vessels", "--scalpel", "--poses", "--tip", "--axis", "--danger-mm", "--frame-budget-ms", "--hysteresis-mm", "-o" });
  const Arguments args(argv, options, { "--no-surface", "--repair" });
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
  const DangerThresholds thresholds = ParseDangerThresholds(args);
  const ScalpelTipDefinition tip = ParseTipDefinition(args);
  const double budgetMs = ParseFrameBudgetMs(args);
  const double hysteresisMm = ParseHysteresisMm(args);
  const bool surface = !args.Has("--no-surface");
  const std::string outDir = args.Get("-o");
  RunFolder run(outDir, "summary.json");

  // Everything that can be refused is read before any computing: poses first, they are cheap.
  // They are read through once to be checked and counted, and again, a pose at a time, as the
  // frames are computed: an hour of tracking never has to fit in memory.
  const double start = NowMs();
  const std::string posesFile = args.Get("--poses");
  std::size_t poseCount = 0;
  {
    PoseStream check(posesFile);
    for (TrackedPose pose; check.Next(pose);)
    {
      ++poseCount;
    }
  }
  auto engine = MakeDistanceEngine(method, args);
  auto meshes = LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels"));
  if (args.Has("--repair"))
  {
    RepairVesselMeshes(meshes);
  }
  auto scalpel = LoadScalpel(args.Get("--scalpel"), tip);
  // The module logic builds the engine, and beside it the exact engine when the check of
  // --method both or the whole surface needs one.
  vtkNew<vtkVesselProximityLogic> proximity;
  proximity->SetDistanceEngine(engine);
  proximity->SetScalpel(scalpel);
  proximity->SetDangerThresholds(thresholds);
  proximity->SetComputeSurfaceDistance(surface);
  proximity->SetCompareWithExact(method == "both");
  for (const auto& m : meshes)
  {
    proximity->AddVessel(m.ClassName, m.Mesh);
  }
  proximity->Build();
  const double buildMs = NowMs() - start;
  vtkScalpelTrackingLogic* logic = proximity->GetTrackingLogic();
  logic->SetFrameBudgetMs(budgetMs);
  logic->SetHysteresisMm(hysteresisMm);
  logic->ValidateSettings();
  // Said once everything is built and checked: a line before a refusal would make its one line two.
  std::cerr << "track: " << scalpel->GetTipSource() << "\n";
  ReportSurfaceDefects("track", engine, meshes);
  if (logic->GetPenetration() && !logic->GetPenetration()->IsToolClosed())
  {
    std::cerr << "track: " << args.Get("--scalpel")
              << ": the surface is not closed, so the instrument's penetration depth and volume cannot be known (left empty)\n";
  }
  TrackingSummary summary;
  vtkNew<vtkCallbackCommand> onChange;
  onChange->SetClientData(&summary);
  onChange->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<TrackingSummary*>(client)->AddChange(*static_cast<DangerLevelChange*>(call));
  });
  logic->AddObserver(vtkScalpelTrackingLogic::DangerLevelChangedEvent, onChange);

  // The frames stream into frames.csv in the run's staging folder as they are computed, and the
  // summary and the plot keep what they need in memory that does not grow with the run.
  run.Begin();
  std::ofstream framesCsv(run.File("frames.csv"), std::ios::binary | std::ios::trunc);
  const auto writeFailed = [&]() {
    return InputError(run.Target() + "/frames.csv", std::string("write failed: ") + std::strerror(errno));
  };
  if (!framesCsv)
  {
    throw writeFailed();
  }
  std::unique_ptr<DistancePlotRecorder> plot;
  ExactComparison check;
  double lastReport = NowMs();
  PoseStream poses(posesFile);
  for (TrackedPose pose; poses.Next(pose);)
  {
    if (RunFolder::SignalPending())
    {
      return 1; // the RunFolder removes what was written, then the signal acts
    }
    const TrackedFrame& frame = proximity->ProcessPose(pose); // valid until the next pose
    summary.Add(frame);
    if (!plot)
    {
      plot = std::make_unique<DistancePlotRecorder>(summary.GetClassNames(), surface);
      framesCsv << FramesCsvHeader(summary.GetClassNames(), surface);
    }
    plot->Add(frame);
    framesCsv << FramesCsvRow(frame, surface);
    if (!framesCsv)
    {
      throw writeFailed();
    }
    if (method == "both")
    {
      check.Add(frame.Proximity, proximity->GetLastExactProximity(), engine->GetRangeMm(), engine->GetErrorBoundMm());
    }
    if (NowMs() - lastReport > 1000.0)
    {
      lastReport = NowMs();
      const std::size_t done = poses.PosesRead();
      std::fprintf(stderr, "track: frame %zu of %zu (%.0f%%)\n", done, poseCount, 100.0 * done / poseCount);
    }
  }
  framesCsv.flush();
  if (!framesCsv)
  {
    throw writeFailed();
  }
  framesCsv.close();
  Json comparison;
  if (method == "both")
  {
    comparison = { { "reference", "exact" }, { "max_abs_difference_mm", check.MaxAbsDifferenceMm },
      { "outside_bound", check.OutsideBound } };
    if (check.OutsideBound > 0)
    {
      std::cerr << "vesselproximity: warning: " << check.OutsideBound << " answer(s) of the z-buffer engine outside its error bound of "
                << engine->GetErrorBoundMm() << " mm\n";
    }
  }

  std::vector<std::string> classes = summary.GetClassNames();
  Json doc = SummaryJson(summary, logic, engine, meshes, posesFile, surface, comparison);
  doc["timing_ms"]["load_and_build"] = buildMs;
  doc["files"] = { "frames.csv", "summary.json", "distance.png" };
  struct rusage usage = {};
  getrusage(RUSAGE_SELF, &usage);
  doc["peak_memory_mb"] = static_cast<double>(usage.ru_maxrss) / 1024.0; // Linux: kB

  // The plot and the summary, then the folder holds this run whole, or the previous one as it was.
  plot->Write(run.File("distance.png"), thresholds, engine->GetRangeMm());
  WriteFileAtomically(run.File("summary.json"), doc.dump(2) + "\n");
  run.Commit();

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
  if (method == "both")
  {
    std::printf("  against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n",
      check.MaxAbsDifferenceMm, check.OutsideBound);
  }
  std::printf("wrote %s/frames.csv, summary.json, distance.png\n", outDir.c_str());
  return 0;
}
} // namespace vp
