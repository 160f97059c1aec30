#include "vpVesselMeshSet.h"

#include "vpClassName.h"

#include "vpInputError.h"
#include "vpModelsFile.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>

#include <cctype>
#include <filesystem>
#include <set>

namespace vp
{
namespace
{
/// The surface in memory, else the one its file holds.
void ReadUnlessGiven(NamedMesh& mesh)
{
  if (!mesh.Mesh)
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(mesh.FileName);
    reader->Read();
    mesh.Mesh = reader->GetOutput();
  }
}
} // namespace

std::vector<NamedMesh> LoadVesselMeshes(std::vector<NamedMesh> vessels)
{
  std::set<std::string> seen;
  for (NamedMesh& vessel : vessels)
  {
    const std::string problem = ClassNameProblem(vessel.ClassName);
    if (!problem.empty())
    {
      throw ParameterError("Vessels", "'" + Printable(vessel.ClassName) + "': " + problem);
    }
    if (!seen.insert(vessel.ClassName).second)
    {
      throw ParameterError("Vessels", "class '" + vessel.ClassName + "' is given twice");
    }
    ReadUnlessGiven(vessel);
  }
  return vessels;
}

std::vector<NamedMesh> LoadVesselMeshes(const std::vector<std::pair<std::string, std::string>>& pairs)
{
  std::vector<NamedMesh> vessels;
  for (const auto& pair : pairs)
  {
    vessels.push_back({ pair.first, pair.second, nullptr, std::nullopt });
  }
  return LoadVesselMeshes(std::move(vessels));
}

std::vector<NamedMesh> LoadTumourMeshes(std::vector<NamedMesh> tumours)
{
  std::set<std::string> seen;
  for (NamedMesh& tumour : tumours)
  {
    const std::string problem = ClassNameProblem(tumour.ClassName); // it is a column's value and a JSON key
    if (!problem.empty())
    {
      throw ParameterError("Tumours", "tumour id '" + Printable(tumour.ClassName) + "' (" + Printable(tumour.FileName) +
          "): " + problem);
    }
    if (!seen.insert(tumour.ClassName).second)
    {
      throw ParameterError("Tumours", "tumour '" + Printable(tumour.ClassName) + "' is given twice");
    }
    ReadUnlessGiven(tumour);
  }
  return tumours;
}

namespace
{
std::string TumourIdOfFile(const std::string& file)
{
  std::string name = file.substr(file.find_last_of('/') + 1);
  for (const std::string ext : { ".gz", ".stl", ".vtk", ".vtp", ".ply", ".obj" })
  {
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0)
    {
      name.resize(name.size() - ext.size());
    }
  }
  for (char& c : name)
  {
    const auto u = static_cast<unsigned char>(c);
    c = u < 128 && (std::isalnum(u) || c == '_' || c == '-') ? c : '_';
  }
  return name.empty() || !std::isalpha(static_cast<unsigned char>(name[0])) ? "tumour_" + name : name.substr(0, 64);
}

/// Every tumour of a models folder or models.json, under its id and display name.
void AddModelsTumours(const std::string& entry, std::set<std::string>& ids, std::vector<NamedMesh>& tumours)
{
  const ModelsFile models = ReadModelsFile(entry);
  const std::vector<ModelStructure> found = models.WithRole(ModelRole::Tumour);
  if (found.empty())
  {
    std::string names;
    for (const ModelStructure& s : models.Structures)
    {
      names += (names.empty() ? "" : ", ") + s.Name;
    }
    throw InputError(models.FileName, "lists no tumour (it has " + names + "): build the models from a segmentation "
      "with tumour structures, or give the tumour's surface file");
  }
  for (const ModelStructure& s : found)
  {
    ids.insert(s.Name);
    NamedMesh tumour{ s.Name, s.File, nullptr, std::nullopt };
    tumour.DisplayName = s.Label;
    tumours.push_back(std::move(tumour));
  }
}
} // namespace

std::vector<NamedMesh> TumourEntries(const std::vector<std::string>& entries, const std::string& source)
{
  std::vector<NamedMesh> tumours;
  std::set<std::string> ids;
  for (const std::string& entry : entries)
  {
    if (entry.find('=') == std::string::npos && IsModelsPath(entry))
    {
      AddModelsTumours(entry, ids, tumours);
      continue;
    }
    std::error_code ec;
    if (entry.find('=') != std::string::npos && IsModelsPath(entry.substr(entry.find('=') + 1)))
    {
      throw InputError(source, "'" + Printable(entry) + "': a models folder takes no ID= (its tumours keep their own ids: "
        "tumour_01, ...); give the folder alone, or ID=FILE for one tumour's surface");
    }
    if (std::filesystem::is_directory(entry.substr(entry.find('=') + 1), ec))
    {
      throw InputError(entry.substr(entry.find('=') + 1), "is a folder without a models.json: give a tumour's surface, or "
        "a models folder (`vesselproximity models SEGMENTATION -o DIR` builds one surface per tumour)");
    }
    const std::size_t equals = entry.find('=');
    std::string id = equals == std::string::npos ? TumourIdOfFile(entry) : entry.substr(0, equals);
    const std::string file = equals == std::string::npos ? entry : entry.substr(equals + 1);
    if (file.empty())
    {
      throw InputError(source, "expected FILE or ID=FILE for each tumour, got '" + Printable(entry) + "'");
    }
    if (equals == std::string::npos)
    {
      const std::string stem = id;
      for (int k = 2; ids.count(id) > 0; ++k)
      {
        id = stem + "_" + std::to_string(k);
      }
    }
    ids.insert(id);
    tumours.push_back({ id, file, nullptr, std::nullopt });
  }
  return tumours;
}

void RepairVesselMeshes(std::vector<NamedMesh>& meshes)
{
  for (NamedMesh& m : meshes)
  {
    vtkNew<vtkVesselSurfaceRepair> repair;
    repair->SetInputData(m.Mesh);
    repair->Update();
    m.Mesh = repair->GetOutput();
    m.Repair = repair->GetReport();
  }
}
} // namespace vp
