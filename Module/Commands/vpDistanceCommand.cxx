// vesselproximity distance: the distance from one or more tips to each vessel class.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vtkExactVesselDistance.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

const char* Usage =
  "usage: vesselproximity distance --vessels CLASS=FILE[,CLASS=FILE...] (--tip X,Y,Z | --tips FILE.csv)\n"
  "         [--axis X,Y,Z] [--method exact|zbuffer|both|brute|auto] [--range MM]\n"
  "         [--device NAME] [--cell MM | --resolution PX] [--layers exact|paper] [--box fixed|moving]\n"
  "         [--box-size X,Y,Z] [--bins N] [--space LPS|RAS] [--repair] [--json]\n"
  "  Distance from each tip to the nearest surface point of every vessel class.\n"
  "  --space RAS: tips are given and points reported in RAS (Slicer's view); default LPS.\n"
  "  --axis: scalpel axis (unit or not), for the directional distance along it.\n"
  "  --repair: merge coincident points, drop duplicated triangles and fins, fill holes up to\n"
  "    30 mm and make the winding consistent before building (vtkVesselSurfaceRepair; no point\n"
  "    moves), saying per class on stderr what changed; an open surface's inside is otherwise a\n"
  "    vote of five rays.\n"
  "  --tips: answered as one batch (the z-buffer engine: one GPU submission per 256 tips); the\n"
  "    query times are then the batch's time per tip.\n";

/// LPS <-> RAS is its own inverse: negate x and y.
std::array<double, 3> ConvertSpace(const std::array<double, 3>& p, bool ras)
{
  return ras ? std::array<double, 3>{ -p[0], -p[1], p[2] } : p;
}

Json PointJson(const double p[3], bool ras)
{
  const auto q = ConvertSpace({ p[0], p[1], p[2] }, ras);
  return Json::array({ q[0], q[1], q[2] });
}

} // namespace

int RunDistanceCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage << EngineOptionsUsage({ "exact", "zbuffer", "both", "brute", "auto" });
    return 0;
  }
  std::set<std::string> options = EngineValueOptions();
  options.insert({ "--vessels", "--tip", "--tips", "--axis", "--space" });
  const Arguments args(argv, options, { "--json", "--repair" });
  if (!args.Positional().empty())
  {
    throw InputError(args.Positional()[0], "unexpected argument (see vesselproximity distance --help)");
  }
  if (!args.Has("--vessels"))
  {
    throw InputError("--vessels", "is required (CLASS=FILE[,CLASS=FILE...])");
  }
  if (args.Has("--tip") == args.Has("--tips"))
  {
    throw InputError("--tip/--tips", "give exactly one of --tip X,Y,Z or --tips FILE.csv");
  }
  const std::string space = args.Get("--space", "LPS");
  if (space != "LPS" && space != "RAS")
  {
    throw InputError("--space", "expected LPS or RAS, got '" + space + "'");
  }
  const bool ras = space == "RAS";
  const std::string method = args.Get("--method", "exact");
  auto engine = MakeDistanceEngine(method, args);
  // --method both: the exact engine beside the z-buffer one, every answer checked against it.
  vtkSmartPointer<vtkExactVesselDistance> reference;
  if (method == "both")
  {
    reference = vtkSmartPointer<vtkExactVesselDistance>::New();
    reference->SetRangeMm(engine->GetRangeMm());
  }

  std::vector<std::array<double, 3>> tips;
  if (args.Has("--tip"))
  {
    tips.push_back(ParsePoint(args.Get("--tip"), "--tip"));
  }
  else
  {
    tips = ReadPointCsv(args.Get("--tips"));
  }
  for (auto& t : tips)
  {
    t = ConvertSpace(t, ras);
  }
  std::array<double, 3> axis{};
  const bool hasAxis = args.Has("--axis");
  if (hasAxis)
  {
    axis = ConvertSpace(ParsePoint(args.Get("--axis"), "--axis"), ras);
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(n > 0))
    {
      throw InputError("--axis", "must not be the zero vector");
    }
    for (double& c : axis)
    {
      c /= n;
    }
  }

  const double loadStart = NowMs();
  auto meshes = LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels"));
  if (args.Has("--repair"))
  {
    RepairVesselMeshes(meshes);
  }
  const double loadMs = NowMs() - loadStart;
  for (const auto& m : meshes)
  {
    engine->AddVessel(m.ClassName, m.Mesh);
    if (reference)
    {
      reference->AddVessel(m.ClassName, m.Mesh);
    }
  }
  engine->Build();
  if (reference)
  {
    reference->Build();
  }
  ReportSurfaceDefects("distance", engine, meshes);

  // One batch: the same answers as tip by tip (bit for bit), in one submission where the engine can.
  const std::vector<std::array<double, 3>> axes(tips.size(), axis);
  std::vector<ProximityResult> results;
  const double start = NowMs();
  engine->ComputeProximityBatch(tips, hasAxis ? &axes : nullptr, results);
  const double batchMs = NowMs() - start;
  const std::vector<double> queryMs(tips.size(), batchMs / static_cast<double>(std::max<std::size_t>(1, tips.size())));
  std::vector<ProximityResult> exactResults;
  if (reference)
  {
    reference->ComputeProximityBatch(tips, hasAxis ? &axes : nullptr, exactResults);
  }
  const double bound = engine->GetErrorBoundMm();
  ExactComparison comparison;
  std::vector<std::vector<char>> withinBound(exactResults.size());
  for (std::size_t i = 0; i < exactResults.size(); ++i)
  {
    comparison.Add(results[i], exactResults[i], engine->GetRangeMm(), bound, &withinBound[i]);
  }
  const int outsideBound = comparison.OutsideBound;
  const double maxDifference = comparison.MaxAbsDifferenceMm;
  if (outsideBound > 0)
  {
    std::cerr << "vesselproximity: warning: " << outsideBound << " answer(s) of the z-buffer engine outside its error bound of "
              << bound << " mm\n";
  }

  // Everything is computed before anything is printed: a failure leaves no partial output.
  if (args.Has("--json"))
  {
    Json out;
    out["method"] = engine->GetMethodName();
    out["device"] = engine->GetDeviceDescription();
    out["space"] = space;
    out["range_mm"] = engine->GetRangeMm();
    out["error_bound_mm"] = bound;
    out["surfaces"] = SurfacesJson(engine, meshes);
    Json list = Json::array();
    for (std::size_t i = 0; i < results.size(); ++i)
    {
      const ProximityResult& r = results[i];
      Json item;
      item["tip"] = PointJson(r.Tip, ras);
      item["error_bound_mm"] = r.ErrorBoundMm;
      const int nearest = r.NearestIndex();
      if (nearest >= 0)
      {
        const ClassProximity& n = r.Classes[nearest];
        item["nearest"] = { { "class", n.ClassName }, { "distance_mm", n.DistanceMm }, { "point", PointJson(n.ClosestPoint, ras) } };
      }
      else
      {
        item["nearest"] = nullptr;
      }
      Json classes = Json::object();
      for (std::size_t k = 0; k < r.Classes.size(); ++k)
      {
        const ClassProximity& c = r.Classes[k];
        Json entry;
        entry["distance_mm"] = c.InRange ? Json(c.DistanceMm) : Json(nullptr);
        entry["point"] = c.InRange ? PointJson(c.ClosestPoint, ras) : Json(nullptr);
        entry["inside"] = c.Inside ? Json(*c.Inside) : Json(nullptr);
        if (c.InsideUncertain)
        {
          entry["inside_uncertain"] = true; // the votes on a defective surface disagreed
        }
        entry["in_range"] = c.InRange;
        entry["directional_mm"] = c.DirectionalMm ? Json(*c.DirectionalMm) : Json(nullptr);
        if (reference)
        {
          const ClassProximity& e = exactResults[i].Classes[k];
          entry["exact_mm"] = e.InRange ? Json(e.DistanceMm) : Json(nullptr);
          entry["difference_mm"] = e.InRange && c.InRange ? Json(c.DistanceMm - e.DistanceMm) : Json(nullptr);
          entry["within_bound"] = withinBound[i][k] != 0;
        }
        classes[c.ClassName] = entry;
      }
      item["classes"] = classes;
      list.push_back(item);
    }
    out["results"] = list;
    if (reference)
    {
      out["comparison"] = { { "reference", "exact" }, { "max_abs_difference_mm", maxDifference },
        { "outside_bound", outsideBound } };
    }
    out["timing_ms"] = { { "load", loadMs }, { "build", engine->GetBuildTimeMs() },
      { "query_median", Quantile(queryMs, 0.5) }, { "query_p95", Quantile(queryMs, 0.95) }, { "batch", batchMs },
      { "tips_per_second", 1000.0 * static_cast<double>(tips.size()) / std::max(1e-9, batchMs) } };
    std::cout << out.dump(2) << "\n";
    return 0;
  }

  std::printf("method %s on %s, range %.1f mm, error bound %.3f mm, space %s, %zu tip(s)\n", engine->GetMethodName(),
    engine->GetDeviceDescription().c_str(), engine->GetRangeMm(), bound, space.c_str(), tips.size());
  for (std::size_t i = 0; i < results.size(); ++i)
  {
    const ProximityResult& r = results[i];
    const auto tip = ConvertSpace({ r.Tip[0], r.Tip[1], r.Tip[2] }, ras);
    const int nearest = r.NearestIndex();
    std::printf("tip (%.2f, %.2f, %.2f)  nearest: %s\n", tip[0], tip[1], tip[2],
      nearest >= 0 ? r.Classes[nearest].ClassName.c_str() : "none in range");
    std::printf("  %-16s %12s  %-28s %-7s %-14s%s\n", "class", "distance mm", "closest point", "inside", "directional mm",
      reference ? "  exact mm  within bound" : "");
    for (std::size_t k = 0; k < r.Classes.size(); ++k)
    {
      const ClassProximity& c = r.Classes[k];
      char check[64] = "";
      if (reference)
      {
        const ClassProximity& e = exactResults[i].Classes[k];
        const bool ok = withinBound[i][k] != 0;
        if (e.InRange)
        {
          std::snprintf(check, sizeof(check), "  %8.3f  %s", e.DistanceMm, ok ? "yes" : "NO");
        }
        else
        {
          std::snprintf(check, sizeof(check), "  %8s  %s", "-", ok ? "yes" : "NO");
        }
      }
      if (!c.InRange)
      {
        std::printf("  %-16s %12s  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), "out of range", "", "", "", check);
        continue;
      }
      const auto q = ConvertSpace({ c.ClosestPoint[0], c.ClosestPoint[1], c.ClosestPoint[2] }, ras);
      char point[64];
      std::snprintf(point, sizeof(point), "(%.2f, %.2f, %.2f)", q[0], q[1], q[2]);
      char directional[32] = "-";
      if (c.DirectionalMm)
      {
        std::snprintf(directional, sizeof(directional), "%.3f", *c.DirectionalMm);
      }
      std::printf("  %-16s %12.3f  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), c.DistanceMm, point,
        c.Inside ? (*c.Inside ? "yes" : "no") : "open", directional, check);
    }
  }
  std::printf("load %.1f ms, build %.1f ms, query median %.4f ms, p95 %.4f ms\n", loadMs, engine->GetBuildTimeMs(),
    Quantile(queryMs, 0.5), Quantile(queryMs, 0.95));
  if (reference)
  {
    std::printf("against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n", maxDifference,
      outsideBound);
  }
  return 0;
}
} // namespace vp
