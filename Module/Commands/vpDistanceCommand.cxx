// vesselproximity distance: the distance from one or more tips to each vessel class.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpCommands.h"
#include "vpEngineOptions.h"
#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpPatientSpace.h"
#include "vpRegistrationFile.h"
#include "vpTipDistanceQuery.h"

#include <vtkSmartPointer.h>

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
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
std::string ClassRow(const ClassProximity& c, const ClassProximity* exact, bool within, bool ras)
{
  char check[64] = "";
  if (exact)
  {
    std::snprintf(check, sizeof(check), "  %8s  %s", exact->InRange ? FixedText(exact->DistanceMm, "%.3f").c_str() : "-",
      within ? "yes" : "NO");
  }
  char row[512];
  if (!c.InRange)
  {
    std::snprintf(row, sizeof(row), "  %-16s %12s  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), "out of range", "", "", "", check);
    return row;
  }
  const auto q = ConvertSpace({ c.ClosestPoint[0], c.ClosestPoint[1], c.ClosestPoint[2] }, ras);
  char point[64];
  std::snprintf(point, sizeof(point), "(%.2f, %.2f, %.2f)", q[0], q[1], q[2]);
  std::snprintf(row, sizeof(row), "  %-16s %12.3f  %-28s %-7s %-14s%s\n", c.ClassName.c_str(), c.DistanceMm, point,
    c.Inside ? (*c.Inside ? "yes" : "no") : "open", c.DirectionalMm ? FixedText(*c.DirectionalMm, "%.3f").c_str() : "-", check);
  return row;
}

/// Output held back until every tip is answered (a failure leaves no partial output), in an
/// unnamed temporary file rather than memory: a million tips' report is hundreds of megabytes.
class HeldOutput
{
public:
  HeldOutput()
    : File(std::tmpfile())
  {
    if (!this->File)
    {
      throw InputError("temporary file", std::string("cannot hold the output: ") + std::strerror(errno));
    }
  }
  ~HeldOutput() { std::fclose(this->File); }
  HeldOutput(const HeldOutput&) = delete;
  HeldOutput& operator=(const HeldOutput&) = delete;
  void Write(const std::string& text)
  {
    if (std::fwrite(text.data(), 1, text.size(), this->File) != text.size())
    {
      throw InputError("temporary file", std::string("cannot hold the output: ") + std::strerror(errno));
    }
  }
  /// Everything written, to stdout.
  void Release()
  {
    std::fflush(this->File);
    std::rewind(this->File);
    char block[65536];
    for (std::size_t n; (n = std::fread(block, 1, sizeof(block), this->File)) > 0;)
    {
      std::fwrite(block, 1, n, stdout);
    }
  }

private:
  std::FILE* File;
};

/// A tip's rows for the tumours: the signed distance (negative inside), exact, however far.
std::string TumourRows(const TipDistanceAnswer& answer, std::size_t i, bool ras)
{
  if (answer.Tumours.empty())
  {
    return std::string();
  }
  char line[512];
  std::snprintf(line, sizeof(line), "  %-16s %12s  %-28s %-7s\n", "tumour", "signed mm", "closest point", "inside");
  std::string rows = line;
  for (const TumourProximity& t : answer.Tumours[i].Tumours)
  {
    const auto q = ConvertSpace({ t.ClosestPoint[0], t.ClosestPoint[1], t.ClosestPoint[2] }, ras);
    char point[64];
    std::snprintf(point, sizeof(point), "(%.2f, %.2f, %.2f)", q[0], q[1], q[2]);
    std::snprintf(line, sizeof(line), "  %-16s %12.3f  %-28s %-7s\n", t.Id.c_str(), t.SignedMm, point,
      t.InsideUncertain ? "unsure" : t.SignedMm < 0.0 ? "yes" : "no");
    rows += line;
  }
  return rows;
}

/// The table's rows for one tip.
std::string TableRows(const TipDistanceAnswer& answer, std::size_t i, bool ras)
{
  const bool compared = !answer.Exact.empty();
  const ProximityResult& r = answer.Results[i];
  const auto tip = ConvertSpace({ r.Tip[0], r.Tip[1], r.Tip[2] }, ras);
  const int nearest = r.NearestIndex();
  char line[512];
  std::snprintf(line, sizeof(line), "tip (%.2f, %.2f, %.2f)  nearest: %s\n", tip[0], tip[1], tip[2],
    nearest >= 0 ? r.Classes[nearest].ClassName.c_str() : "none in range");
  std::string rows = line;
  std::snprintf(line, sizeof(line), "  %-16s %12s  %-28s %-7s %-14s%s\n", "class", "distance mm", "closest point", "inside",
    "directional mm", compared ? "  exact mm  within bound" : "");
  rows += line;
  for (std::size_t k = 0; k < r.Classes.size(); ++k)
  {
    rows += ClassRow(r.Classes[k], compared ? &answer.Exact[i].Classes[k] : nullptr, compared && answer.WithinBound[i][k], ras);
  }
  return rows + TumourRows(answer, i, ras);
}
/// The table: what answered and how, the held rows, then the times and the comparison.
void PrintDistanceTable(const TipDistanceRequest& request, const TipDistanceTotals& totals, HeldOutput& held, bool ras, double loadMs)
{
  vtkVesselDistanceEngine* engine = request.Engine;
  const std::optional<TrackerRegistration>& registration = request.Registration;
  std::printf("method %s on %s, range %.1f mm, error bound %.3f mm, space %s, %zu tip(s)%s\n", engine->GetMethodName(),
    engine->GetDeviceDescription().c_str(), engine->GetRangeMm(), engine->GetErrorBoundMm(), ras ? "RAS" : "LPS", totals.Tips,
    registration ? (", registered by " + registration->FileName + " (" + registration->Kind + ")").c_str() : "");
  held.Release();
  // The tips go in batches: a tip's own time is not known, only the batches' mean.
  std::printf("load %.1f ms, build %.1f ms, query %.4f ms a tip (the batches' mean over %zu tip(s))\n", loadMs,
    engine->GetBuildTimeMs(), totals.QueryMs(), totals.Tips);
  if (totals.Compared)
  {
    std::printf("against the exact engine: largest difference %.4f mm, %d answer(s) outside the bound\n",
      totals.Comparison.MaxAbsDifferenceMm, totals.Comparison.OutsideBound);
  }
}

} // namespace

