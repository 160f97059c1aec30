// VesselProximityDistance: `vesselproximity distance` as a 3D Slicer CLI module. Slicer hands
// over the vessel models (temporary files) and the scalpel tip (a markups point, in LPS); the
// program returns the distance to each vessel class through the return-parameter file and,
// when asked, writes the distance command's JSON report.
#include "vpCliDescription.h"
#include "vpCliProgress.h"
#include "vpCliTableSchema.h"
#include "vpCliVessels.h"
#include "vpOutputFile.h"
#include "vpClock.h"
#include "vpDistanceEngineFactory.h"
#include "vpDefaultScalpel.h"
#include "vpInputError.h"
#include "vpMarkupsFile.h"
#include "vpPlotValues.h"
#include "vpRegistrationFile.h"
#include "vpScalpelLoader.h"
#include "vpTipDistanceQuery.h"
#include "vtkScalpelModel.h"

#include <vtkObject.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <limits>

#ifndef VP_VERSION
#define VP_VERSION "0.1.0"
#endif

namespace
{
namespace fs = std::filesystem;
using vp::cli::Channel;
using vp::cli::Parameter;
using vp::cli::ParameterType;

/// The return parameter of a class's distance ("portalVeinDistanceMm").
std::string DistanceResult(const vp::cli::VesselClassParameter& v)
{
  return std::string(v.Parameter) + "DistanceMm";
}

/// No answer (a model not given, beyond the range, no axis) is no value: the distances are signed
/// (negative inside), so no number can mean "none", and 0 or -1 read as touching or inside.
const char* NoDistance = "";

/// Negative inside: the depth, as the track program's minima.
double SignedDistance(const vp::ClassProximity& c)
{
  return c.Inside.value_or(false) ? -c.DistanceMm : c.DistanceMm;
}

vp::cli::ParameterGroup ScalpelGroup()
{
  vp::cli::ParameterGroup scalpel{ "Scalpel", "Where the tip is: a point, a point list, or the tracked tool's transform", {} };
  scalpel.Parameters.push_back(Parameter(ParameterType::Point, "tip")
                                 .SetCoordinateSystem("lps")
                                 .SetLongFlag("tip")
                                 .SetLabel("Scalpel tip")
                                 .SetDescription("The scalpel tip, one point (Slicer passes it in LPS). Give this, a tip "
                                                 "point list or the scalpel's transform."));
  scalpel.Parameters.push_back(Parameter(ParameterType::PointFile, "tipFile")
                                 .SetCoordinateSystem("lps")
                                 .SetFileExtensions(".mrk.json,.fcsv")
                                 .SetLongFlag("tipFile")
                                 .SetChannel(Channel::Input)
                                 .SetLabel("Scalpel tip (point list)")
                                 .SetDescription("A point list whose first defined point is the tip (markups JSON or "
                                                 ".fcsv, in the file's coordinate system)."));
  scalpel.Parameters.push_back(Parameter(ParameterType::Transform, "scalpelPose")
                                 .SetTypeAttribute("linear")
                                 .SetFileExtensions(".h5")
                                 .SetLongFlag("scalpelPose")
                                 .SetChannel(Channel::Input)
                                 .SetLabel("Scalpel transform")
                                 .SetDescription("The tracked tool's transform, tool to patient (as a tracked tool "
                                                 "arrives in Slicer: StylusToReference, after the tracker's registration), "
                                                 "rigid. The tip and axis are the scalpel model's, carried by it."));
  scalpel.Parameters.push_back(vp::cli::ScalpelModelParameter("With the scalpel transform: the instrument in its own "
                                                                 "coordinates, tip and axis found from its shape. Default: "
                                                                 "the built-in CUSA handpiece."));
  scalpel.Parameters.push_back(Parameter(ParameterType::DoubleVector, "axis")
                                 .SetLongFlag("axis")
                                 .SetLogicName("Axis")
                                 .SetLabel("Scalpel axis")
                                 .SetDescription("Direction the scalpel points, x,y,z in LPS (need not be unit "
                                                 "length), for the directional distance along it. Optional (with the "
                                                 "scalpel transform: the model's axis)."));
  return scalpel;
}

vp::cli::ParameterGroup EngineGroup()
{
  vp::cli::ParameterGroup engine{ "Distance engine", "Which engine answers, and how far it looks", {} };
  engine.Parameters.push_back(Parameter(ParameterType::StringEnumeration, "method")
                                .SetLongFlag("method")
                                .SetLogicName("Method")
                                .SetLabel("Method")
                                .SetDescription(vp::EngineMethodHelp(vp::EngineMethodNames(vp::OfferedToSlicerTips), ". ") + ".")
                                .SetDefault(vp::DistanceEngineSettings().Method)
                                .SetElements(vp::EngineMethodNames(vp::OfferedToSlicerTips)));
  engine.Parameters.push_back(Parameter(ParameterType::Float, "rangeMm")
                                .SetLongFlag("rangeMm")
                                .SetLogicName("RangeMm")
                                .SetLabel("Range (mm)")
                                .SetDescription("Classes further from the tip than this return -1.")
                                .SetDefault(vp::cli::FormatNumber(vtkVesselDistanceEngine::DefaultRangeMm))
                                .SetRange(1.0, 1000.0, 1.0));
  engine.Parameters.push_back(Parameter(ParameterType::PointFile, "closestPoints")
                                .SetCoordinateSystem("lps")
                                .SetFileExtensions(".mrk.json")
                                .SetLongFlag("closestPoints")
                                .SetChannel(Channel::Output)
                                .SetLabel("Closest points")
                                .SetDescription("A point list: per vessel class within range its closest point to the "
                                                "tip, labelled with the class and the distance, and the tip itself."));
  engine.Parameters.push_back(Parameter(ParameterType::Table, "resultsTable")
                                .SetFileExtensions(".csv")
                                .SetLongFlag("resultsTable")
                                .SetChannel(Channel::Output)
                                .SetLabel("Results table")
                                .SetDescription("A table, a row per vessel class: distance, inside, in range, closest "
                                                "point (LPS), directional distance, error bound, engine (nan: no answer "
                                                "within range)."));
  engine.Parameters.push_back(Parameter(ParameterType::File, "report")
                                .SetFileExtensions(".json")
                                .SetLongFlag("report")
                                .SetChannel(Channel::Output)
                                .SetLabel("JSON report")
                                .SetDescription("Writes the distance command's JSON (per class: distance, closest "
                                                "point, inside, in range, directional distance; timing). Optional."));
  return engine;
}

vp::cli::ParameterGroup ResultsGroup()
{
  vp::cli::ParameterGroup out{ "Results",
    "Signed distances from the tip, negative inside (no value: model not given, or beyond the range)", {} };
  auto result = [&](ParameterType type, const char* name, const char* label, const std::string& text,
                  const char* value) {
    out.Parameters.push_back(
      Parameter(type, name).SetChannel(Channel::Output).SetLabel(label).SetDescription(text).SetDefault(value));
  };
  result(ParameterType::String, "nearestClass", "Nearest class",
    "The vessel class nearest to the tip: portal_vein, hepatic_artery, hepatic_vein, or none within range.", "none");
  // Distances as text: a Slicer number field always holds a number, and no number means "none".
  result(ParameterType::String, "nearestDistanceMm", "Nearest distance (mm)",
    "Signed distance to the nearest class: negative inside it (minus the penetration depth); no value when none is "
    "within range.",
    NoDistance);
  result(ParameterType::Boolean, "nearestInside", "Tip inside",
    "True when the tip is inside the nearest vessel (closed models only).", "false");
  result(ParameterType::DoubleVector, "nearestPoint", "Nearest point (LPS)",
    "Closest point on the nearest class, x,y,z in LPS; empty when none is within range.", "");
  for (const vp::cli::VesselClassParameter& v : vp::cli::VesselClassParameters())
  {
    result(ParameterType::String, DistanceResult(v).c_str(), (std::string(v.Label) + " distance (mm)").c_str(),
      std::string("Signed distance to the ") + v.ClassName + " model, negative inside; no value when not given or beyond "
      "the range.", NoDistance);
  }
  result(ParameterType::String, "directionalDistanceMm", "Directional distance (mm)",
    "Distance along the axis to the first vessel surface; no value without an axis or when none is hit within range.",
    NoDistance);
  result(ParameterType::Float, "errorBoundMm", "Error bound (mm)",
    "Bound on |reported - exact| (0 for the exact engine); a z-buffer answer may overstate danger by this much, "
    "never understate it.",
    "0");
  result(ParameterType::String, "methodUsed", "Engine used",
    "The engine that answered (auto resolves to zbuffer or exact).", "");
  return out;
}

/// The one table: the XML, --help and the parser all come from it.
vp::cli::ModuleDescription Describe()
{
  auto d = vp::cli::ModuleDescription::VesselProximity(
    "VesselProximityDistance", "Vessel Proximity Distance", VP_VERSION, { vp::cli::VesselModelsGroup(), ScalpelGroup(), EngineGroup(), ResultsGroup() });
  d.Description =
    "Distance from a scalpel tip to the nearest surface point of each vessel system (portal vein, "
    "hepatic artery, hepatic vein), for liver surgery navigation. The exact engine answers from a "
    "BVH in double precision; the z-buffer engine (the GPU method of Noborio et al., on Vulkan) "
    "answers within a stated error bound. Coordinates are LPS millimetres. A class whose model is not "
    "given, or that lies beyond the range, returns -1. Exit codes: 0 success, 1 bad input, 2 bad usage, "
    "3 internal error, 4 no usable Vulkan device (zbuffer, both). Same as `vesselproximity distance`.";
  return d;
}

/// The tip (LPS) from exactly one of --tip, --tipFile and --scalpelPose; with the transform, the
/// scalpel model's axis too, unless --axis gave one.
std::array<double, 3> TipOf(const vp::cli::ParsedArguments& args, std::optional<std::array<double, 3>>& axis)
{
  const int given = args.IsSet("tip") + args.IsSet("tipFile") + args.IsSet("scalpelPose");
  if (given != 1)
  {
    throw vp::cli::UsageError("--tip/--tipFile/--scalpelPose",
      given == 0 ? "give the tip: a point, a point list or the scalpel's transform" : "give only one of them");
  }
  if (args.IsSet("scalpel") && !args.IsSet("scalpelPose"))
  {
    throw vp::cli::UsageError("--scalpel", "the scalpel model is carried by --scalpelPose; give that too");
  }
  if (args.IsSet("tip"))
  {
    return args.GetPoint("tip");
  }
  if (args.IsSet("tipFile"))
  {
    return vp::ReadMarkupsPoints(args.GetString("tipFile")).front().PositionLps;
  }
  const vp::TrackerRegistration pose = vp::ReadTrackerRegistration(args.GetString("scalpelPose"));
  const vtkSmartPointer<vtkScalpelModel> scalpel = args.IsSet("scalpel")
    ? vp::LoadScalpel(args.GetString("scalpel"), vp::ScalpelTipDefinition())
    : vp::MakeDefaultScalpel();
  const double* tip = scalpel->GetTipMm();
  const double* direction = scalpel->GetAxis();
  if (!axis)
  {
    axis = vp::TransformDirection(pose.TrackerToPatient, { direction[0], direction[1], direction[2] });
  }
  return vp::TransformPoint(pose.TrackerToPatient, { tip[0], tip[1], tip[2] });
}

vp::TipDistanceRequest ParseRequest(const vp::cli::ParsedArguments& args)
{
  vp::TipDistanceRequest request;
  vp::DistanceEngineSettings settings;
  settings.Method = args.GetString("method");
  settings.RangeMm = args.GetNumber("rangeMm");
  request.Engine = vp::MakeDistanceEngine(settings); // no device: exit 4 (ReportFailure)
  request.CompareWithExact = settings.Method == "both";
  if (args.IsSet("axis"))
  {
    const std::vector<double> axis = args.GetNumbers("axis");
    if (axis.size() != 3)
    {
      throw vp::InputError("--axis", "expected three numbers x,y,z, got " + std::to_string(axis.size()));
    }
    request.Axis = std::array<double, 3>{ axis[0], axis[1], axis[2] };
  }
  request.TipsMm.push_back(TipOf(args, request.Axis));
  return request;
}

void SetResults(const vp::ProximityResult& r, double rangeMm, vp::cli::ReturnValues& results)
{
  const int nearest = r.NearestIndex();
  if (nearest >= 0)
  {
    const vp::ClassProximity& n = r.Classes[nearest];
    results.Set("nearestClass", n.ClassName);
    results.Set("nearestDistanceMm", SignedDistance(n));
    results.Set("nearestPoint", std::vector<double>(n.ClosestPoint, n.ClosestPoint + 3));
    results.Set("nearestInside", n.Inside && *n.Inside);
  }
  double directional = std::numeric_limits<double>::infinity();
  for (const vp::cli::VesselClassParameter& v : vp::cli::VesselClassParameters())
  {
    for (const vp::ClassProximity& c : r.Classes)
    {
      if (c.ClassName == v.ClassName && c.InRange)
      {
        results.Set(DistanceResult(v), SignedDistance(c));
      }
      directional = c.ClassName == v.ClassName && c.DirectionalMm ? std::min(directional, *c.DirectionalMm) : directional;
    }
  }
  if (directional <= rangeMm)
  {
    results.Set("directionalDistanceMm", directional);
  }
  results.Set("errorBoundMm", r.ErrorBoundMm);
}

/// The tip and, per class within range, its closest point labelled "portal_vein 3.21 mm", a
/// z-buffer answer with the interval its truth lies in ("portal_vein 2.86-3.56 mm"), as the
/// readout shows it.
std::vector<vp::MarkupsPoint> ClosestPoints(const vp::ProximityResult& r, const std::array<double, 3>& tip)
{
  std::vector<vp::MarkupsPoint> points = { { "tip", "the scalpel tip", tip } };
  for (const vp::ClassProximity& c : r.Classes)
  {
    if (!c.InRange)
    {
      continue;
    }
    const bool inside = c.Inside && *c.Inside;
    const std::string distance = (r.ErrorBoundMm > 0 ? vp::DistanceText(c.DistanceMm, r.ErrorBoundMm, 2)
                                                     : vp::cli::FormatNumber(std::round(c.DistanceMm * 100.0) / 100.0)) +
      " mm";
    points.push_back({ c.ClassName + " " + distance + (inside ? " inside" : ""),
      "closest point of " + c.ClassName + " to the tip" +
        (r.ErrorBoundMm > 0 ? ", within " + vp::cli::FormatNumber(r.ErrorBoundMm) + " mm" : std::string(", exact")),
      { c.ClosestPoint[0], c.ClosestPoint[1], c.ClosestPoint[2] } });
  }
  return points;
}

/// The results as a table node (CSV) with its schema beside it (name.schema.csv), which Slicer
/// reads to type the columns: without it every column is text and none can be plotted or sorted.
void WriteResultsTable(const std::string& fileName, const vp::ProximityResult& r, const std::string& method)
{
  std::ostringstream csv;
  csv << "class,distance_mm,inside,in_range,closest_x_lps,closest_y_lps,closest_z_lps,directional_mm,error_bound_mm,engine\n";
  for (const vp::ClassProximity& c : r.Classes)
  {
    // "nan" where there is no answer: an empty cell of a number column reads as 0, a distance
    // this table never measured.
    csv << c.ClassName << "," << (c.InRange ? vp::cli::FormatNumber(c.DistanceMm) : "nan") << ","
        << (c.Inside ? (*c.Inside ? "true" : "false") : "") << "," << (c.InRange ? "true" : "false");
    for (int a = 0; a < 3; ++a)
    {
      csv << "," << (c.InRange ? vp::cli::FormatNumber(c.ClosestPoint[a]) : "nan");
    }
    csv << "," << (c.DirectionalMm ? vp::cli::FormatNumber(*c.DirectionalMm) : "nan") << ","
        << vp::cli::FormatNumber(r.ErrorBoundMm) << "," << method << "\n";
  }
  std::vector<vp::cli::TableColumn> columns;
  for (const char* column : { "class", "distance_mm", "inside", "in_range", "closest_x_lps", "closest_y_lps",
         "closest_z_lps", "directional_mm", "error_bound_mm", "engine" })
  {
    const std::string name = column;
    // true/false (empty when unknown) stay text: Slicer's bit columns read them as 0.
    const bool text = name == "class" || name == "engine" || name == "inside" || name == "in_range";
    columns.push_back({ name, text ? "string" : "double", text ? "" : "mm" });
  }
  vp::cli::WriteTableSchema(fileName, columns);
  vp::WriteFileAtomically(fileName, csv.str());
}

void Run(const vp::cli::ParsedArguments& args, vp::cli::ReturnValues& results)
{
  const std::vector<std::pair<std::string, std::string>> models = vp::cli::GivenVesselModels(args);
  vp::TipDistanceRequest request = ParseRequest(args);
  const double loadStart = vp::NowMs();
  request.Vessels = vp::LoadVesselMeshes(models);
  const double loadMs = vp::NowMs() - loadStart;
  // Slicer's progress bar, from the models read (a refused input writes nothing, not even this):
  // the engine's build and the query, then the outputs.
  vp::cli::FilterProgress progress("VesselProximityDistance");
  progress.Stage("Building the engine and measuring", 0.5);
  const vp::TipDistanceAnswer answer = vp::ComputeTipDistances(request);
  progress.Stage("Writing the results", 0.95);
  if (args.IsSet("report"))
  {
    vp::WriteFileAtomically(args.GetString("report"), vp::TipDistanceReportJson(request, answer, false, loadMs).dump(2) + "\n");
  }
  const vp::ProximityResult& result = answer.Results.at(0);
  const std::string method = request.Engine->GetMethodName();
  if (args.IsSet("closestPoints"))
  {
    vp::WriteFileAtomically(args.GetString("closestPoints"), vp::MarkupsJsonText(ClosestPoints(result, request.TipsMm[0])));
  }
  if (args.IsSet("resultsTable"))
  {
    WriteResultsTable(args.GetString("resultsTable"), result, method);
  }
  SetResults(result, request.Engine->GetRangeMm(), results);
  results.Set("methodUsed", method);
  progress.Finish();
}
} // namespace

int main(int argc, char* argv[])
{
  // Errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  return vp::cli::RunProgram(Describe(), argc, argv, Run);
}
