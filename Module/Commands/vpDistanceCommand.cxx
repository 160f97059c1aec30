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

TipDistanceRequest ParseRequest(const cli::ParsedArguments& args, bool ras)
{
  TipDistanceRequest request;
  const std::string method = args.GetString("method");
  request.Engine = MakeDistanceEngine(method, args);
  request.CompareWithExact = method == "both";
  if (args.IsSet("tip"))
  {
    request.TipsMm.push_back(ParsePoint(args.GetString("tip"), "--tip"));
  }
  else
  {
    request.TipsMm = ReadPointCsv(args.GetString("tips"));
  }
  for (auto& t : request.TipsMm)
  {
    t = ConvertSpace(t, ras);
  }
  if (args.IsSet("axis"))
  {
    request.Axis = ConvertSpace(ParsePoint(args.GetString("axis"), "--axis"), ras);
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

cli::ModuleDescription DescribeDistanceCommand()
{
  using cli::ParameterType;
  return cli::ModuleDescription::Subcommand("vesselproximity distance",
    "distance from scalpel tip(s) to each vessel class (exact, zbuffer, both, brute, auto)",
    "Distance from each tip to the nearest surface point of every vessel class: the distance, the closest point, "
    "whether the tip is inside, and the directional distance along --axis. Give exactly one of --tip and --tips.",
    {
      { "Inputs", "", { VesselsOption().SetRequired(), RepairSwitch() } },
      { "Tips", "",
        {
          Option(ParameterType::String, "tip", "One tip.").SetPlaceholder("X,Y,Z"),
          Option(ParameterType::File, "tips",
            "Tips, one x,y,z per line, answered as one batch (the z-buffer engine: one GPU submission per 256 tips); "
            "the query times are then the batch's time per tip.")
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("FILE.csv"),
          Option(ParameterType::String, "axis", "The scalpel's axis (unit or not), for the directional distance along it.")
            .SetPlaceholder("X,Y,Z")
            .SetLogicName("Axis"),
          Option(ParameterType::StringEnumeration, "space",
            "The tips are given and the points reported in LPS (DICOM's frame) or RAS (Slicer's view).")
            .SetElements({ "LPS", "RAS" })
            .SetDefault("LPS"),
        } },
      EngineOptions({ "exact", "zbuffer", "both", "brute", "auto" }),
      { "Output", "", { Switch("json", "Print the answer as JSON instead of a table.") } },
    });
}

int RunDistanceCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  if (args.IsSet("tip") == args.IsSet("tips"))
  {
    throw InputError("--tip/--tips", "give exactly one of --tip X,Y,Z or --tips FILE.csv");
  }
  const std::string space = args.GetString("space");
  const bool ras = space == "RAS";
  TipDistanceRequest request = ParseRequest(args, ras);
  const double loadStart = NowMs();
  request.Vessels = LoadVesselMeshes(ParsePairs(args.GetString("vessels"), "--vessels"));
  if (args.GetBoolean("repair"))
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
  if (args.GetBoolean("json"))
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
