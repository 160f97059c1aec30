// vesselproximity register: the scalpel's registrations from files, each with its error as IGT
// tools report it, written as a JSON transform (and tip).
#include "vpArguments.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpJsonFile.h"
#include "vpPairedPointRegistration.h"
#include "vpPivotCalibration.h"
#include "vpPointCsv.h"
#include "vpPoseFile.h"
#include "vpSurfaceIcpRegistration.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkPolyData.h>

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
  "usage: vesselproximity register landmarks --model-points M.csv --world-points W.csv -o RESULT.json\n"
  "       vesselproximity register icp --model FILE.stl --points W.csv\n"
  "                                    [--initial T.json | --model-points M.csv --world-points W.csv] -o RESULT.json\n"
  "       vesselproximity register pivot --poses FILE [--min-poses N] [--min-rotation-deg D] -o RESULT.json\n"
  "  landmarks: rigid least-squares fit of the same points in model and world coordinates (one\n"
  "    x,y,z per line, same order); reports each point's error and their RMS (FRE).\n"
  "  icp: fits the model surface to points measured on it (world), from --initial (a RESULT.json\n"
  "    with \"model_to_world\"), from landmarks, or from identity; 25 starts around it (turned 10\n"
  "    and 20 degrees, shifted 5 and 10 mm), then hops to neighbouring minima (2 and 4 degrees,\n"
  "    1.5 and 3 mm) while the fit improves; reports the residuals, and refuses a\n"
  "    fit whose median residual exceeds 1 mm or that leaves more than 3.75% of the points\n"
  "    farther than 4 times it (not noise: a wrong minimum, or points of another instrument).\n"
  "  pivot: the tip offset in tool coordinates from tool-to-world poses pivoting about the tip\n"
  "    (pose file as for track); reports the RMSE. The result, with \"tip_mm\", serves as the\n"
  "    scalpel's tip definition (FILE.json beside the model, or read by --tip's caller).\n"
  "  RESULT.json: {\"method\", \"model_to_world\": [16, row-major], error fields, ...}.\n";

Json MatrixJson(const std::array<double, 16>& m)
{
  return Json(std::vector<double>(m.begin(), m.end()));
}

Json PointJson(const std::array<double, 3>& p)
{
  return Json::array({ p[0], p[1], p[2] });
}

std::array<double, 16> ReadInitialTransform(const std::string& file)
{
  const nlohmann::json root = ReadJsonFile(file, "an initial transform");
  if (!root.is_object() || !root.contains("model_to_world") || !root.at("model_to_world").is_array() ||
    root.at("model_to_world").size() != 16)
  {
    throw InputError(file, "expected \"model_to_world\": an array of 16 numbers (row-major 4x4)");
  }
  std::array<double, 16> m{};
  for (int i = 0; i < 16; ++i)
  {
    const auto& v = root.at("model_to_world")[i];
    if (!v.is_number() || !std::isfinite(v.get<double>()))
    {
      throw InputError(file, "model_to_world: element " + std::to_string(i) + " is not a finite number");
    }
    m[i] = v.get<double>();
  }
  return m;
}

RigidRegistration Landmarks(const Arguments& args)
{
  const auto model = ReadPointCsv(args.Get("--model-points"));
  const auto world = ReadPointCsv(args.Get("--world-points"));
  if (model.size() != world.size())
  {
    throw InputError(args.Get("--world-points"), std::to_string(world.size()) + " points, but " +
        args.Get("--model-points") + " has " + std::to_string(model.size()) + ": the lists must pair up");
  }
  return RegisterPairedPoints(model, world);
}

Json RunLandmarks(const Arguments& args)
{
  const RigidRegistration r = Landmarks(args);
  std::printf("landmarks: %zu points, FRE (RMS) %.3f mm\n", r.PointErrorsMm.size(), r.RmsErrorMm);
  for (std::size_t i = 0; i < r.PointErrorsMm.size(); ++i)
  {
    std::printf("  point %zu: %.3f mm\n", i + 1, r.PointErrorsMm[i]);
  }
  return { { "method", "landmarks" }, { "model_to_world", MatrixJson(r.ModelToWorld) }, { "fre_mm", r.RmsErrorMm },
    { "point_errors_mm", r.PointErrorsMm } };
}

