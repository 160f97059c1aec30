// VesselProximityModels: `vesselproximity models` as a 3D Slicer CLI module. Slicer hands over a
// labelmap volume (a temporary .nrrd); the program writes one closed surface per vessel class
// into the output folder and returns how many it wrote.
#include "vpCliDescription.h"
#include "vpInputError.h"
#include "vpRunFolder.h"
#include "vpVesselModelSet.h"

#include <vtkObject.h>

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
  io.Parameters.push_back(Parameter(ParameterType::Directory, "outputDirectory")
                            .SetLongFlag("outputDirectory")
                            .SetChannel(Channel::Output)
                            .SetRequired()
                            .SetLabel("Output folder")
                            .SetDescription("Folder for <class>.stl per vessel class and models.json; created "
                                            "when missing. Nothing is written when the run fails. Required."));
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
    "VesselProximityModels", "Vessel Proximity Models", VP_VERSION, { IoGroup(), SurfaceGroup(), ResultsGroup() });
  d.Description =
    "Builds closed vessel surface models from a labelmap for scalpel-to-vessel distance "
    "measurement in liver surgery: one STL per vessel class found (portal_vein, hepatic_artery, "
    "hepatic_vein; liver too when present) and models.json, written to the output folder. "
    "Structures map to classes through a label table; in an unnamed labelmap (as Slicer passes "
    "one) only by label value, so give a table unless the values are TotalSegmentator's. "
    "Surfaces follow Slicer's closed-surface conversion: discrete flying edges, windowed-sinc "
    "smoothing, optional decimation. Same as `vesselproximity models`.";
  d.Acknowledgements =
    "Method after Noborio et al., \"Comparison of GPU-based and CPU-based Algorithms for Determining "
    "the Minimum Distance between a CUSA Scalpel and Blood Vessels\". Surface generation follows 3D "
    "Slicer's labelmap-to-closed-surface conversion.";
  return d;
}

void Run(const vp::cli::ParsedArguments& args, vp::cli::ReturnValues& results)
{
  vp::RunFolder run(args.GetString("outputDirectory"), "models.json");
  run.SetInputs({ args.GetString("inputVolume"), args.IsSet("labelTable") ? args.GetString("labelTable") : std::string() });
  vp::VesselModelParameters parameters;
  parameters.SmoothingFactor = args.GetNumber("smoothing");
  parameters.SmoothingIterations = args.GetInteger("smoothingIterations");
  parameters.DecimationFactor = args.GetNumber("decimation");
  parameters.FileSpace = args.GetString("space") == "RAS" ? vp::MeshSpace::RAS : vp::MeshSpace::LPS;
  parameters.LabelTableFile = args.IsSet("labelTable") ? args.GetString("labelTable") : std::string();
  const vp::VesselModelSet set = vp::BuildVesselModels({ args.GetString("inputVolume") }, parameters,
    [](const std::string& line) { std::cerr << "models: " << line << "\n"; });
  vp::WriteVesselModels(set, run);
  std::string classes;
  for (const vp::VesselClassModel& m : set.Models)
  {
    classes += (classes.empty() ? "" : ",") + m.ClassName;
  }
  results.Set("numberOfModels", static_cast<int>(set.Models.size()));
  results.Set("modelClasses", classes);
}
} // namespace

int main(int argc, char* argv[])
{
  // Errors are reported as one line each; VTK's console chatter would break that.
  vtkObject::GlobalWarningDisplayOff();
  return vp::cli::RunProgram(Describe(), argc, argv, Run);
}
