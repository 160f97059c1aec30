#include "vpEngineOptions.h"

#include "vpInputError.h"
#include "vpPointCsv.h"
#include "vtkZBufferVesselDistance.h"

#include <iostream>

namespace vp
{
cli::ParameterGroup EngineOptions(const std::vector<std::string>& methods)
{
  using cli::ParameterType;
  const DistanceEngineSettings defaults;
  cli::ParameterGroup group{ "Distance engine", "", {} };
  if (!methods.empty())
  {
    const std::string help = EngineMethodHelp(methods, "; ");
    group.Parameters.push_back(
      Option(ParameterType::StringEnumeration, "method", help + ".").SetElements(methods).SetDefault(defaults.Method).SetLogicName("Method"));
  }
  group.Parameters.push_back(Option(ParameterType::Double, "range", "Classes further than this are reported as out of range (null).")
                               .SetPlaceholder("MM")
                               .SetDefault(cli::FormatNumber(vtkVesselDistanceEngine::DefaultRangeMm))
                               .SetLogicName("RangeMm"));
  // The z-buffer's defaults as its engine declares them, and the bound they give.
  const double* box = vtkZBufferVesselDistance::DefaultMovingBoxSizeMm;
  const double cell = vtkZBufferVesselDistance::DefaultCellSizeMm;
  const std::vector<cli::Parameter> zbuffer = {
    Option(ParameterType::String, "device", "z-buffer: the Vulkan device by name or index (default: a GPU if any, else lavapipe).")
      .SetLogicName("DeviceSelector")
      .SetPlaceholder("NAME|INDEX"),
    Option(ParameterType::Double, "cell",
      "z-buffer: the cell edge (default " + cli::FormatNumber(cell) + " mm: error bound " +
        FixedText(vtkZBufferVesselDistance::ErrorBoundForCellMm(cell), "%.2f") + " mm).")
      .SetPlaceholder("MM")
      .SetLogicName("CellSizeMm"),
    Option(ParameterType::Integer, "resolution", "z-buffer: pixels across the box, instead of --cell.").SetPlaceholder("PX").SetLogicName("ResolutionPx"),
    Option(ParameterType::StringEnumeration, "layers", "z-buffer: exact intervals, or the paper's nearest and farthest depth only.")
      .SetElements({ "exact", "paper" }).SetDefault(defaults.LayerMode).SetLogicName("LayerMode"),
    Option(ParameterType::StringEnumeration, "box", "z-buffer: a box fixed around the vessels, or moving with the tip.")
      .SetElements({ "fixed", "moving" }).SetDefault(defaults.BoxMode).SetLogicName("BoxMode"),
    Option(ParameterType::String, "box-size",
      "z-buffer: the moving box's size (default " + cli::FormatNumber(box[0]) + "," + cli::FormatNumber(box[1]) + "," +
        cli::FormatNumber(box[2]) + " mm).")
      .SetPlaceholder("X,Y,Z")
      .SetLogicName("MovingBoxSizeMm"),
    Option(ParameterType::Integer, "bins", "z-buffer: the paper's distance bits, N bins over the range, a multiple of 16 (0: off).")
      .SetPlaceholder("N").SetDefault(std::to_string(defaults.DistanceBins)).SetLogicName("DistanceBins"),
  };
  group.Parameters.insert(group.Parameters.end(), zbuffer.begin(), zbuffer.end());
  return group;
}

DistanceEngineSettings ParseEngineSettings(const std::string& method, const cli::ParsedArguments& args)
{
  DistanceEngineSettings s;
  s.Method = method;
  if (args.IsSet("range"))
  {
    s.RangeMm = args.GetNumber("range");
  }
  s.DeviceSelector = args.GetString("device");
  if (args.IsSet("cell"))
  {
    s.CellSizeMm = args.GetNumber("cell");
  }
  s.ResolutionPx = args.IsSet("resolution") ? args.GetInteger("resolution") : 0;
  s.LayerMode = args.GetString("layers");
  s.BoxMode = args.GetString("box");
  if (args.IsSet("boxSize"))
  {
    s.MovingBoxSizeMm = ParsePoint(args.GetString("boxSize"), "--box-size");
  }
  s.DistanceBins = args.GetInteger("bins"); // 0: off, as the help says
  return s;
}

vtkSmartPointer<vtkVesselDistanceEngine> MakeDistanceEngine(const std::string& method, const cli::ParsedArguments& args)
{
  std::string note;
  auto engine = MakeDistanceEngine(ParseEngineSettings(method, args), &note);
  ReportEngineNote(note);
  return engine;
}

void ReportEngineNote(const std::string& note)
{
  if (!note.empty())
  {
    std::cerr << "vesselproximity: note: " << note << "; --method auto uses the exact engine\n";
  }
}
} // namespace vp
