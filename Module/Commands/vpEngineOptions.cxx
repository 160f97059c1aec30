#include "vpEngineOptions.h"

#include "vpInputError.h"
#include "vpPointCsv.h"

#include <iostream>

namespace vp
{
const char* EngineSettingsUsage =
  "  --range MM: classes further than this are reported as null (default 50 mm).\n"
  "  z-buffer settings: --device NAME|INDEX (default: a GPU if any, else lavapipe),\n"
  "    --cell MM (cell edge, default 0.4: bound 0.35 mm), --resolution PX (pixels across the\n"
  "    box instead), --layers exact|paper (paper: nearest and farthest depth only),\n"
  "    --box fixed|moving, --box-size X,Y,Z (moving box, default 106,106,213 mm),\n"
  "    --bins N (the paper's distance bits: N bins over the range, a multiple of 16; 0, the\n"
  "    default, off).\n";

std::string EngineOptionsUsage(const std::set<std::string>& methods)
{
  static const std::pair<const char*, const char*> all[] = {
    { "exact", "exact (default; Embree BVH, exact)" },
    { "zbuffer", "zbuffer (Vulkan depth layers, within error_bound_mm)" },
    { "both", "both (z-buffer, checked against exact)" },
    { "brute", "brute (the paper's CPU algorithm)" },
    { "auto", "auto (z-buffer when a Vulkan device opens, else exact)" },
  };
  std::string text = "  --method, one of:\n";
  for (const auto& [name, description] : all)
  {
    if (methods.count(name))
    {
      text += "    " + std::string(description) + "\n";
    }
  }
  return text + EngineSettingsUsage;
}

std::set<std::string> EngineValueOptions()
{
  return { "--method", "--range", "--device", "--cell", "--resolution", "--layers", "--box", "--box-size", "--bins" };
}

std::string FlagOfParameter(const std::string& parameter)
{
  static const std::pair<const char*, const char*> flags[] = { { "RangeMm", "--range" }, { "CellSizeMm", "--cell" },
    { "ResolutionPx", "--resolution" }, { "LayerMode", "--layers" }, { "BoxMode", "--box" }, { "MovingBoxSizeMm", "--box-size" },
    { "DistanceBins", "--bins" }, { "CellSizeMm/ResolutionPx", "--cell/--resolution" }, { "Method", "--method" },
    { "Vessels", "--vessels" }, { "Axis", "--axis" }, { "SmoothingFactor", "--smoothing" },
    { "SmoothingIterations", "--smoothing-iterations" }, { "DecimationFactor", "--decimation" },
    { "FrameBudgetMs", "--frame-budget-ms" }, { "HysteresisMm", "--hysteresis-mm" } };
  for (const auto& [name, flag] : flags)
  {
    if (parameter == name)
    {
      return flag;
    }
  }
  return parameter;
}

DistanceEngineSettings ParseEngineSettings(const std::string& method, const Arguments& args)
{
  DistanceEngineSettings s;
  s.Method = method;
  if (args.Has("--range"))
  {
    s.RangeMm = args.GetNumber("--range", 0.0);
  }
  s.DeviceSelector = args.Get("--device");
  if (args.Has("--cell"))
  {
    s.CellSizeMm = args.GetNumber("--cell", 0.0);
  }
  s.ResolutionPx = args.GetInteger("--resolution", 0);
  s.LayerMode = args.Get("--layers", "exact");
  s.BoxMode = args.Get("--box", "fixed");
  if (args.Has("--box-size"))
  {
    s.MovingBoxSizeMm = ParsePoint(args.Get("--box-size"), "--box-size");
  }
  s.DistanceBins = args.GetInteger("--bins", 0, 0); // 0: off, as the help says
  return s;
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const Arguments& args)
{
  std::string note;
  auto engine = MakeDistanceEngine(ParseEngineSettings(method, args), &note);
  if (!note.empty())
  {
    std::cerr << "vesselproximity: note: " << note << "; --method auto uses the exact engine\n";
  }
  return engine;
}
} // namespace vp
