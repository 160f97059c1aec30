// VesselProximityModels: `vesselproximity models` as a 3D Slicer CLI module. Slicer hands over a
// labelmap volume (a temporary .nrrd) and its colour table (a temporary .ctbl: the volume's file
// carries no names); the program writes one closed surface per vessel class where Slicer asks for
// each model node (and, for scripts, into a folder) and returns how many it built.
#include "vpCliDescription.h"
#include "vpCliProgress.h"
#include "vpInputError.h"
#include "vpRunFolder.h"
#include "vpVesselModelSet.h"
#include "vtkVesselMeshWriter.h"

#include <vtkNew.h>
#include <vtkObject.h>

#include <algorithm>
#include <iostream>

#ifndef VP_VERSION
#define VP_VERSION "0.1.0"
#endif

namespace
{
using vp::cli::Channel;
using vp::cli::Parameter;
using vp::cli::ParameterType;

vp::cli::ParameterGroup IoGroup()
{
  vp::cli::ParameterGroup io{ "IO", "Input labelmap, label table and output folder", {} };
  io.Parameters.push_back(Parameter(ParameterType::Image, "inputVolume")
                            .SetTypeAttribute("label")
                            .SetIndex(0)
                            .SetChannel(Channel::Input)
                            .SetRequired()
                            .SetLabel("Input labelmap")
                            .SetDescription("Labelmap whose voxel values are structures, geometry in the file's "
                                            "frame (.nrrd as Slicer passes it; .seg.nrrd, .nii and .nii.gz too). "
                                            "Required."));
  io.Parameters.push_back(Parameter(ParameterType::Table, "colorTable")
                            .SetTypeAttribute("color")
                            .SetFileExtensions(".ctbl")
                            .SetLongFlag("colorTable")
                            .SetLogicName("ColorTableFile")
                            .SetChannel(Channel::Input)
                            .SetLabel("Colour table")
                            .SetDescription("The labelmap's colour table (its names for the label values, such as "
                                            "portal vein, hepatic artery, hepatic vein, liver): Slicer passes the "
                                            "volume without them. Matched before the label table's values."));
  io.Parameters.push_back(Parameter(ParameterType::File, "labelTable")
                            .SetLongFlag("labelTable")
                            .SetLogicName("LabelTableFile")
                            .SetFileExtensions(".json")
                            .SetChannel(Channel::Input)
                            .SetLabel("Label table")
                            .SetDescription("JSON label table in the format of Resources/VesselLabels.json: per "
                                            "class its names, codes and label values. Default: the built-in table "
                                            "(IRCADb names, SNOMED codes, TotalSegmentator values 5 liver, 63 "
                                            "inferior vena cava as hepatic_vein, 64 portal vein)."));
  return io;
}

/// The classes a model output can bring into the scene, each its own model node.
struct ModelOutput
{
  const char* Parameter;
  const char* ClassName;
  const char* Label;
};
const ModelOutput ModelOutputs[] = {
  { "portalVeinModel", "portal_vein", "Portal vein model" },
  { "hepaticArteryModel", "hepatic_artery", "Hepatic artery model" },
  { "hepaticVeinModel", "hepatic_vein", "Hepatic vein model" },
  { "liverModel", "liver", "Liver model" },
};

vp::cli::ParameterGroup ModelsGroup()
{
  vp::cli::ParameterGroup models{ "Models", "Where the models go: scene model nodes, and a folder for scripts", {} };
  for (const ModelOutput& m : ModelOutputs)
  {
    models.Parameters.push_back(Parameter(ParameterType::Geometry, m.Parameter)
                                  .SetTypeAttribute("model")
                                  .SetFileExtensions(".stl")
                                  .SetLongFlag(m.Parameter)
                                  .SetChannel(Channel::Output)
                                  .SetLabel(m.Label)
                                  .SetDescription(std::string("The ") + m.ClassName +
                                    " surface as a model node (STL, its header tagged with its space). The run "
                                    "is refused, writing nothing, when the labelmap has no such structure."));
  }
  models.Parameters.push_back(Parameter(ParameterType::Directory, "outputDirectory")
                                .SetLongFlag("outputDirectory")
                                .SetChannel(Channel::Output)
                                .SetLabel("Output folder")
                                .SetDescription("Also a folder with <class>.stl per class found and models.json (for "
                                                "scripts; created when missing). Optional: give it or a model."));
  return models;
}

vp::cli::ParameterGroup SurfaceGroup()
{
  vp::cli::ParameterGroup surface{ "Surface", "Smoothing, decimation and coordinate system of the models", {} };
  surface.Parameters.push_back(Parameter(ParameterType::Float, "smoothing")
                                 .SetLongFlag("smoothing")
                                 .SetLogicName("SmoothingFactor")
                                 .SetLabel("Smoothing")
                                 .SetDescription("Windowed-sinc smoothing factor as Slicer codes it: pass band "
                                                 "10^(-4 x factor). 0 keeps the voxel steps.")
                                 .SetDefault(vp::cli::FormatNumber(vp::VesselModelParameters().SmoothingFactor))
                                 .SetRange(0.0, 1.0, 0.05));
  surface.Parameters.push_back(Parameter(ParameterType::Integer, "smoothingIterations")
                                 .SetLongFlag("smoothingIterations")
                                 .SetLogicName("SmoothingIterations")
                                 .SetLabel("Smoothing iterations")
                                 .SetDescription("Windowed-sinc iterations (Slicer uses 20; more shrink thin vessels).")
                                 .SetDefault(std::to_string(vp::VesselModelParameters().SmoothingIterations))
                                 .SetRange(1, 1000, 1));
  surface.Parameters.push_back(Parameter(ParameterType::Float, "decimation")
                                 .SetLongFlag("decimation")
                                 .SetLogicName("DecimationFactor")
                                 .SetLabel("Decimation")
                                 .SetDescription("Fraction of triangles removed, keeping topology (0: none).")
                                 .SetDefault(vp::cli::FormatNumber(vp::VesselModelParameters().DecimationFactor))
                                 .SetRange(0.0, 0.99, 0.05));
  surface.Parameters.push_back(Parameter(ParameterType::StringEnumeration, "space")
                                 .SetLongFlag("space")
                                 .SetLabel("Coordinate system")
                                 .SetDescription("Coordinates of the STL files, tagged in their header as Slicer "
                                                 "does: LPS (the DICOM frame, Slicer's default for files) or RAS.")
                                 .SetDefault(vp::MeshSpaceName(vp::VesselModelParameters().FileSpace))
                                 .SetElements({ "LPS", "RAS" }));
  return surface;
}

vp::cli::ParameterGroup ResultsGroup()
{
  vp::cli::ParameterGroup outputs{ "Results", "What the run wrote", {} };
  outputs.Parameters.push_back(Parameter(ParameterType::Integer, "numberOfModels")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Models written")
                                 .SetDescription("Number of class models (STL files) written.")
                                 .SetDefault("0"));
  outputs.Parameters.push_back(Parameter(ParameterType::String, "modelClasses")
                                 .SetChannel(Channel::Output)
                                 .SetLabel("Classes")
                                 .SetDescription("The classes modelled, comma separated (each is <class>.stl in the "
                                                 "output folder)."));
  return outputs;
}

/// The one table: the XML, --help and the parser all come from it.
vp::cli::ModuleDescription Describe()
{
  auto d = vp::cli::ModuleDescription::VesselProximity(
    "VesselProximityModels", "Vessel Proximity Models", VP_VERSION, { IoGroup(), ModelsGroup(), SurfaceGroup(), ResultsGroup() });
  d.Description =
    "Builds closed vessel surface models from a labelmap for scalpel-to-vessel distance "
    "measurement in liver surgery: one STL per vessel class found (portal_vein, hepatic_artery, "
    "hepatic_vein; liver too when present), each a model node in the scene and, with an output folder, "
    "an STL there with models.json. "
    "Structures map to classes through a label table; in an unnamed labelmap (as Slicer passes "
    "one) by the names its colour table gives the values, else by value through the label table. "
    "Surfaces follow Slicer's closed-surface conversion: discrete flying edges, windowed-sinc "
    "smoothing, optional decimation. Same as `vesselproximity models`.";
  return d;
}

/// Every asked-for model, found before any is written: a run is whole or writes nothing.
std::vector<std::pair<const ModelOutput*, const vp::VesselClassModel*>> FindWantedModels(
  const vp::VesselModelSet& set, const std::vector<const ModelOutput*>& wanted, const std::string& input, const std::string& classes)
{
  std::vector<std::pair<const ModelOutput*, const vp::VesselClassModel*>> writes;
  for (const ModelOutput* out : wanted)
  {
    const auto found = std::find_if(set.Models.begin(), set.Models.end(),
      [&](const vp::VesselClassModel& m) { return m.ClassName == out->ClassName; });
    if (found == set.Models.end())
    {
      throw vp::InputError(input, std::string("no ") + out->ClassName + " structure in the labelmap (asked for by --" +
          out->Parameter + "); it has " + (classes.empty() ? std::string("none") : classes) +
          ": leave that output unset, or name the structure in the colour or label table");
    }
    writes.emplace_back(out, &*found);
  }
  return writes;
}

void Run(const vp::cli::ParsedArguments& args, vp::cli::ReturnValues& results)
{
  std::vector<const ModelOutput*> wanted;
  for (const ModelOutput& m : ModelOutputs)
  {
    if (args.IsSet(m.Parameter))
    {
      wanted.push_back(&m);
    }
  }
  if (wanted.empty() && !args.IsSet("outputDirectory"))
  {
    throw vp::cli::UsageError("--portalVeinModel/.../--outputDirectory", "give a model to create or an output folder");
  }
  vp::cli::FilterProgress progress("VesselProximityModels");
  vp::VesselModelParameters parameters;
  parameters.SmoothingFactor = args.GetNumber("smoothing");
  parameters.SmoothingIterations = args.GetInteger("smoothingIterations");
  parameters.DecimationFactor = args.GetNumber("decimation");
  parameters.FileSpace = args.GetString("space") == "RAS" ? vp::MeshSpace::RAS : vp::MeshSpace::LPS;
  parameters.LabelTableFile = args.IsSet("labelTable") ? args.GetString("labelTable") : std::string();
  parameters.ColorTableFile = args.IsSet("colorTable") ? args.GetString("colorTable") : std::string();
  if (!args.IsSet("outputDirectory"))
  {
    for (const ModelOutput* out : wanted)
    {
      parameters.Classes.push_back(out->ClassName); // only the models asked for are built
    }
  }
  const std::string input = args.GetString("inputVolume");
  const vp::VesselModelSet set = vp::BuildVesselModels({ input }, parameters, [&](const std::string& line, double done) {
    std::cout << "models: " << line << "\n";
    progress.Stage("Building the surfaces", done * 0.95);
  });
  std::string classes, found;
  for (const vp::VesselClassModel& m : set.Models)
  {
    classes += (classes.empty() ? "" : ",") + m.Name;
  }
  for (const std::string& c : set.ClassesFound)
  {
    found += (found.empty() ? "" : ",") + c;
  }
  for (const auto& [out, model] : FindWantedModels(set, wanted, input, found))
  {
    vtkNew<vtkVesselMeshWriter> writer;
    writer->SetFileName(args.GetString(out->Parameter));
    writer->SetInputData(model->Surface);
    writer->SetFileSpace(parameters.FileSpace);
    writer->Write();
  }
  if (args.IsSet("outputDirectory"))
  {
    vp::RunFolder run(args.GetString("outputDirectory"), "models.json");
    run.SetInputs({ input, parameters.LabelTableFile, parameters.ColorTableFile });
    vp::WriteVesselModels(set, run);
  }
  results.Set("numberOfModels", static_cast<int>(set.Models.size()));
  results.Set("modelClasses", classes);
  progress.Finish();
}
} // namespace

int main(int argc, char* argv[])
{
  // Errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  return vp::cli::RunProgram(Describe(), argc, argv, Run);
}
