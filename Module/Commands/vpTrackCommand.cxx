// vesselproximity track: a recorded stream of scalpel poses replayed against the vessels, with the
// per-frame record (frames.csv), the run's summary (summary.json) and its plot (distance.png).
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpDangerBands.h"
#include "vpDangerLevels.h"
#include "vpDistancePlot.h"
#include "vpPlotValues.h"
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

#include <cmath>
#include <cstdio>
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

std::string Number(double value, const char* format = "%.4f")
{
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string FramesCsv(const std::vector<TrackedFrame>& frames, const std::vector<std::string>& classes, bool surface)
{
  std::string csv = "frame,time,tip_x,tip_y,tip_z,nearest_class,nearest_mm";
  for (const auto& c : classes)
  {
    csv += "," + c + "_mm";
  }
  csv += ",danger_level,error_bound_mm,frame_ms,axis_x,axis_y,axis_z";
  for (const auto& c : classes)
  {
    csv += "," + c + "_point_x," + c + "_point_y," + c + "_point_z," + c + "_directional_mm," + c + "_inside," + c +
      "_inside_uncertain," + c + "_level";
    if (surface)
    {
      csv += "," + c + "_surface_mm," + c + "_penetration_depth_mm," + c + "_penetration_volume_mm3," + c +
        "_penetration_depth_bound_mm," + c + "_penetration_volume_bound_mm3," + c + "_surface_bound_mm";
    }
  }
  csv += "\n";
  for (const TrackedFrame& f : frames)
  {
    const auto& r = f.Proximity;
    const int nearest = r.NearestIndex();
    csv += std::to_string(f.Frame) + "," + Number(f.TimeS, "%.6f") + "," + Number(f.TipMm[0]) + "," + Number(f.TipMm[1]) +
      "," + Number(f.TipMm[2]) + "," + (nearest >= 0 ? r.Classes[nearest].ClassName : "") + "," +
      (nearest >= 0 ? Number(r.Classes[nearest].DistanceMm) : "");
    for (const auto& c : r.Classes)
    {
      csv += "," + (c.InRange ? Number(c.DistanceMm) : "");
    }
    csv += std::string(",") + DangerLevelName(f.Level) + "," + Number(r.ErrorBoundMm) + "," + Number(f.FrameMs, "%.5f") +
      "," + Number(f.AxisWorld[0], "%.6f") + "," + Number(f.AxisWorld[1], "%.6f") + "," + Number(f.AxisWorld[2], "%.6f");
    for (std::size_t k = 0; k < r.Classes.size(); ++k)
    {
      const ClassProximity& c = r.Classes[k];
      for (int a = 0; a < 3; ++a)
      {
        csv += "," + (c.InRange ? Number(c.ClosestPoint[a]) : "");
      }
      csv += "," + (c.DirectionalMm ? Number(*c.DirectionalMm) : "");
      csv += "," + (c.InRange && c.Inside ? std::string(*c.Inside ? "1" : "0") : "");
      csv += "," + (c.InRange ? std::string(c.InsideUncertain ? "1" : "0") : "");
      csv += std::string(",") + DangerLevelName(f.ClassLevels[k]);
      if (surface)
      {
        csv += "," + (f.Surface[k].InRange ? Number(f.Surface[k].DistanceMm) : "");
        // Empty where it cannot be known (an open surface has no inside), never a silent 0.
        const bool known = k < f.Penetrations.size() && f.Penetrations[k].Known;
        const Penetration none;
        const Penetration& p = known ? f.Penetrations[k] : none;
        for (double v : { p.DepthMm, p.VolumeMm3, p.DepthBoundMm, p.VolumeBoundMm3 })
        {
          csv += "," + (known ? Number(v) : "");
        }
        csv += "," + (f.Surface[k].InRange ? Number(f.Surface[k].ErrorBoundMm) : "");
      }
    }
    csv += "\n";
  }
  return csv;
}

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

/// Per class, the tip's signed distance (negative: the penetration depth) and, with the whole
/// surface, the instrument's (its distance, or minus its penetration depth), below zero drawn
/// over a breach band.
void WritePlot(const std::string& file, const std::vector<TrackedFrame>& frames, const std::vector<std::string>& classes,
  const DangerThresholds& t, double rangeMm, bool surface)
{
  std::vector<double> times;
  std::vector<PlotSeries> series;
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const Rgb colour = PlotSeriesColour(classes[c], static_cast<int>(c));
    series.push_back({ classes[c] + " (tip)", colour, {} });
    if (surface)
    {
      series.push_back({ classes[c] + " (instrument)", InstrumentColour(colour), {} });
    }
  }
  for (const TrackedFrame& f : frames)
  {
    times.push_back(f.TimeS);
    std::size_t s = 0;
    for (std::size_t c = 0; c < classes.size(); ++c)
    {
      series[s++].ValuesMm.push_back(TipPlotValueMm(f, c));
      if (surface)
      {
        series[s++].ValuesMm.push_back(InstrumentPlotValueMm(f, c));
      }
    }
  }
  const std::vector<PlotBand> bands = DangerBands(t, rangeMm, LowestValueMm(series) < 0);
  DistancePlotOptions options;
  options.Title = surface ? "Tip and instrument distance to each vessel class over time (inside: below 0)"
                          : "Tip distance to each vessel class over time (inside: below 0)";
  WriteDistancePlotPng(file, times, series, bands, options);
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
  const double start = NowMs();
  const std::vector<TrackedPose> poses = ReadPoseFile(args.Get("--poses"));
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

  std::vector<TrackedFrame> frames;
  frames.reserve(poses.size());
  ExactComparison check;
  double lastReport = NowMs();
  for (std::size_t i = 0; i < poses.size(); ++i)
  {
    frames.push_back(proximity->ProcessPose(poses[i]));
    summary.Add(frames.back());
    if (method == "both")
    {
      check.Add(frames.back().Proximity, proximity->GetLastExactProximity(), engine->GetRangeMm(), engine->GetErrorBoundMm());
    }
    if (NowMs() - lastReport > 1000.0)
    {
      lastReport = NowMs();
      std::fprintf(stderr, "track: frame %zu of %zu (%.0f%%)\n", i + 1, poses.size(), 100.0 * (i + 1) / poses.size());
    }
  }
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
  const std::string csv = FramesCsv(frames, classes, surface);
  Json doc = SummaryJson(summary, logic, engine, meshes, args.Get("--poses"), surface, comparison);
  doc["timing_ms"]["load_and_build"] = buildMs;
  doc["files"] = { "frames.csv", "summary.json", "distance.png" };

  // Write: the folder holds this run whole, or the previous one as it was.
  run.Begin();
  WriteFileAtomically(run.File("frames.csv"), csv);
  WriteFileAtomically(run.File("summary.json"), doc.dump(2) + "\n");
  WritePlot(run.File("distance.png"), frames, classes, thresholds, engine->GetRangeMm(), surface);
  run.Commit();

  std::printf("%zu frames over %.2f s, method %s on %s, error bound %.3f mm\n", frames.size(), summary.GetDurationS(),
    engine->GetMethodName(), engine->GetDeviceDescription().c_str(), engine->GetErrorBoundMm());
  std::printf("  %-16s %16s %10s %20s\n", "class", "tip minimum mm", "at time", surface ? "whole surface mm" : "");
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    const ClassMinimum& m = summary.GetTipMinimum()[c];
    const ClassMinimum& s = summary.GetSurfaceMinimum()[c];
    std::printf("  %-16s %16s %10s %20s\n", classes[c].c_str(),
      m.Seen ? (Number(m.DistanceMm, "%.3f") + (m.Inside ? " inside" : "")).c_str() : "out of range",
      m.Seen ? Number(m.TimeS, "%.3f").c_str() : "", surface ? (s.Seen ? Number(s.DistanceMm, "%.3f").c_str() : "out of range") : "");
  }
  std::printf("  time at each level:");
  for (int l = 0; l < NumberOfDangerLevels; ++l)
  {
    std::printf(" %s %.2f s", DangerLevelName(static_cast<DangerLevel>(l)), summary.GetTimeInLevelS()[l]);
  }
  std::printf("\n  %zu level change(s), worst level %s\n", summary.GetChanges().size(), DangerLevelName(summary.GetWorstLevel()));
  std::printf("  frame median %.4f ms, p95 %.4f ms, max %.4f ms; %s\n", summary.GetFrameMsQuantile(0.5),
    summary.GetFrameMsQuantile(0.95), summary.GetFrameMsQuantile(1.0),
    budgetMs > 0 ? (std::to_string(summary.GetFramesOverBudget()) + " of " + std::to_string(frames.size()) +
                     " frames over the " + Number(budgetMs, "%g") + " ms budget")
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
