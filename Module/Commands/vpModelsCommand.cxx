// vesselproximity models: segmented labelmaps in, one closed STL surface per vessel class out.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpVesselModelSet.h"

#include <cstdio>
#include <iomanip>
#include <iostream>

namespace vp
{
namespace
{
void PrintModels(const VesselModelSet& set, const std::string& outDir)
{
  std::cout << std::left << std::setw(16) << "model" << std::right << std::setw(10) << "voxels" << std::setw(12)
            << "triangles" << std::setw(14) << "volume_mm3" << std::setw(12) << "area_mm2" << "  centroid_mm (LPS)"
            << std::setw(12) << "" << "file\n";
  for (const VesselClassModel& m : set.Models)
  {
    char centroid[96];
    std::snprintf(centroid, sizeof centroid, "%.1f,%.1f,%.1f", m.CentroidMm[0], m.CentroidMm[1], m.CentroidMm[2]);
    std::cout << std::left << std::setw(16) << m.Name << std::right << std::setw(10) << m.Voxels << std::setw(12)
              << m.Surface->GetNumberOfPolys() << std::setw(14) << std::fixed << std::setprecision(0) << m.VolumeMm3
              << std::setw(12) << m.AreaMm2 << "  " << std::left << std::setw(29) << centroid << outDir << "/" << m.Name
              << ".stl" << (m.Role == ModelRole::Tumour ? "  " + m.DisplayName : std::string()) << "\n";
  }
}
} // namespace

cli::ModuleDescription DescribeModelsCommand()
{
  using cli::FormatNumber;
  using cli::ParameterType;
  const VesselModelParameters defaults;
  return cli::ModuleDescription::Subcommand("vesselproximity models",
    "segmented labelmaps (DICOM series, DICOM SEG, NRRD, .seg.nrrd, NIfTI) to vessel and tumour surface models",
    "Writes OUTDIR/<class>.stl for each vessel class found (portal_vein, hepatic_vein, hepatic_artery; liver too "
    "when present), OUTDIR/tumour_01.stl, tumour_02.stl, ... for each tumour structure (IRCADb's livertumor01, a "
    "segment or colour-table name holding tumor, tumour, lesion or metastasis) and each connected piece of one, and "
    "OUTDIR/models.json (per model its bounds, centroid, volume and voxels). Structures map to classes through the "
    "label table; structures it does not know are listed on stderr and in models.json, not modelled.",
    {
      { "Inputs", "",
        {
          cli::Parameter(ParameterType::String, "inputs")
            .SetIndex(0)
            .SetMultiple()
            .SetRequired()
            .SetPlaceholder("INPUT")
            .SetDescription("A folder of DICOM label series (one sub-folder per structure, as 3D-IRCADb's MASKS_DICOM, "
                            "or one series of several label values), a DICOM SEG, a .nrrd, .seg.nrrd, .nii or .nii.gz labelmap."),
          Option(ParameterType::File, "labels", "The label table (default: the built-in Resources/VesselLabels.json).")
            .SetChannel(cli::Channel::Input)
            .SetPlaceholder("TABLE.json"),
          Option(ParameterType::File, "colors",
            "A 3D Slicer colour table (.ctbl, or Slicer's .txt colour files) naming the label values of an unnamed labelmap "
            "(\"2 portal_vein ...\"): its names are matched before the label table's values.")
            .SetChannel(cli::Channel::Input)
            .SetLogicName("ColorTableFile")
            .SetPlaceholder("COLORS.ctbl"),
          OutputFolderOption("The run's folder: one STL per class and models.json.").SetRequired(),
          Switch("allow-mixed",
            "Build inputs of different patients or frames of reference into one set of models (refused without it).")
            .SetLogicName("AllowMixedPatients"),
        } },
      { "Surfaces", "",
        {
          Option(ParameterType::Double, "smoothing", "Windowed-sinc smoothing factor, 0 to 1, as Slicer.")
            .SetPlaceholder("F")
            .SetDefault(FormatNumber(defaults.SmoothingFactor))
            .SetLogicName("SmoothingFactor"),
          Option(ParameterType::Integer, "smoothing-iterations", "Smoothing iterations, as Slicer.")
            .SetPlaceholder("N")
            .SetDefault(std::to_string(defaults.SmoothingIterations))
            .SetLogicName("SmoothingIterations"),
          Option(ParameterType::Double, "decimation", "The fraction of triangles removed, 0 to 0.99.")
            .SetPlaceholder("F")
            .SetDefault(FormatNumber(defaults.DecimationFactor))
            .SetLogicName("DecimationFactor"),
          Option(ParameterType::StringEnumeration, "space", "The coordinates of the STL files (LPS: the DICOM frame).")
            .SetElements({ "LPS", "RAS" })
            .SetDefault("LPS"),
        } },
    });
}

int RunModelsCommand(const cli::ParsedArguments& args, const ModuleServices&)
{
  const std::string outDir = args.GetString("output");
  RunFolder run(outDir, "models.json");
  std::vector<std::string> inputs = args.GetStrings("inputs");
  inputs.push_back(args.GetString("labels"));
  inputs.push_back(args.GetString("colors"));
  run.SetInputs(inputs); // never removed or written over, even inside the output folder
  VesselModelParameters parameters;
  parameters.FileSpace = args.GetString("space") == "RAS" ? MeshSpace::RAS : MeshSpace::LPS;
  parameters.SmoothingFactor = args.GetNumber("smoothing");
  parameters.DecimationFactor = args.GetNumber("decimation");
  parameters.SmoothingIterations = args.GetInteger("smoothingIterations");
  parameters.LabelTableFile = args.GetString("labels");
  parameters.ColorTableFile = args.GetString("colors");
  parameters.AllowMixedPatients = args.GetBoolean("allowMixed");
  // Every line is said once its step is done: a line before a refusal would make its one line two.
  const VesselModelSet set = BuildVesselModels(
    args.GetStrings("inputs"), parameters, [](const std::string& line, double) { std::cerr << "models: " << line << "\n"; });
  WriteVesselModels(set, run);
  PrintModels(set, outDir);
  std::cerr << "models: done in " << FixedText(set.TotalMs, "%.0f") << " ms\n";
  return 0;
}
} // namespace vp
