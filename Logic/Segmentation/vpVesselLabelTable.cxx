#include "vpVesselLabelTable.h"

#include "vpClassName.h"
#include "vpInputError.h"
#include "vpRegularFile.h"

#include "VesselLabels_json.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

namespace vp
{
namespace
{
// "Portal_Vein", "portal-vein" and "portal  vein" are one name.
std::string Normalized(const std::string& name)
{
  std::string out;
  for (unsigned char c : name)
  {
    const char k = (c == '_' || c == '-') ? ' ' : static_cast<char>(std::tolower(c));
    if (k == ' ' && (out.empty() || out.back() == ' '))
    {
      continue;
    }
    out.push_back(k);
  }
  while (!out.empty() && out.back() == ' ')
  {
    out.pop_back();
  }
  return out;
}

// "liver tumor 03" holds "tumor": words are matched with the blanks left out.
std::string Squeezed(const std::string& normalized)
{
  std::string out;
  for (char c : normalized)
  {
    if (c != ' ')
    {
      out.push_back(c);
    }
  }
  return out;
}

ModelRole ParseRole(const nlohmann::json& entry, const std::string& name, const std::string& source)
{
  const std::string fallback = name == "liver" ? "liver" : name == "tumour" ? "tumour" : "vessel";
  const std::string role = entry.value("role", fallback);
  ModelRole r = ModelRole::Vessel;
  if (ModelRoleFromName(role, r))
  {
    return r;
  }
  throw InputError(source, "class \"" + name + "\": role \"" + Printable(role) + "\" is not vessel, liver or tumour");
}
} // namespace

VesselLabelTable VesselLabelTable::Default()
{
  return Parse(std::string(reinterpret_cast<const char*>(VesselLabels_json), VesselLabels_json_size),
    "Resources/VesselLabels.json");
}

VesselLabelTable VesselLabelTable::Load(const std::string& fileName)
{
  // A label table names a few classes: a device, a pipe or a file of megabytes is none.
  constexpr std::uint64_t MaxBytes = 1u << 20;
  const std::uint64_t size = RegularFileSize(fileName, "is a folder, not a label table",
    "is not a regular file (a device, pipe or socket), not a label table");
  if (size > MaxBytes)
  {
    throw InputError(fileName, "is " + std::to_string(size) + " bytes: a label table holds at most " +
        std::to_string(MaxBytes) + " (a few classes and their names)");
  }
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    throw InputError(fileName, "cannot be opened");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return Parse(text.str(), fileName);
}

VesselLabelTable VesselLabelTable::Parse(const std::string& json, const std::string& source)
{
  VesselLabelTable table;
  try
  {
    const nlohmann::json doc = nlohmann::json::parse(json);
    const auto& classes = doc.at("classes");
    if (!classes.is_array() || classes.empty())
    {
      throw InputError(source, "\"classes\" must be a non-empty array");
    }
    for (const auto& entry : classes)
    {
      const std::string name = entry.at("class").get<std::string>();
      const std::string problem = ClassNameProblem(name);
      if (!problem.empty())
      {
        throw InputError(source, "class \"" + Printable(name) + "\": " + problem);
      }
      if (std::count(table.ClassNames.begin(), table.ClassNames.end(), name))
      {
        throw InputError(source, "class \"" + name + "\" is listed twice");
      }
      table.ClassNames.push_back(name);
      table.Colors[name] = entry.value("color", std::array<double, 3>{ 0.8, 0.8, 0.8 });
      table.Roles[name] = ParseRole(entry, name, source);
      for (const auto& word : entry.value("name_excludes", std::vector<std::string>{}))
      {
        table.Excludes[name].push_back(Squeezed(Normalized(word)));
      }
      for (const auto& word : entry.value("name_contains", std::vector<std::string>{}))
      {
        const std::string part = Squeezed(Normalized(word));
        if (part.size() < 3)
        {
          throw InputError(source, "class \"" + name + "\": name_contains word \"" + Printable(word) +
              "\" is under 3 letters (it would match names of other structures)");
        }
        table.ByNamePart.emplace_back(part, name);
      }
      auto claim = [&](auto& map, const auto& key, const std::string& what) {
        if (map.count(key) && map.at(key) != name)
        {
          std::ostringstream k;
          k << key;
          throw InputError(source, what + " \"" + k.str() + "\" maps to both " + map.at(key) + " and " + name);
        }
        map[key] = name;
      };
      for (const auto& n : entry.value("names", std::vector<std::string>{}))
      {
        claim(table.ByName, Normalized(n), "name");
      }
      for (const auto& c : entry.value("codes", std::vector<std::string>{}))
      {
        claim(table.ByCode, c, "code");
      }
      for (int v : entry.value("values", std::vector<int>{}))
      {
        claim(table.ByValue, v, "value");
      }
    }
  }
  catch (const nlohmann::json::exception& e)
  {
    std::string what = e.what();
    throw InputError(source, "not a label table: " + what.substr(what.find(']') + 2));
  }
  return table;
}

bool VesselLabelTable::Excluded(const std::string& squeezed, const std::string& className) const
{
  const auto it = this->Excludes.find(className);
  return it != this->Excludes.end() &&
    std::any_of(it->second.begin(), it->second.end(), [&](const std::string& w) { return squeezed.find(w) != std::string::npos; });
}

std::string VesselLabelTable::ClassOfName(const std::string& name) const
{
  const std::string normalized = Normalized(name);
  const std::string squeezed = Squeezed(normalized);
  // The name as listed, then without a number after it ("Tumor 2", "lesion_3").
  std::string unnumbered = normalized;
  while (!unnumbered.empty() && (std::isdigit(static_cast<unsigned char>(unnumbered.back())) || unnumbered.back() == ' '))
  {
    unnumbered.pop_back();
  }
  for (const std::string* candidate : std::initializer_list<const std::string*>{ &normalized, &unnumbered })
  {
    const auto it = this->ByName.find(*candidate);
    if (it != this->ByName.end() && !this->Excluded(squeezed, it->second))
    {
      return it->second;
    }
  }
  for (const auto& [part, cls] : this->ByNamePart)
  {
    if (squeezed.find(part) != std::string::npos && !this->Excluded(squeezed, cls))
    {
      return cls;
    }
  }
  return std::string();
}

ModelRole VesselLabelTable::RoleOf(const std::string& className) const
{
  const auto it = this->Roles.find(className);
  return it == this->Roles.end() ? ModelRole::Vessel : it->second;
}

std::string VesselLabelTable::ClassOf(const LabelStructure& structure) const
{
  if (!structure.Type.Empty())
  {
    const auto it = this->ByCode.find(structure.Type.Key());
    if (it != this->ByCode.end())
    {
      return it->second;
    }
  }
  const std::string byName = this->ClassOfName(structure.Name);
  if (!byName.empty())
  {
    return byName;
  }
  // An unnamed label, or a labelmap of one value whose name (its file's) the table does not know:
  // the value is all that says what it is (Slicer hands a CLI a temporary file of a volume).
  if (structure.IsUnnamed())
  {
    const auto it = this->ByValue.find(structure.LabelValue);
    if (it != this->ByValue.end())
    {
      return it->second;
    }
  }
  return std::string();
}

std::array<double, 3> VesselLabelTable::Color(const std::string& className) const
{
  const auto it = this->Colors.find(className);
  return it == this->Colors.end() ? std::array<double, 3>{ 0.8, 0.8, 0.8 } : it->second;
}
} // namespace vp
