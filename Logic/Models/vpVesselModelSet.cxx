#include "vpVesselModelSet.h"

#include "vpOutputFile.h"
#include "vpClock.h"
#include "vpColorTableFile.h"
#include "vpInputError.h"
#include "vpLabelComponents.h"
#include "vpRunFolder.h"
#include "vpSegmentationImport.h"
#include "vpSurfaceJson.h"
#include "vpVesselLabelTable.h"
#include "vpVesselSurface.h"
#include "vtkVesselMeshWriter.h"
#include "vtkVesselModelBuilder.h"

#include <vtkCellArray.h>
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
/// The centroid of the volume a closed, outward-facing triangle surface encloses: the tetrahedra
/// from a point inside its box to each triangle, weighted by their signed volumes (the surface's
/// points' mean would lean toward its finely meshed parts).
std::array<double, 3> VolumeCentroid(vtkPolyData* surface)
{
  double bounds[6];
  surface->GetBounds(bounds);
  const double o[3] = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]) };
  double sum[3] = { 0, 0, 0 }, volume = 0.0;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = surface->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      double a[3], b[3], c[3];
      surface->GetPoint(ids[0], a);
      surface->GetPoint(ids[k], b);
      surface->GetPoint(ids[k + 1], c);
      for (int i = 0; i < 3; ++i)
      {
        a[i] -= o[i], b[i] -= o[i], c[i] -= o[i];
      }
      const double v = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
      volume += v;
      for (int i = 0; i < 3; ++i)
      {
        sum[i] += v * (a[i] + b[i] + c[i]) / 4.0;
      }
    }
  }
  if (volume == 0.0)
  {
    return { o[0], o[1], o[2] };
  }
  return { o[0] + sum[0] / volume, o[1] + sum[1] / volume, o[2] + sum[2] / volume };
}

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
  model.Surface->GetBounds(model.BoundsMm.data());
  model.CentroidMm = VolumeCentroid(model.Surface);
  model.BuildMs = NowMs() - t0;
  return model;
}

nlohmann::json StructureJson(const LabelStructure& s)
{
  nlohmann::json j = { { "name", s.Name }, { "source", s.Source }, { "label", s.LabelValue } };
  if (s.Piece > 0)
  {
    j["piece"] = s.Piece;
    j["pieces"] = s.PieceCount;
  }
  return j;
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

/// "portal_vein" as it is said: "portal vein".
std::string Spoken(std::string name)
{
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

/// Where a tumour came from: "livertumor03", "livertumor, piece 2 of 3".
std::string SourceText(const LabelStructure& s)
{
  return s.PieceCount > 1 ? s.Name + ", piece " + std::to_string(s.Piece) + " of " + std::to_string(s.PieceCount) : s.Name;
}

/// The models a class makes: a vessel class (or the liver) one, of all its structures; a tumour
/// class one per structure, or per connected piece of one (each a target with its own margin),
/// numbered in the order the inputs list them: tumour_01, tumour_02, ...
std::vector<VesselClassModel> ModelsOfClass(const VesselClassModel& cls, std::vector<std::unique_ptr<LabelStructure>>& pieces)
{
  if (cls.Role != ModelRole::Tumour)
  {
    VesselClassModel model = cls;
    model.Name = cls.ClassName;
    model.DisplayName = Spoken(cls.ClassName);
    return { model };
  }
  std::vector<VesselClassModel> models;
  for (const LabelStructure* structure : cls.Structures)
  {
    for (LabelStructure& piece : SplitIntoComponents(*structure))
    {
      pieces.push_back(std::make_unique<LabelStructure>(std::move(piece)));
      VesselClassModel model;
      model.ClassName = cls.ClassName;
      model.Role = cls.Role;
      const std::string number = FixedText(static_cast<double>(models.size() + 1), "%02.0f");
      model.Name = cls.ClassName + "_" + number;
      model.DisplayName = Spoken(cls.ClassName) + " " + number + " (" + SourceText(*pieces.back()) + ")";
      model.Structures = { pieces.back().get() };
      models.push_back(std::move(model));
    }
  }
  return models;
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
      byClass[cls].Role = table.RoleOf(cls);
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
  std::size_t classesBuilt = 0;
  for (const std::string& cls : table.Classes())
  {
    const auto it = byClass.find(cls);
    if (it == byClass.end())
    {
      continue;
    }
    set.ClassesFound.push_back(cls);
    if (!asked(cls))
    {
      continue;
    }
    const double done = readShare + (1.0 - readShare) * static_cast<double>(++classesBuilt) / static_cast<double>(std::max<long>(1, toBuild));
    for (VesselClassModel& model : ModelsOfClass(it->second, set.Pieces))
    {
      set.Models.push_back(BuildClassModel(std::move(model), parameters));
      const VesselClassModel& m = set.Models.back();
      progress(m.Name + ": " + std::to_string(m.Voxels) + " voxels -> " + std::to_string(m.Surface->GetNumberOfPolys()) +
          " triangles in " + FixedText(m.BuildMs, "%.0f") + " ms", done);
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
    doc["structures"].push_back({ { "id", m.Name }, { "name", name }, { "class", m.ClassName }, { "role", ModelRoleName(m.Role) },
      { "display_name", m.DisplayName }, { "label", m.Structures.front()->LabelValue }, { "voxels", m.Voxels },
      { "triangles", m.Surface->GetNumberOfPolys() }, { "volume_mm3", m.VolumeMm3 }, { "voxel_volume_mm3", m.VoxelVolumeMm3 },
      { "area_mm2", m.AreaMm2 }, { "bounds", m.BoundsMm }, { "centroid", m.CentroidMm }, { "bounds_mm", m.BoundsMm }, { "centroid_mm", m.CentroidMm }, { "file", m.Name + ".stl" },
      { "surface", SurfaceJson(VesselSurface(m.Name, m.Surface)) }, { "sources", sources }, { "build_ms", m.BuildMs } });
    doc["files"].push_back(m.Name + ".stl");
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
    writer->SetFileName(pathOf(m.Name + ".stl"));
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
