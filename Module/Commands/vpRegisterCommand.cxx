// vesselproximity register: the scalpel's registrations from files, each with its error as IGT
// tools report it, written as a JSON transform (and tip).
#include "vpArguments.h"
#include "vpOutputFile.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpJsonFile.h"
#include "vpPairedPointRegistration.h"
#include "vpPivotCalibration.h"
#include "vpPointCsv.h"
#include "vpDwellPoints.h"
#include "vpPoseFile.h"
#include "vpRegistrationFile.h"
#include "vpTrackingOptions.h"
#include "vpSurfaceIcpRegistration.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace vp
{
namespace
{
using Json = nlohmann::ordered_json;

Json MatrixJson(const std::array<double, 16>& m)
{
  return Json(std::vector<double>(m.begin(), m.end()));
}

Json PointJson(const std::array<double, 3>& p)
{
  return Json::array({ p[0], p[1], p[2] });
}

/// What a registration says once its result is written (a refusal of the output leaves no word
/// of a result that was never saved).
template <typename... Values>
void Say(std::string& said, const char* format, Values... values)
{
  char line[512];
  std::snprintf(line, sizeof(line), format, values...);
  said += line;
}

/// The points where a recorded stylus rested, in world (or reference) coordinates.
std::vector<Point3> DwellWorldPoints(const cli::ParsedArguments& args, std::string& said)
{
  const std::string sequence = args.GetString("sequence");
  const auto poses = ReadPoseFile(sequence, ParsePoseReading(args));
  std::vector<double> times;
  std::vector<std::array<double, 16>> matrices;
  for (const TrackedPose& p : poses)
  {
    times.push_back(p.TimeS);
    matrices.push_back(p.ModelToWorld);
  }
  const std::vector<DwellPoint> dwells = FindDwellPoints(times, matrices, ReadMatrixText(args.GetString("tipTransform")));
  std::vector<Point3> world;
  for (std::size_t i = 0; i < dwells.size(); ++i)
  {
    const DwellPoint& d = dwells[i];
    world.push_back(d.PointMm);
    Say(said, "  rest %zu: %.2f-%.2f s, (%.2f, %.2f, %.2f) mm, tip within %.2f mm, shaft moved %.0f mm\n", i + 1, d.StartS, d.EndS,
      d.PointMm[0], d.PointMm[1], d.PointMm[2], d.TipSpreadMm, d.ShaftMotionMm);
  }
  return world;
}

RigidRegistration Landmarks(const cli::ParsedArguments& args, std::string& said)
{
  const auto model = ReadPointCsv(args.GetString("modelPoints"));
  const bool recorded = args.IsSet("sequence");
  const auto world = recorded ? DwellWorldPoints(args, said) : ReadPointCsv(args.GetString("worldPoints"));
  if (model.size() != world.size())
  {
    const std::string source = recorded ? args.GetString("sequence") : args.GetString("worldPoints");
    throw InputError(source, std::to_string(world.size()) + (recorded ? " rests of the stylus" : " points") + ", but " +
        args.GetString("modelPoints") + " has " + std::to_string(model.size()) + ": the lists must pair up");
  }
  return RegisterPairedPoints(model, world);
}


Json RunLandmarks(const cli::ParsedArguments& args, std::string& said)
{
  const RigidRegistration r = Landmarks(args, said);
  Say(said, "landmarks: %zu points, FRE (RMS) %.3f mm\n", r.PointErrorsMm.size(), r.RmsErrorMm);
  for (std::size_t i = 0; i < r.PointErrorsMm.size(); ++i)
  {
    Say(said, "  point %zu: %.3f mm\n", i + 1, r.PointErrorsMm[i]);
  }
  return { { "method", "landmarks" }, { "model_to_world", MatrixJson(r.ModelToWorld) }, { "fre_mm", r.RmsErrorMm },
    { "point_errors_mm", r.PointErrorsMm } };
}

Json RunIcp(const cli::ParsedArguments& args, std::string& said)
{
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(args.GetString("model"));
  reader->Read();
  const auto points = ReadPointCsv(args.GetString("points"));
  std::array<double, 16> initial{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::string start = "identity";
  if (args.IsSet("initial"))
  {
    initial = ReadModelToWorld(args.GetString("initial"), "an initial transform");
    start = args.GetString("initial");
  }
  else if (args.IsSet("modelPoints") || args.IsSet("worldPoints"))
  {
    std::string ignored;
    const RigidRegistration guess = Landmarks(args, ignored);
    initial = guess.ModelToWorld;
    start = "landmarks (FRE " + NumberText(guess.RmsErrorMm, 3) + " mm)";
  }
  const SurfaceRegistration r = RegisterSurfaceIcpMultiStart(reader->GetOutput(), points, initial);
  if (!r.ExplainsThePoints())
  {
    char why[400];
    std::snprintf(why, sizeof(why),
      "ICP from %s found no fit that explains the points (best of %d starts: median residual %.3f mm, %.1f%% of "
      "the points farther than %g times that; noise leaves a median under %g mm and at most %.3g%%): start closer "
      "(landmarks: --model-points, --world-points; or --initial), or check that the points were measured on this model",
      start.c_str(), r.Starts, r.MedianResidualMm, 100.0 * r.FarFraction, SurfaceRegistration::FarResidualFactor,
      SurfaceRegistration::MaximumMedianResidualMm, 100.0 * SurfaceRegistration::MaximumFarFraction);
    throw InputError(args.GetString("points"), why);
  }
  double squares = 0.0;
  for (double e : r.ResidualsMm)
  {
    squares += e * e;
  }
  const double fre = std::sqrt(squares / static_cast<double>(std::max<std::size_t>(1, r.ResidualsMm.size())));
  Say(said, "icp: %zu points from %s, best of %d starts, %d iterations, FRE (RMS) %.3f mm, mean residual %.3f mm (median %.3f, "
    "p95 %.3f)\n", points.size(), start.c_str(), r.Starts, r.Iterations, fre, r.MeanResidualMm, r.MedianResidualMm, r.P95ResidualMm);
  return { { "method", "icp" }, { "model_to_world", MatrixJson(r.ModelToWorld) }, { "fre_mm", fre },
    { "point_errors_mm", r.ResidualsMm }, { "mean_residual_mm", r.MeanResidualMm },
    { "median_residual_mm", r.MedianResidualMm }, { "p95_residual_mm", r.P95ResidualMm }, { "far_fraction", r.FarFraction },
    { "iterations", r.Iterations }, { "starts", r.Starts }, { "points", points.size() }, { "initial", start } };
}

Json RunPivot(const cli::ParsedArguments& args, std::string& said)
{
  const auto poses = ReadPoseFile(args.GetString(args.IsSet("sequence") ? "sequence" : "poses"), ParsePoseReading(args));
  std::vector<std::array<double, 16>> matrices;
  for (const auto& p : poses)
  {
    matrices.push_back(p.ModelToWorld);
  }
  const PivotCalibration r = CalibratePivot(
    matrices, static_cast<std::size_t>(args.GetInteger("minPoses")), args.GetNumber("minRotationDeg"));
  Say(said, "pivot: %zu poses turning up to %.1f deg, tip (%.3f, %.3f, %.3f) mm in tool coordinates, RMSE %.3f mm\n",
    poses.size(), r.RotationSpreadDeg, r.TipInToolMm[0], r.TipInToolMm[1], r.TipInToolMm[2], r.RmseMm);
  // A translation to the tip: placing the model by it puts its origin at the tip.
  std::array<double, 16> tipToTool{ 1, 0, 0, r.TipInToolMm[0], 0, 1, 0, r.TipInToolMm[1], 0, 0, 1, r.TipInToolMm[2], 0, 0, 0,
    1 };
  // No model_to_world: a calibration places no model in the world, and a registration reader
  // would take it for one (every tip moved by the tip's offset). fre_mm: the poses' RMS miss of
  // the pivot, as landmarks' FRE is the points' RMS miss.
  return { { "method", "pivot" }, { "fre_mm", r.RmseMm },
    { "point_errors_mm", r.PoseErrorsMm }, { "tip_mm", PointJson(r.TipInToolMm) }, { "pivot_mm", PointJson(r.PivotInWorldMm) },
    { "rmse_mm", r.RmseMm }, { "rotation_spread_deg", r.RotationSpreadDeg }, { "poses", poses.size() },
    { "tip_to_tool", MatrixJson(tipToTool) } };
}
} // namespace

cli::ModuleDescription DescribeRegisterCommand()
{
  using cli::ParameterType;
  auto input = [](const char* flag, const char* placeholder, const char* description) {
    return Option(ParameterType::File, flag, description).SetChannel(cli::Channel::Input).SetPlaceholder(placeholder);
  };
  return cli::ModuleDescription::Subcommand("vesselproximity register",
    "scalpel registration: landmarks, surface ICP, pivot calibration (JSON result)",
    "landmarks (needs --model-points, --world-points): rigid least-squares fit of the same points in model and "
    "world coordinates (one x,y,z per line, same order); reports each point's error and their RMS (FRE).\n"
    "icp (needs --model, --points): fits the model surface to points measured on it (world), from --initial, from "
    "landmarks, or from identity; 25 starts around it (turned 10 and 20 degrees, shifted 5 and 10 mm), then hops "
    "to neighbouring minima (2 and 4 degrees, 1.5 and 3 mm) while the fit improves; reports the residuals, and "
    "refuses a fit whose median residual exceeds 1 mm or that leaves more than 3.75% of the points farther than 4 "
    "times it (not noise: a wrong minimum, or points of another instrument).\n"
    "pivot (needs --poses, or --sequence: a PLUS recording with --tool and --reference): the tip offset in tool "
    "coordinates from tool-to-world poses pivoting about the tip (pose file as for track); reports each pose's miss "
    "of the pivot and their RMS (fre_mm). The result, with \"tip_mm\", serves as the scalpel's tip "
    "definition (FILE.json beside the model, or read by --tip's caller).\n"
    "RESULT.json: {\"method\", \"model_to_world\": [16, row-major] (not pivot's: a calibration, its tip_to_tool), \"fre_mm\", "
    "\"point_errors_mm\" (each point's, or pose's, error), ...}.",
    {
      { "Registration", "",
        {
          cli::Parameter(ParameterType::StringEnumeration, "method")
            .SetIndex(0)
            .SetRequired()
            .SetElements({ "landmarks", "icp", "pivot" })
            .SetPlaceholder("METHOD")
            .SetDescription("The registration: landmarks, icp or pivot."),
          Option(ParameterType::File, "output", "The result.").SetFlag("o").SetChannel(cli::Channel::Output).SetPlaceholder("RESULT.json").SetRequired(),
        } },
      { "landmarks (also icp's start)", "",
        { input("model-points", "M.csv", "Points in model coordinates."),
          input("world-points", "W.csv", "The same points in world coordinates."),
          input("sequence", "REC.igs.mha",
            "Instead of --world-points (pivot: instead of --poses, the pivoting itself): a recording (PLUS sequence or pose file, --tool and --reference as for track) "
            "of a stylus resting about a second on each landmark in turn, pivoting on it; the rests are matched to "
            "--model-points in order."),
          input("tip-transform", "T.txt", "With --sequence: the stylus tip in tool coordinates, a 4x4 matrix (16 numbers, row-major).") } },
      { "icp", "",
        { input("model", "FILE.stl", "The model surface."), input("points", "W.csv", "Points measured on it, in world coordinates."),
          input("initial", "T.json", "The start: a RESULT.json with \"model_to_world\".") } },
      { "pivot", "",
        { input("poses", "FILE", "Tool-to-world poses pivoting about the tip."),
          Option(ParameterType::Integer, "min-poses", "The fewest poses accepted.").SetPlaceholder("N").SetDefault("6").SetRange(3, 1000000000, 1),
          Option(ParameterType::Double, "min-rotation-deg", "The least rotation the poses must span.").SetPlaceholder("D").SetDefault("10") } },
      { "Recordings (pivot's poses, landmarks' sequence)", "", PoseReadingOptions() },
    });
}

int RunRegisterCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  const std::string method = args.GetString("method");
  // Which options a registration needs depends on which it is: beyond what a table can say.
  auto require = [&](std::initializer_list<std::pair<const char*, const char*>> options) {
    for (const auto& [name, flag] : options)
    {
      if (!args.IsSet(name))
      {
        throw InputError(flag, "is required for register " + method + " (see vesselproximity register --help)");
      }
    }
  };
  Json result;
  std::string said;
  if (method == "landmarks")
  {
    require({ { "modelPoints", "--model-points" } });
    if (args.IsSet("sequence"))
    {
      require({ { "tipTransform", "--tip-transform" } });
    }
    else
    {
      require({ { "worldPoints", "--world-points" } });
    }
    result = RunLandmarks(args, said);
  }
  else if (method == "icp")
  {
    require({ { "model", "--model" }, { "points", "--points" } });
    result = RunIcp(args, said);
  }
  else // pivot: the parser accepts only the three
  {
    if (args.IsSet("poses") == args.IsSet("sequence"))
    {
      throw InputError("--poses/--sequence", "register pivot takes its poses from one of --poses FILE and --sequence REC.igs.mha");
    }
    result = RunPivot(args, said);
  }
  WriteFileAtomically(args.GetString("output"), result.dump(2) + "\n");
  std::printf("%swrote %s\n", said.c_str(), args.GetString("output").c_str());
  return 0;
}
} // namespace vp
