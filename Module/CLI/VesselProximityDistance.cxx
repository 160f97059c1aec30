// VesselProximityDistance: `vesselproximity distance` as a 3D Slicer CLI module. Slicer hands
// over the vessel models (temporary files) and the scalpel tip (a markups point, in LPS); the
// program returns the distance to each vessel class through the return-parameter file and,
// when asked, writes the distance command's JSON report.
#include "vpCliDescription.h"
#include "vpOutputFile.h"
#include "vpClock.h"
#include "vpDistanceEngineFactory.h"
#include "vpInputError.h"
#include "vpTipDistanceQuery.h"

#include <vtkObject.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <limits>

#ifndef VP_VERSION
#define VP_VERSION "0.1.0"
#endif

namespace
{
using vp::cli::Channel;
using vp::cli::Parameter;
using vp::cli::ParameterType;

/// The vessel classes, each with the parameter that brings its model and the one that returns
/// its distance.
struct VesselClass
{
  const char* Parameter;
  const char* ClassName;
  const char* DistanceResult;
  const char* Label;
};
const VesselClass Vessels[] = {
  { "portalVein", "portal_vein", "portalVeinDistanceMm", "Portal vein" },
  { "hepaticArtery", "hepatic_artery", "hepaticArteryDistanceMm", "Hepatic artery" },
  { "hepaticVein", "hepatic_vein", "hepaticVeinDistanceMm", "Hepatic vein" },
};

/// -1 marks "no answer" in the distance results: distances are never negative, and Slicer's
/// number fields show -1 where NaN would show as garbage or be clamped.
const char* NoDistance = "-1";

vp::cli::ParameterGroup ModelsGroup()
{
  vp::cli::ParameterGroup models{ "Vessel models", "Surface models of the vessel systems; give at least one", {} };
  for (const VesselClass& v : Vessels)
  {
    models.Parameters.push_back(Parameter(ParameterType::Geometry, v.Parameter)
                                  .SetTypeAttribute("model")
                                  .SetFileExtensions(".stl,.vtk,.vtp,.obj")
                                  .SetLongFlag(v.Parameter)
                                  .SetLogicName("Vessels")
                                  .SetChannel(Channel::Input)
                                  .SetLabel(v.Label)
                                  .SetDescription(std::string(v.Label) + " surface model (class " + v.ClassName +
                                    "): STL, VTK, VTP or OBJ; a SPACE=RAS/LPS header tag is honoured, untagged "
                                    "files are LPS."));
  }
  return models;
}

vp::cli::ParameterGroup ScalpelGroup()
{
  vp::cli::ParameterGroup scalpel{ "Scalpel", "Tip position and direction of the scalpel", {} };
  scalpel.Parameters.push_back(Parameter(ParameterType::Point, "tip")
                                 .SetCoordinateSystem("lps")
                                 .SetLongFlag("tip")
                                 .SetRequired()
                                 .SetLabel("Scalpel tip")
                                 .SetDescription("The scalpel tip, one point (Slicer passes it in LPS). Required."));
  scalpel.Parameters.push_back(Parameter(ParameterType::DoubleVector, "axis")
                                 .SetLongFlag("axis")
                                 .SetLogicName("Axis")
                                 .SetLabel("Scalpel axis")
                                 .SetDescription("Direction the scalpel points, x,y,z in LPS (need not be unit "
                                                 "length), for the directional distance along it. Optional."));
  return scalpel;
}

vp::cli::ParameterGroup EngineGroup()
{
  vp::cli::ParameterGroup engine{ "Distance engine", "Which engine answers, and how far it looks", {} };
  engine.Parameters.push_back(Parameter(ParameterType::StringEnumeration, "method")
                                .SetLongFlag("method")
                                .SetLogicName("Method")
                                .SetLabel("Method")
                                .SetDescription("exact: BVH, exact. zbuffer: Vulkan depth layers, within the error "
                                                "bound. both: z-buffer checked against exact. auto: z-buffer when a "
                                                "Vulkan device opens, else exact.")
                                .SetDefault(vp::DistanceEngineSettings().Method)
                                .SetElements({ "exact", "zbuffer", "both", "auto" }));
  engine.Parameters.push_back(Parameter(ParameterType::Float, "rangeMm")
                                .SetLongFlag("rangeMm")
                                .SetLogicName("RangeMm")
                                .SetLabel("Range (mm)")
                                .SetDescription("Classes further from the tip than this return -1.")
                                .SetDefault(vp::cli::FormatNumber(vtkVesselDistanceEngine::DefaultRangeMm))
                                .SetRange(1.0, 1000.0, 1.0));
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
  vp::cli::ParameterGroup out{ "Results", "Distances from the tip (-1: model not given, or beyond the range)", {} };
  auto result = [&](ParameterType type, const char* name, const char* label, const std::string& text,
                  const char* value) {
    out.Parameters.push_back(
      Parameter(type, name).SetChannel(Channel::Output).SetLabel(label).SetDescription(text).SetDefault(value));
  };
  result(ParameterType::String, "nearestClass", "Nearest class",
    "The vessel class nearest to the tip: portal_vein, hepatic_artery, hepatic_vein, or none within range.", "none");
  result(ParameterType::Float, "nearestDistanceMm", "Nearest distance (mm)",
    "Distance to the nearest class (penetration depth when the tip is inside it); -1 when none is within range.",
    NoDistance);
  result(ParameterType::Boolean, "nearestInside", "Tip inside",
    "True when the tip is inside the nearest vessel (closed models only).", "false");
  result(ParameterType::DoubleVector, "nearestPoint", "Nearest point (LPS)",
    "Closest point on the nearest class, x,y,z in LPS; empty when none is within range.", "");
  for (const VesselClass& v : Vessels)
  {
    result(ParameterType::Float, v.DistanceResult, (std::string(v.Label) + " distance (mm)").c_str(),
      std::string("Distance to the ") + v.ClassName + " model; -1 when not given or beyond the range.", NoDistance);
  }
  result(ParameterType::Float, "directionalDistanceMm", "Directional distance (mm)",
    "Distance along the axis to the first vessel surface; -1 without an axis or when none is hit within range.",
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
    "VesselProximityDistance", "Vessel Proximity Distance", VP_VERSION, { ModelsGroup(), ScalpelGroup(), EngineGroup(), ResultsGroup() });
  d.Description =
    "Distance from a scalpel tip to the nearest surface point of each vessel system (portal vein, "
    "hepatic artery, hepatic vein), for liver surgery navigation. The exact engine answers from a "
    "BVH in double precision; the z-buffer engine (the GPU method of Noborio et al., on Vulkan) "
    "answers within a stated error bound. Coordinates are LPS millimetres. A class whose model is not "
    "given, or that lies beyond the range, returns -1. Exit codes: 0 success, 1 bad input, 2 bad usage, "
    "3 internal error, 4 no usable Vulkan device (zbuffer, both). Same as `vesselproximity distance`.";
  d.Acknowledgements =
    "Implements and extends Noborio et al., \"Comparison of GPU-based and CPU-based Algorithms for "
    "Determining the Minimum Distance between a CUSA Scalpel and Blood Vessels\".";
  return d;
}

vp::TipDistanceRequest ParseRequest(const vp::cli::ParsedArguments& args)
{
  vp::TipDistanceRequest request;
  vp::DistanceEngineSettings settings;
  settings.Method = args.GetString("method");
  settings.RangeMm = args.GetNumber("rangeMm");
  request.Engine = vp::MakeDistanceEngine(settings); // no device: exit 4 (ReportFailure)
  request.CompareWithExact = settings.Method == "both";
  request.TipsMm.push_back(args.GetPoint("tip"));
  if (args.IsSet("axis"))
  {
    const std::vector<double> axis = args.GetNumbers("axis");
    if (axis.size() != 3)
    {
      throw vp::InputError("--axis", "expected three numbers x,y,z, got " + std::to_string(axis.size()));
    }
    request.Axis = std::array<double, 3>{ axis[0], axis[1], axis[2] };
  }
  return request;
}

/// The models given, each from its own parameter: file names are names, commas and all.
std::vector<std::pair<std::string, std::string>> GivenModels(const vp::cli::ParsedArguments& args)
{
  std::vector<std::pair<std::string, std::string>> vessels;
  for (const VesselClass& v : Vessels)
  {
    if (args.IsSet(v.Parameter))
    {
      vessels.emplace_back(v.ClassName, args.GetString(v.Parameter));
    }
  }
  if (vessels.empty())
  {
    throw vp::cli::UsageError("--portalVein/--hepaticArtery/--hepaticVein", "give at least one vessel model");
  }
  return vessels;
}

void SetResults(const vp::ProximityResult& r, double rangeMm, vp::cli::ReturnValues& results)
{
  const int nearest = r.NearestIndex();
  if (nearest >= 0)
  {
    const vp::ClassProximity& n = r.Classes[nearest];
    results.Set("nearestClass", n.ClassName);
    results.Set("nearestDistanceMm", n.DistanceMm);
    results.Set("nearestPoint", std::vector<double>(n.ClosestPoint, n.ClosestPoint + 3));
    results.Set("nearestInside", n.Inside && *n.Inside);
  }
  double directional = std::numeric_limits<double>::infinity();
  for (const VesselClass& v : Vessels)
  {
    for (const vp::ClassProximity& c : r.Classes)
    {
      if (c.ClassName == v.ClassName && c.InRange)
      {
        results.Set(v.DistanceResult, c.DistanceMm);
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

void Run(const vp::cli::ParsedArguments& args, vp::cli::ReturnValues& results)
{
  const std::vector<std::pair<std::string, std::string>> models = GivenModels(args);
  vp::TipDistanceRequest request = ParseRequest(args);
  const double loadStart = vp::NowMs();
  request.Vessels = vp::LoadVesselMeshes(models);
  const double loadMs = vp::NowMs() - loadStart;
  const vp::TipDistanceAnswer answer = vp::ComputeTipDistances(request);
  if (args.IsSet("report"))
  {
    vp::WriteFileAtomically(args.GetString("report"), vp::TipDistanceReportJson(request, answer, false, loadMs).dump(2) + "\n");
  }
  SetResults(answer.Results.at(0), request.Engine->GetRangeMm(), results);
  results.Set("methodUsed", std::string(request.Engine->GetMethodName()));
}
} // namespace

int main(int argc, char* argv[])
{
  // Errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  return vp::cli::RunProgram(Describe(), argc, argv, Run);
}
