#include "vpVesselModelSet.h"

#include "vpOutputFile.h"
#include "vpClock.h"
#include "vpColorTableFile.h"
#include "vpInputError.h"
#include "vpRunFolder.h"
#include "vpSegmentationImport.h"
#include "vpSurfaceJson.h"
#include "vpVesselLabelTable.h"
#include "vpVesselSurface.h"
#include "vtkVesselMeshWriter.h"
#include "vtkVesselModelBuilder.h"

#include <vtkMassProperties.h>
#include <vtkNew.h>

#include <algorithm>
#include <map>

namespace vp
{
void VesselModelParameters::Validate() const
{
  if (!(this->SmoothingFactor >= 0.0 && this->SmoothingFactor <= 1.0))
  {
    throw ParameterError("SmoothingFactor", "must be between 0 and 1");
  }
  if (!(this->DecimationFactor >= 0.0 && this->DecimationFactor <= 0.99))
  {
    throw ParameterError("DecimationFactor", "must be between 0 and 0.99");
  }
  if (this->SmoothingIterations < 1 || this->SmoothingIterations > 1000)
  {
    throw ParameterError("SmoothingIterations", "must be between 1 and 1000");
  }
}

namespace
{
VesselClassModel BuildClassModel(VesselClassModel model, const VesselModelParameters& p)
{
  const double t0 = NowMs();
  vtkNew<vtkVesselModelBuilder> builder;
  builder->SetSmoothingFactor(p.SmoothingFactor);
  builder->SetSmoothingIterations(p.SmoothingIterations);
  builder->SetDecimationFactor(p.DecimationFactor);
  model.Surface = builder->Build(model.Structures);
  model.Voxels = builder->GetNumberOfVoxels();
  model.VoxelVolumeMm3 = builder->GetVoxelVolumeMm3();
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(model.Surface);
  mass->Update();
  model.VolumeMm3 = mass->GetVolume();
  model.AreaMm2 = mass->GetSurfaceArea();
  model.BuildMs = NowMs() - t0;
  return model;
}

nlohmann::json StructureJson(const LabelStructure& s)
{
  return { { "name", s.Name }, { "source", s.Source }, { "label", s.LabelValue } };
}
/// Every structure read is of one patient, study and frame of reference, as far as the inputs say
/// (NRRD and NIfTI say nothing): two patients' vessels in one model is a model of no one.
void CheckOnePatient(const std::vector<LabelStructures>& imports)
{
  const LabelStructure* first = nullptr;
  for (const LabelStructures& structures : imports)
  {
    for (const LabelStructure& s : structures)
    {
      if (!s.Grid.Labels)
      {
        continue;
      }
      if (!first)
      {
        first = &s;
        continue;
      }
      const std::string differs = first->Grid.Identity.DiffersIn(s.Grid.Identity);
      if (!differs.empty())
      {
        throw ParameterError("AllowMixedPatients", first->Source + " is " + first->Grid.Identity.Describe() + "; " + s.Source +
            " is " + s.Grid.Identity.Describe() + ": another " + differs + ", and a run builds one patient's models " +
            "unless mixing them is allowed");
      }
    }
  }
}

} // namespace

namespace
{
/// A structure the labelmap left unnamed ("label N", or its only value under its file's name)
/// takes the colour table's name for its value when the label table knows that name; one it does
/// not know stays unnamed, so that the table's values still place it.
void NameUnnamedStructures(
  LabelStructures& structures, const std::map<int, std::string>& colorNames, const VesselLabelTable& table)
{
  for (LabelStructure& s : structures)
  {
    const auto named = colorNames.find(s.LabelValue);
    if (named != colorNames.end() && !table.ClassOfName(named->second).empty() && s.IsUnnamed())
    {
      s.Name = named->second;
      s.OnlyValue = false;
    }
  }
}

/// Why nothing became a model, and what would name the structures.
std::string NothingMappedText(const std::vector<const LabelStructure*>& unmapped, bool hadColorTable)
{
  std::string values;
  bool unnamed = true;
  for (const LabelStructure* s : unmapped)
  {
    unnamed = unnamed && s->IsUnnamed();
    values += (values.empty() ? "" : ", ") + (s->OnlyValue ? std::to_string(s->LabelValue) : s->Name);
  }
  if (unnamed)
  {
    return "no vessel or liver structure found: the labelmap names none of its values (" + values + ")" +
      (hadColorTable ? ", the colour table names none of them as a vessel or the liver," : "") +
      " and the label table knows none by value; give the labelmap's colour table (Slicer writes it as .ctbl) "
      "naming them (portal vein, hepatic artery, hepatic vein, liver), or a label table of your own";
  }
  return "no vessel or liver structure found (" + std::to_string(unmapped.size()) + " structure(s): " + values +
    "; none in the label table); name them in a label table of your own";
}
} // namespace

VesselModelSet BuildVesselModels(
  const std::vector<std::string>& inputs, const VesselModelParameters& parameters, const ProgressReporter& progress)
{
  parameters.Validate();
  const VesselLabelTable table =
    parameters.LabelTableFile.empty() ? VesselLabelTable::Default() : VesselLabelTable::Load(parameters.LabelTableFile);
  const std::map<int, std::string> colorNames =
    parameters.ColorTableFile.empty() ? std::map<int, std::string>() : ReadColorTableNames(parameters.ColorTableFile);
  VesselModelSet set;
  set.Inputs = inputs;
  set.Parameters = parameters;
  // Read: only the structures the table can place are worth their voxels.
  const double start = NowMs();
  const double readShare = 0.4;
  for (const std::string& input : inputs)
  {
    const double t0 = NowMs();
    set.Imports.push_back(ImportSegmentation(input, [&](const std::string& name) { return !table.ClassOfName(name).empty(); }));
    NameUnnamedStructures(set.Imports.back(), colorNames, table);
    if (!parameters.AllowMixedPatients)
    {
      CheckOnePatient(set.Imports); // before the input's line: a refusal is one line
    }
    progress(input + ": " + std::to_string(set.Imports.back().size()) + " structure(s) read in " +
      FixedText(NowMs() - t0, "%.0f") + " ms",
      readShare * static_cast<double>(set.Imports.size()) / static_cast<double>(inputs.size()));
  }
  set.ReadMs = NowMs() - start;

  std::map<std::string, VesselClassModel> byClass;
  for (const auto& structures : set.Imports)
  {
    for (const LabelStructure& s : structures)
    {
      const std::string cls = s.Grid.Labels ? table.ClassOf(s) : std::string();
      if (cls.empty())
      {
        set.Unmapped.push_back(&s);
        continue;
      }
      byClass[cls].ClassName = cls;
      byClass[cls].Structures.push_back(&s);
    }
  }
  for (const LabelStructure* s : set.Unmapped)
  {
    progress("not a vessel class in the label table, skipped: " + s->Name + " (" + s->Source + ")", readShare);
  }
  if (byClass.empty())
  {
    throw InputError(inputs.front(), NothingMappedText(set.Unmapped, !colorNames.empty()));
  }
  const auto asked = [&](const std::string& cls) {
    return parameters.Classes.empty() || std::find(parameters.Classes.begin(), parameters.Classes.end(), cls) != parameters.Classes.end();
  };
  const auto toBuild = std::count_if(byClass.begin(), byClass.end(), [&](const auto& c) { return asked(c.first); });
  for (const std::string& cls : table.Classes())
  {
    const auto it = byClass.find(cls);
    if (it == byClass.end())
    {
      continue;
    }
    set.ClassesFound.push_back(cls);
    if (asked(cls))
    {
      set.Models.push_back(BuildClassModel(it->second, parameters));
      const VesselClassModel& m = set.Models.back();
      progress(cls + ": " + std::to_string(m.Voxels) + " voxels -> " + std::to_string(m.Surface->GetNumberOfPolys()) +
        " triangles in " + FixedText(m.BuildMs, "%.0f") + " ms",
        readShare + (1.0 - readShare) * static_cast<double>(set.Models.size()) / static_cast<double>(std::max<long>(1, toBuild)));
    }
  }
  set.TotalMs = NowMs() - start;
  return set;
}

nlohmann::json VesselModelsJson(const VesselModelSet& set)
{
  const VesselModelParameters& p = set.Parameters;
  nlohmann::json doc;
  doc["space"] = p.FileSpace == MeshSpace::RAS ? "RAS" : "LPS";
  doc["inputs"] = set.Inputs;
  doc["parameters"] = { { "smoothing", p.SmoothingFactor }, { "smoothing_iterations", p.SmoothingIterations },
    { "decimation", p.DecimationFactor }, { "labels", p.LabelTableFile.empty() ? "built-in" : p.LabelTableFile } };
  doc["structures"] = nlohmann::json::array();
  doc["files"] = nlohmann::json::array();
  for (const VesselClassModel& m : set.Models)
  {
    std::string name;
    nlohmann::json sources = nlohmann::json::array();
    for (const LabelStructure* s : m.Structures)
    {
      name += (name.empty() ? "" : "+") + s->Name;
      sources.push_back(StructureJson(*s));
    }
    doc["structures"].push_back({ { "name", name }, { "class", m.ClassName }, { "label", m.Structures.front()->LabelValue },
      { "voxels", m.Voxels }, { "triangles", m.Surface->GetNumberOfPolys() }, { "volume_mm3", m.VolumeMm3 },
      { "voxel_volume_mm3", m.VoxelVolumeMm3 }, { "area_mm2", m.AreaMm2 }, { "file", m.ClassName + ".stl" },
      { "surface", SurfaceJson(VesselSurface(m.ClassName, m.Surface)) }, { "sources", sources }, { "build_ms", m.BuildMs } });
    doc["files"].push_back(m.ClassName + ".stl");
  }
  doc["files"].push_back("models.json");
  doc["unmapped"] = nlohmann::json::array();
  for (const LabelStructure* s : set.Unmapped)
  {
    doc["unmapped"].push_back(StructureJson(*s));
  }
  doc["timing_ms"] = { { "read", set.ReadMs }, { "total", set.TotalMs } };
  return doc;
}

namespace
{
void WriteModelFiles(const VesselModelSet& set, const std::function<std::string(const std::string&)>& pathOf)
{
  const nlohmann::json doc = VesselModelsJson(set);
  for (const VesselClassModel& m : set.Models)
  {
    vtkNew<vtkVesselMeshWriter> writer;
    writer->SetFileName(pathOf(m.ClassName + ".stl"));
    writer->SetInputData(m.Surface);
    writer->SetFileSpace(set.Parameters.FileSpace);
    writer->Write();
  }
  WriteFileAtomically(pathOf("models.json"), doc.dump(2) + "\n");
}
} // namespace

void WriteVesselModels(const VesselModelSet& set, RunFolder& run)
{
  run.Begin();
  WriteModelFiles(set, [&](const std::string& name) { return run.File(name); });
  run.Commit();
}

void WriteVesselModelFiles(const VesselModelSet& set, const std::string& folder)
{
  WriteModelFiles(set, [&](const std::string& name) { return folder + "/" + name; });
}
} // namespace vp
