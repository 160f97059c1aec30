#include "vpEngineOptions.h"

#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vpVulkanContext.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkZBufferVesselDistance.h"

#include <algorithm>
#include <cmath>
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
    { "ResolutionPx", "--resolution" }, { "LayerMode", "--layers" }, { "BoxMode", "--box" },
    { "MovingBoxSizeMm", "--box-size" }, { "DistanceBins", "--bins" }, { "CellSizeMm/ResolutionPx", "--cell/--resolution" },
    { "Vessels", "--vessels" } };
  for (const auto& [name, flag] : flags)
  {
    if (parameter == name)
    {
      return flag;
    }
  }
  return parameter;
}

namespace
{
vtkSmartPointer<vtkZBufferVesselDistance> MakeZBuffer(const Arguments& args)
{
  auto z = vtkSmartPointer<vtkZBufferVesselDistance>::New();
  z->SetDeviceSelector(args.Get("--device"));
  if (args.Has("--cell"))
  {
    z->SetCellSizeMm(args.GetNumber("--cell", z->GetCellSizeMm()));
  }
  z->SetResolutionPx(args.GetInteger("--resolution", 0));
  const std::string layers = args.Get("--layers", "exact");
  if (layers != "exact" && layers != "paper")
  {
    throw InputError("--layers", "expected exact or paper, got '" + layers + "'");
  }
  z->SetLayerMode(layers == "paper" ? vtkZBufferVesselDistance::PaperNearFar : vtkZBufferVesselDistance::ExactIntervals);
  const std::string box = args.Get("--box", "fixed");
  if (box != "fixed" && box != "moving")
  {
    throw InputError("--box", "expected fixed or moving, got '" + box + "'");
  }
  z->SetBoxMode(box == "moving" ? vtkZBufferVesselDistance::MovingWithTip : vtkZBufferVesselDistance::FixedAroundVessels);
  if (args.Has("--box-size"))
  {
    const auto size = ParsePoint(args.Get("--box-size"), "--box-size");
    z->SetMovingBoxSizeMm(size[0], size[1], size[2]);
  }
  z->SetDistanceBins(args.GetInteger("--bins", 0, 0)); // 0: off, as the help says
  // Open the device now: a missing one is reported before any file is read.
  z->GetDeviceName();
  return z;
}
} // namespace

vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const Arguments& args)
{
  vtkSmartPointer<vtkVesselDistanceEngine> engine;
  if (method == "exact")
  {
    engine = vtkSmartPointer<vtkExactVesselDistance>::New();
  }
  else if (method == "brute")
  {
    engine = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  }
  else if (method == "zbuffer" || method == "both")
  {
    engine = MakeZBuffer(args);
  }
  else if (method == "auto")
  {
    try
    {
      engine = MakeZBuffer(args);
    }
    catch (const DeviceError& e)
    {
      std::cerr << "vesselproximity: note: " << e.what() << "; --method auto uses the exact engine\n";
      engine = vtkSmartPointer<vtkExactVesselDistance>::New();
    }
  }
  else
  {
    throw InputError("--method", "unknown method '" + method + "' (exact, zbuffer, both, brute or auto)");
  }
  if (args.Has("--range"))
  {
    engine->SetRangeMm(args.GetNumber("--range", engine->GetRangeMm()));
  }
  return engine;
}

} // namespace vp
