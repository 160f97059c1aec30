#include "vpModelsFile.h"

#include "vpClassName.h"
#include "vpInputError.h"
#include "vpJsonFile.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace vp
{
namespace
{
namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string StructureText(std::size_t index) { return "structure " + std::to_string(index + 1); }

std::string RequiredString(const Json& s, const char* key, const std::string& file, std::size_t index)
{
  if (!s.contains(key) || !s.at(key).is_string() || s.at(key).get<std::string>().empty())
  {
    throw InputError(file, StructureText(index) + ": no '" + key + "' (a string)");
  }
  return s.at(key).get<std::string>();
}

template <std::size_t N>
std::optional<std::array<double, N>> OptionalNumbers(const Json& s, const char* key, const std::string& file, std::size_t index)
{
  if (!s.contains(key))
  {
    return std::nullopt;
  }
  const Json& v = s.at(key);
  if (!v.is_array() || v.size() != N)
  {
    throw InputError(file, StructureText(index) + ": '" + key + "' is not " + std::to_string(N) + " numbers");
  }
  std::array<double, N> numbers{};
  for (std::size_t k = 0; k < N; ++k)
  {
    if (!v[k].is_number() || !std::isfinite(v[k].get<double>()))
    {
      throw InputError(file, StructureText(index) + ": '" + key + "' is not " + std::to_string(N) + " numbers");
    }
    numbers[k] = v[k].get<double>();
  }
  return numbers;
}

ModelRole RoleOf(const Json& s, const std::string& className, const std::string& file, std::size_t index)
{
  const std::string role = s.contains("role") && s.at("role").is_string() ? s.at("role").get<std::string>() : std::string();
  ModelRole r = ModelRole::Vessel;
  if (ModelRoleFromName(role, r))
  {
    return r;
  }
  if (s.contains("role"))
  {
    throw InputError(file, StructureText(index) + ": role '" + Printable(role) + "' is not vessel, liver or tumour");
  }
  // Written before roles were: the class says it.
  return className == "liver" ? ModelRole::Liver : className == "tumour" ? ModelRole::Tumour : ModelRole::Vessel;
}

ModelStructure ParseStructure(const Json& s, const std::string& file, const fs::path& folder, std::size_t index)
{
  if (!s.is_object())
  {
    throw InputError(file, StructureText(index) + ": not an object");
  }
  ModelStructure m;
  m.ClassName = RequiredString(s, "class", file, index);
  m.Name = s.contains("id") ? RequiredString(s, "id", file, index) : m.ClassName;
  for (const std::string* name : { &m.ClassName, &m.Name })
  {
    const std::string problem = ClassNameProblem(*name);
    if (!problem.empty())
    {
      throw InputError(file, StructureText(index) + ": '" + Printable(*name) + "': " + problem);
    }
  }
  m.Role = RoleOf(s, m.ClassName, file, index);
  m.Label = s.contains("display_name") && s.at("display_name").is_string() ? s.at("display_name").get<std::string>() : m.Name;
  const fs::path relative = fs::path(RequiredString(s, "file", file, index)).lexically_normal();
  if (relative.is_absolute() || relative.empty() || *relative.begin() == "..")
  {
    throw InputError(file, StructureText(index) + ": file '" + Printable(relative.string()) + "' is not beside models.json");
  }
  m.File = (folder / relative).string();
  // "bounds" and "centroid" as the command line's specification names them, in mm.
  m.BoundsMm = OptionalNumbers<6>(s, s.contains("bounds_mm") ? "bounds_mm" : "bounds", file, index);
  m.CentroidMm = OptionalNumbers<3>(s, s.contains("centroid_mm") ? "centroid_mm" : "centroid", file, index);
  m.VolumeMm3 = s.contains("volume_mm3") && s.at("volume_mm3").is_number() ? s.at("volume_mm3").get<double>() : 0.0;
  return m;
}
} // namespace

std::vector<ModelStructure> ModelsFile::WithRole(ModelRole role) const
{
  std::vector<ModelStructure> out;
  for (const ModelStructure& s : this->Structures)
  {
    if (s.Role == role)
    {
      out.push_back(s);
    }
  }
  return out;
}

const ModelStructure* ModelsFile::Find(const std::string& name) const
{
  for (const ModelStructure& s : this->Structures)
  {
    if (s.Name == name)
    {
      return &s;
    }
  }
  return nullptr;
}

bool IsModelsPath(const std::string& path)
{
  std::error_code ec;
  if (fs::is_directory(path, ec))
  {
    return fs::exists(fs::path(path) / "models.json", ec);
  }
  return fs::path(path).filename() == "models.json";
}

ModelsFile ReadModelsFile(const std::string& folderOrJson)
{
  std::error_code ec;
  const bool folder = fs::is_directory(folderOrJson, ec);
  const std::string fileName = folder ? (fs::path(folderOrJson) / "models.json").string() : folderOrJson;
  return ParseModelsFile(ReadJsonFile(fileName, "a models.json"), fileName);
}

ModelsFile ParseModelsFile(const Json& doc, const std::string& fileName)
{
  ModelsFile models;
  models.FileName = fileName;
  if (!doc.is_object() || !doc.contains("structures") || !doc.at("structures").is_array())
  {
    throw InputError(models.FileName, "not a models.json (no \"structures\" list): write it with vesselproximity models");
  }
  models.Space = doc.contains("space") && doc.at("space") == "RAS" ? "RAS" : "LPS";
  const fs::path dir = fs::path(models.FileName).parent_path();
  const Json& structures = doc.at("structures");
  for (std::size_t i = 0; i < structures.size(); ++i)
  {
    models.Structures.push_back(ParseStructure(structures[i], models.FileName, dir, i));
    for (std::size_t j = 0; j + 1 < models.Structures.size(); ++j)
    {
      if (models.Structures[j].Name == models.Structures.back().Name)
      {
        throw InputError(models.FileName, StructureText(i) + ": '" + models.Structures.back().Name + "' is listed twice");
      }
    }
  }
  if (models.Structures.empty())
  {
    throw InputError(models.FileName, "lists no structure");
  }
  return models;
}
} // namespace vp
