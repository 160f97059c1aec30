#include "vpVesselModelSet.h"

#include "vpOutputFile.h"
#include "vpClock.h"
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

VesselModelSet BuildVesselModels(
  const std::vector<std::string>& inputs, const VesselModelParameters& parameters, const ProgressReporter& progress)
{
  parameters.Validate();
  const VesselLabelTable table =
    parameters.LabelTableFile.empty() ? VesselLabelTable::Default() : VesselLabelTable::Load(parameters.LabelTableFile);
  VesselModelSet set;
  set.Inputs = inputs;
  set.Parameters = parameters;
  // Read: only the structures the table can place are worth their voxels.
  const double start = NowMs();
  for (const std::string& input : inputs)
  {
    const double t0 = NowMs();
    set.Imports.push_back(ImportSegmentation(input, [&](const std::string& name) { return !table.ClassOfName(name).empty(); }));
    if (!parameters.AllowMixedPatients)
    {
      CheckOnePatient(set.Imports); // before the input's line: a refusal is one line
    }
    progress(input + ": " + std::to_string(set.Imports.back().size()) + " structure(s) read in " +
      FixedText(NowMs() - t0, "%.0f") + " ms");
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
    progress("not a vessel class in the label table, skipped: " + s->Name + " (" + s->Source + ")");
  }
  if (byClass.empty())
  {
    throw InputError(inputs.front(), "no vessel or liver structure found (" + std::to_string(set.Unmapped.size()) +
        " structure(s), none in the label table); name them in a label table of your own");
  }
  for (const std::string& cls : table.Classes())
  {
    const auto it = byClass.find(cls);
    if (it != byClass.end())
    {
      set.Models.push_back(BuildClassModel(it->second, parameters));
      const VesselClassModel& m = set.Models.back();
      progress(cls + ": " + std::to_string(m.Voxels) + " voxels -> " + std::to_string(m.Surface->GetNumberOfPolys()) +
        " triangles in " + FixedText(m.BuildMs, "%.0f") + " ms");
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
