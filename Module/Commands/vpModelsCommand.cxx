// vesselproximity models: segmented labelmaps in, one closed STL surface per vessel class out.
#include "vpArguments.h"
#include "vpCommandSupport.h"
#include "vpRunFolder.h"
#include "vpCommands.h"
#include "vpInputError.h"
#include "vpSegmentationImport.h"
#include "vpVesselLabelTable.h"
#include "vpVesselSurface.h"
#include "vtkVesselMeshWriter.h"
#include "vtkVesselModelBuilder.h"

#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

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

struct ClassModel
{
  std::string ClassName;
  std::vector<const LabelStructure*> Structures;
  vtkSmartPointer<vtkPolyData> Surface;
  vtkIdType Voxels = 0;
  double VoxelVolumeMm3 = 0.0, VolumeMm3 = 0.0, AreaMm2 = 0.0, Ms = 0.0;
};

double Fraction(const Arguments& args, const std::string& option, double fallback, double hi)
{
  const double value = args.GetNumber(option, fallback);
  if (!(value >= 0.0 && value <= hi))
  {
    std::ostringstream range;
    range << "must be between 0 and " << hi;
    throw InputError(option, range.str());
  }
  return value;
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
  const double smoothing = Fraction(args, "--smoothing", 0.5, 1.0);
  const double decimation = Fraction(args, "--decimation", 0.0, 0.99);
  const int iterations = args.GetInteger("--smoothing-iterations", 20);
  if (iterations < 1 || iterations > 1000)
  {
    throw InputError("--smoothing-iterations", "must be between 1 and 1000");
  }
  const VesselLabelTable table =
    args.Has("--labels") ? VesselLabelTable::Load(args.Get("--labels")) : VesselLabelTable::Default();

  // Read: only the structures the table can place are worth their voxels.
  const double start = NowMs();
  std::vector<LabelStructures> imports;
  for (const std::string& input : args.Positional())
  {
    // Said once read: a line before a refusal would make its one line two.
    const double t0 = NowMs();
    imports.push_back(ImportSegmentation(input, [&](const std::string& name) { return !table.ClassOfName(name).empty(); }));
    std::cerr << "models: " << input << ": " << imports.back().size() << " structure(s) read in " << std::fixed
              << std::setprecision(0) << NowMs() - t0 << " ms\n";
  }
  const double readMs = NowMs() - start;

  std::map<std::string, ClassModel> byClass;
  std::vector<const LabelStructure*> unmapped;
  for (const auto& structures : imports)
  {
    for (const LabelStructure& s : structures)
    {
      const std::string cls = s.Grid.Labels ? table.ClassOf(s) : std::string();
      if (cls.empty())
      {
        unmapped.push_back(&s);
        continue;
      }
      byClass[cls].ClassName = cls;
      byClass[cls].Structures.push_back(&s);
    }
  }
  for (const LabelStructure* s : unmapped)
  {
    std::cerr << "models: not a vessel class in the label table, skipped: " << s->Name << " (" << s->Source << ")\n";
  }
  if (byClass.empty())
  {
    throw InputError(args.Positional().front(),
      "no vessel or liver structure found (" + std::to_string(unmapped.size()) +
        " structure(s), none in the label table); name them in a table given with --labels");
  }

  // Build every model before writing anything: a failure leaves nothing behind.
  std::vector<ClassModel> models;
  for (const std::string& cls : table.Classes())
  {
    auto it = byClass.find(cls);
    if (it == byClass.end())
    {
      continue;
    }
    ClassModel model = it->second;
    const double t0 = NowMs();
    vtkNew<vtkVesselModelBuilder> builder;
    builder->SetSmoothingFactor(smoothing);
    builder->SetSmoothingIterations(iterations);
    builder->SetDecimationFactor(decimation);
    model.Surface = builder->Build(model.Structures);
    model.Voxels = builder->GetNumberOfVoxels();
    model.VoxelVolumeMm3 = builder->GetVoxelVolumeMm3();
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(model.Surface);
    mass->Update();
    model.VolumeMm3 = mass->GetVolume();
    model.AreaMm2 = mass->GetSurfaceArea();
    model.Ms = NowMs() - t0;
    std::cerr << "models: " << cls << ": " << model.Voxels << " voxels -> " << model.Surface->GetNumberOfPolys()
              << " triangles in " << std::setprecision(0) << model.Ms << " ms\n";
    models.push_back(model);
  }

  nlohmann::json doc;
  doc["space"] = spaceName;
  doc["inputs"] = args.Positional();
  doc["parameters"] = { { "smoothing", smoothing }, { "smoothing_iterations", iterations },
    { "decimation", decimation }, { "labels", args.Get("--labels", "built-in") } };
  doc["structures"] = nlohmann::json::array();
  for (const ClassModel& m : models)
  {
    std::string name;
    nlohmann::json sources = nlohmann::json::array();
    for (const LabelStructure* s : m.Structures)
    {
      name += (name.empty() ? "" : "+") + s->Name;
      sources.push_back({ { "name", s->Name }, { "source", s->Source }, { "label", s->LabelValue } });
    }
    doc["structures"].push_back({ { "name", name }, { "class", m.ClassName },
      { "label", m.Structures.front()->LabelValue }, { "voxels", m.Voxels },
      { "triangles", m.Surface->GetNumberOfPolys() }, { "volume_mm3", m.VolumeMm3 },
      { "voxel_volume_mm3", m.VoxelVolumeMm3 }, { "area_mm2", m.AreaMm2 }, { "file", m.ClassName + ".stl" },
      { "surface", SurfaceJson(VesselSurface(m.ClassName, m.Surface)) }, { "sources", sources }, { "build_ms", m.Ms } });
  }
  doc["files"] = nlohmann::json::array();
  for (const ClassModel& m : models)
  {
    doc["files"].push_back(m.ClassName + ".stl");
  }
  doc["files"].push_back("models.json");
  doc["unmapped"] = nlohmann::json::array();
  for (const LabelStructure* s : unmapped)
  {
    doc["unmapped"].push_back({ { "name", s->Name }, { "source", s->Source }, { "label", s->LabelValue } });
  }
  doc["timing_ms"] = { { "read", readMs }, { "total", NowMs() - start } };

  // Write: the folder holds this run whole, or the previous one as it was.
  run.Begin();
  for (const ClassModel& m : models)
  {
    vtkNew<vtkVesselMeshWriter> writer;
    writer->SetFileName(run.File(m.ClassName + ".stl"));
    writer->SetInputData(m.Surface);
    writer->SetFileSpace(spaceName == "RAS" ? MeshSpace::RAS : MeshSpace::LPS);
    writer->Write();
  }
  WriteFileAtomically(run.File("models.json"), doc.dump(2) + "\n");
  run.Commit();

  std::cout << std::left << std::setw(16) << "class" << std::right << std::setw(10) << "voxels" << std::setw(12)
            << "triangles" << std::setw(14) << "volume_mm3" << std::setw(12) << "area_mm2" << "  file\n";
  for (const ClassModel& m : models)
  {
    std::cout << std::left << std::setw(16) << m.ClassName << std::right << std::setw(10) << m.Voxels << std::setw(12)
              << m.Surface->GetNumberOfPolys() << std::setw(14) << std::fixed << std::setprecision(0) << m.VolumeMm3 << std::setw(12)
              << m.AreaMm2 << "  " << outDir << "/" << m.ClassName << ".stl\n";
  }
  std::cerr << "models: done in " << std::setprecision(0) << NowMs() - start << " ms\n";
  return 0;
}
} // namespace vp
