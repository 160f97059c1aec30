// vesselproximity models: segmented labelmaps in, one closed STL surface per vessel class out.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpVesselModelSet.h"

#include <iomanip>
#include <iostream>

namespace vp
{
namespace
{
const char* Usage =
  "usage: vesselproximity models INPUT... -o OUTDIR [--labels TABLE.json] [--smoothing F]\n"
  "                              [--smoothing-iterations N] [--decimation F] [--space LPS|RAS]\n"
  "  INPUT: a folder of DICOM label series (one sub-folder per structure, as 3D-IRCADb's\n"
  "         MASKS_DICOM, or one series of several label values), a .nrrd, .seg.nrrd, .nii or\n"
  "         .nii.gz labelmap.\n"
  "  Writes OUTDIR/<class>.stl for each vessel class found (portal_vein, hepatic_vein,\n"
  "  hepatic_artery; liver too when present) and OUTDIR/models.json. Structures map to classes\n"
  "  through the label table (default: the built-in Resources/VesselLabels.json); structures it\n"
  "  does not know are listed on stderr and in models.json, not modelled.\n"
  "  --smoothing F              windowed-sinc smoothing factor 0..1 (default 0.5, as Slicer)\n"
  "  --smoothing-iterations N   default 20, as Slicer\n"
  "  --decimation F             fraction of triangles removed, 0..0.99 (default 0)\n"
  "  --space LPS|RAS            coordinates of the STL files (default LPS, the DICOM frame)\n";

void PrintModels(const VesselModelSet& set, const std::string& outDir)
{
  std::cout << std::left << std::setw(16) << "class" << std::right << std::setw(10) << "voxels" << std::setw(12)
            << "triangles" << std::setw(14) << "volume_mm3" << std::setw(12) << "area_mm2" << "  file\n";
  for (const VesselClassModel& m : set.Models)
  {
    std::cout << std::left << std::setw(16) << m.ClassName << std::right << std::setw(10) << m.Voxels << std::setw(12)
              << m.Surface->GetNumberOfPolys() << std::setw(14) << std::fixed << std::setprecision(0) << m.VolumeMm3
              << std::setw(12) << m.AreaMm2 << "  " << outDir << "/" << m.ClassName << ".stl\n";
  }
}
} // namespace

int RunModelsCommand(const std::vector<std::string>& argv)
{
  if (WantsHelp(argv))
  {
    std::cout << Usage;
    return 0;
  }
  const Arguments args(argv,
    { "-o", "--output", "--labels", "--smoothing", "--smoothing-iterations", "--decimation", "--space" }, {});
  const std::string outDir = args.Has("-o") ? args.Get("-o") : args.Get("--output");
  if (args.Positional().empty())
  {
    throw InputError("models", "give at least one INPUT labelmap (see --help)");
  }
  if (outDir.empty())
  {
    throw InputError("-o", "an output folder is required");
  }
  RunFolder run(outDir, "models.json");
  const std::string spaceName = args.Get("--space", "LPS");
  if (spaceName != "LPS" && spaceName != "RAS")
  {
    throw InputError("--space", "must be LPS or RAS, not '" + spaceName + "'");
  }
  VesselModelParameters parameters;
  parameters.FileSpace = spaceName == "RAS" ? MeshSpace::RAS : MeshSpace::LPS;
  parameters.SmoothingFactor = args.GetNumber("--smoothing", parameters.SmoothingFactor);
  parameters.DecimationFactor = args.GetNumber("--decimation", parameters.DecimationFactor);
  parameters.SmoothingIterations = args.GetInteger("--smoothing-iterations", parameters.SmoothingIterations);
  parameters.LabelTableFile = args.Get("--labels");
  // Every line is said once its step is done: a line before a refusal would make its one line two.
  const VesselModelSet set = BuildVesselModels(
    args.Positional(), parameters, [](const std::string& line) { std::cerr << "models: " << line << "\n"; });
  WriteVesselModels(set, run);
  PrintModels(set, outDir);
  std::cerr << "models: done in " << FixedText(set.TotalMs, "%.0f") << " ms\n";
  return 0;
}
} // namespace vp