Json RunIcp(const Arguments& args)
{
  vtkNew<vtkVesselMeshReader> reader;
  reader->SetFileName(args.Get("--model"));
  reader->Read();
  const auto points = ReadPointCsv(args.Get("--points"));
  std::array<double, 16> initial{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };
  std::string start = "identity";
  if (args.Has("--initial"))
  {
    initial = ReadInitialTransform(args.Get("--initial"));
    start = args.Get("--initial");
  }
  else if (args.Has("--model-points") || args.Has("--world-points"))
  {
    const RigidRegistration guess = Landmarks(args);
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
    throw InputError(args.Get("--points"), why);
  }
  std::printf("icp: %zu points from %s, best of %d starts, %d iterations, mean residual %.3f mm (median %.3f, p95 %.3f)\n",
    points.size(), start.c_str(), r.Starts, r.Iterations, r.MeanResidualMm, r.MedianResidualMm, r.P95ResidualMm);
  return { { "method", "icp" }, { "model_to_world", MatrixJson(r.ModelToWorld) }, { "mean_residual_mm", r.MeanResidualMm },
    { "median_residual_mm", r.MedianResidualMm }, { "p95_residual_mm", r.P95ResidualMm }, { "far_fraction", r.FarFraction },
    { "iterations", r.Iterations }, { "starts", r.Starts }, { "points", points.size() }, { "initial", start } };
}

Json RunPivot(const Arguments& args)
{
  const auto poses = ReadPoseFile(args.Get("--poses"));
  std::vector<std::array<double, 16>> matrices;
  for (const auto& p : poses)
  {
    matrices.push_back(p.ModelToWorld);
  }
  const int minPoses = args.GetInteger("--min-poses", 6);
  if (minPoses < 3)
  {
    throw InputError("--min-poses", "must be at least 3");
  }
  const PivotCalibration r =
    CalibratePivot(matrices, static_cast<std::size_t>(minPoses), args.GetNumber("--min-rotation-deg", 10.0));
  std::printf("pivot: %zu poses turning up to %.1f deg, tip (%.3f, %.3f, %.3f) mm in tool coordinates, RMSE %.3f mm\n",
    poses.size(), r.RotationSpreadDeg, r.TipInToolMm[0], r.TipInToolMm[1], r.TipInToolMm[2], r.RmseMm);
  // A translation to the tip: placing the model by it puts its origin at the tip.
  std::array<double, 16> tipToTool{ 1, 0, 0, r.TipInToolMm[0], 0, 1, 0, r.TipInToolMm[1], 0, 0, 1, r.TipInToolMm[2], 0, 0, 0,
    1 };
  return { { "method", "pivot" }, { "tip_mm", PointJson(r.TipInToolMm) }, { "pivot_mm", PointJson(r.PivotInWorldMm) },
    { "rmse_mm", r.RmseMm }, { "rotation_spread_deg", r.RotationSpreadDeg }, { "poses", poses.size() },
    { "tip_to_tool", MatrixJson(tipToTool) } };
}
} // namespace

int RunRegisterCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv) || argv.empty())
  {
    std::cout << Usage;
    return argv.empty() ? 2 : 0;
  }
  const std::string method = argv[0];
  const Arguments args(std::vector<std::string>(argv.begin() + 1, argv.end()),
    { "--model-points", "--world-points", "--model", "--points", "--initial", "--poses", "--min-poses",
      "--min-rotation-deg", "-o" },
    {});
  if (!args.Positional().empty())
  {
    throw InputError(args.Positional()[0], "unexpected argument (see vesselproximity register --help)");
  }
  auto require = [&](std::initializer_list<const char*> names) {
    for (const char* name : names)
    {
      if (!args.Has(name))
      {
        throw InputError(name, "is required for register " + method + " (see vesselproximity register --help)");
      }
    }
  };
  Json result;
  if (method == "landmarks")
  {
    require({ "--model-points", "--world-points", "-o" });
    result = RunLandmarks(args);
  }
  else if (method == "icp")
  {
    require({ "--model", "--points", "-o" });
    result = RunIcp(args);
  }
  else if (method == "pivot")
  {
    require({ "--poses", "-o" });
    result = RunPivot(args);
  }
  else
  {
    throw InputError(method, "unknown registration (landmarks, icp or pivot)");
  }
  WriteFileAtomically(args.Get("-o"), result.dump(2) + "\n");
  std::printf("wrote %s\n", args.Get("-o").c_str());
  return 0;
}
} // namespace vp