cli::ModuleDescription DescribeDistanceCommand()
{
  using cli::ParameterType;
  return cli::ModuleDescription::Subcommand("vesselproximity distance",
    "distance from scalpel tip(s) to each vessel class (exact, zbuffer, both, brute, auto)",
    "Distance from each tip to the nearest surface point of every vessel class: the distance, the closest point, "
    "whether the tip is inside, and the directional distance along --axis; with --tumour, each tumour's signed "
    "distance beside them. Give exactly one of --tip and --tips.",
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
          Option(ParameterType::String, "tumour",
            "Tumours each tip is also measured against (signed, exact, negative inside, as track's tumour_mm): "
            "FILE[,FILE...], ID=FILE, or a models folder or models.json (all its tumours).")
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("FILE|DIR"),
          Option(ParameterType::String, "axis", "The scalpel's axis (unit or not), for the directional distance along it.")
            .SetPlaceholder("X,Y,Z")
            .SetLogicName("Axis"),
          Option(ParameterType::StringEnumeration, "space",
            "The tips are given and the points reported in LPS (DICOM's frame) or RAS (Slicer's view). Default: LPS, "
            "or RAS with a 3D Slicer transform as --registration.")
            .SetElements({ "LPS", "RAS" }),
          Option(ParameterType::File, "registration",
            "The tips are the tracker's (or its reference's): register's RESULT.json or a 3D Slicer transform (.h5, "
            ".tfm, .txt) takes them into the patient's images; the answers, tips included, are the patient's.")
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("R.json|T.h5"),
        } },
      EngineOptions(EngineMethodNames(OfferedForTips)),
      { "Output", "", { Switch("json", "Print the answer as JSON instead of a table.") } },
    });
}

int RunDistanceCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  if (args.IsSet("tip") == args.IsSet("tips"))
  {
    throw InputError("--tip/--tips", "give exactly one of --tip X,Y,Z or --tips FILE.csv");
  }
  std::optional<TrackerRegistration> registration;
  if (args.IsSet("registration"))
  {
    registration = ReadTrackerRegistration(args.GetString("registration"));
  }
  // A Slicer transform takes the tracker's numbers as RAS, as Slicer holds them; a space given wins.
  const bool ras = args.IsSet("space") ? args.GetString("space") == "RAS" : registration && registration->TrackerSpace == PoseSpace::RAS;
  TipDistanceRequest request = ParseRequest(args, ras);
  request.Registration = registration;
  const double loadStart = NowMs();
  request.Vessels = LoadVesselMeshes(ParsePairs(args.GetString("vessels"), "--vessels"));
  if (args.GetBoolean("repair"))
  {
    RepairVesselMeshes(request.Vessels);
  }
  if (args.IsSet("tumour"))
  {
    request.Tumours = LoadTumourMeshes(TumourEntries(SplitList(args.GetString("tumour"), ','), "--tumour"));
  }
  const double loadMs = NowMs() - loadStart;
  // The tips are answered a chunk at a time and their report held in a temporary file: memory
  // follows the chunk, not the tips; nothing is printed before the last tip is answered.
  const bool json = args.GetBoolean("json");
  HeldOutput held;
  bool firstItem = true;
  const TipDistanceTotals totals = ComputeTipDistancesInChunks(request, 4096, [&](const TipDistanceAnswer& chunk, std::size_t) {
    std::string text;
    for (std::size_t i = 0; i < chunk.Results.size(); ++i)
    {
      text += json ? (firstItem ? "" : ",\n") + IndentedItem(TipResultJson(chunk, i, ras)) : TableRows(chunk, i, ras);
      firstItem = false;
    }
    held.Write(text);
  });
  ReportSurfaceDefects("distance", request.Engine, request.Vessels);
  if (totals.Comparison.OutsideBound > 0)
  {
    std::cerr << "vesselproximity: warning: " << totals.Comparison.OutsideBound
              << " answer(s) of the z-buffer engine outside its error bound of " << request.Engine->GetErrorBoundMm() << " mm\n";
  }
  if (json)
  {
    // The report's text around the held entries, which go out from the file as they are.
    const auto [before, after] = TipDistanceReportAround(
      TipDistanceHeaderJson(request, ras), TipDistanceTrailerJson(request, totals, loadMs), totals.Tips > 0);
    std::fputs(before.c_str(), stdout);
    held.Release();
    std::fputs((after + "\n").c_str(), stdout);
    return 0;
  }
  PrintDistanceTable(request, totals, held, ras, loadMs);
  return 0;
}
} // namespace vp
