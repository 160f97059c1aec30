// vesselproximity distance: the distance from one or more tips to each vessel class.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpPatientSpace.h"
#include "vpTipDistanceQuery.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{

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

TipDistanceRequest ParseRequest(const Arguments& args, bool ras)
{
  TipDistanceRequest request;
  const std::string method = args.Get("--method", "exact");
  request.Engine = MakeDistanceEngine(method, args);
  request.CompareWithExact = method == "both";
  if (args.Has("--tip"))
  {
    request.TipsMm.push_back(ParsePoint(args.Get("--tip"), "--tip"));
  }
  else
  {
    request.TipsMm = ReadPointCsv(args.Get("--tips"));
  }
  for (auto& t : request.TipsMm)
  {
    t = ConvertSpace(t, ras);
  }
  if (args.Has("--axis"))
  {
    request.Axis = ConvertSpace(ParsePoint(args.Get("--axis"), "--axis"), ras);
  }
  return request;
}

/// "  portal_vein  12.345  (1.00, 2.00, 3.00)  no  -" and, when compared, the exact answer.
void PrintClassRow(const ClassProximity& c, const ClassProximity* exact, bool within, bool ras)
{
  char check[64] = "";
  if (exact)
  {
    std::snprintf(check, sizeof(check), "  %8s  %s", exact->InRange ? FixedText(exact->DistanceMm, "%.3f").c_str() : "-",
      within ? "yes" : "NO");
  }
  if (!c.InRange)
  {
    std::printf("  %-16s %12s  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), "out of range", "", "", "", check);
    return;
  }
  const auto q = ConvertSpace({ c.ClosestPoint[0], c.ClosestPoint[1], c.ClosestPoint[2] }, ras);
  char point[64];
  std::snprintf(point, sizeof(point), "(%.2f, %.2f, %.2f)", q[0], q[1], q[2]);
  std::printf("  %-16s %12.3f  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), c.DistanceMm, point,
    c.Inside ? (*c.Inside ? "yes" : "no") : "open", c.DirectionalMm ? FixedText(*c.DirectionalMm, "%.3f").c_str() : "-", check);
}

void PrintTable(const TipDistanceRequest& request, const TipDistanceAnswer& answer, bool ras, double loadMs)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  const bool compared = !answer.Exact.empty();
  std::printf("method %s on %s, range %.1f mm, error bound %.3f mm, space %s, %zu tip(s)\n", engine->GetMethodName(),
    engine->GetDeviceDescription().c_str(), engine->GetRangeMm(), engine->GetErrorBoundMm(), ras ? "RAS" : "LPS",
    answer.Results.size());
  for (std::size_t i = 0; i < answer.Results.size(); ++i)
  {
    const ProximityResult& r = answer.Results[i];
    const auto tip = ConvertSpace({ r.Tip[0], r.Tip[1], r.Tip[2] }, ras);
    const int nearest = r.NearestIndex();
    std::printf("tip (%.2f, %.2f, %.2f)  nearest: %s\n", tip[0], tip[1], tip[2],
      nearest >= 0 ? r.Classes[nearest].ClassName.c_str() : "none in range");
    std::printf("  %-16s %12s  %-28s %-7s %-14s%s\n", "class", "distance mm", "closest point", "inside", "directional mm",
      compared ? "  exact mm  within bound" : "");
    for (std::size_t k = 0; k < r.Classes.size(); ++k)
    {
      PrintClassRow(r.Classes[k], compared ? &answer.Exact[i].Classes[k] : nullptr, compared && answer.WithinBound[i][k], ras);
    }
  }
  std::printf("load %.1f ms, build %.1f ms, query median %.4f ms, p95 %.4f ms\n", loadMs, engine->GetBuildTimeMs(),
    answer.QueryMs(), answer.QueryMs());
  if (compared)
  {
    std::printf("against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n",
      answer.Comparison.MaxAbsDifferenceMm, answer.Comparison.OutsideBound);
  }
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
  TipDistanceRequest request = ParseRequest(args, ras);
  const double loadStart = NowMs();
  request.Vessels = LoadVesselMeshes(ParsePairs(args.Get("--vessels"), "--vessels"));
  if (args.Has("--repair"))
  {
    RepairVesselMeshes(request.Vessels);
  }
  const double loadMs = NowMs() - loadStart;
  const TipDistanceAnswer answer = ComputeTipDistances(request);
  ReportSurfaceDefects("distance", request.Engine, request.Vessels);
  if (answer.Comparison.OutsideBound > 0)
  {
    std::cerr << "vesselproximity: warning: " << answer.Comparison.OutsideBound
              << " answer(s) of the z-buffer engine outside its error bound of " << request.Engine->GetErrorBoundMm() << " mm\n";
  }
  // Everything is computed before anything is printed: a failure leaves no partial output.
  if (args.Has("--json"))
  {
    std::cout << TipDistanceReportJson(request, answer, ras, loadMs).dump(2) << "\n";
  }
  else
  {
    PrintTable(request, answer, ras, loadMs);
  }
  return 0;
}
} // namespace vp
