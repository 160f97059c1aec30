#include "vpOutputGuard.h"

#include "vpCliValues.h"
#include "vpInputError.h"

#include <sys/stat.h>
#include <unistd.h>

#include <set>
#include <utility>

namespace vp
{
namespace cli
{
namespace
{
using Identity = std::pair<dev_t, ino_t>;

/// An output written as one file (a folder output is RunFolder's to guard).
bool IsOutputFile(const Parameter& p)
{
  return p.GetChannel() == Channel::Output && IsData(p.GetType()) && p.GetType() != ParameterType::Directory;
}

/// The paths a value may name: itself, and each entry of a list, "NAME=FILE" by its file.
std::vector<std::string> PathsIn(const std::string& value)
{
  std::vector<std::string> paths = { value };
  std::size_t begin = 0;
  while (begin <= value.size())
  {
    const std::size_t end = std::min(value.find_first_of(",;", begin), value.size());
    const std::string entry = value.substr(begin, end - begin);
    const std::size_t equals = entry.find('=');
    paths.push_back(entry);
    if (equals != std::string::npos)
    {
      paths.push_back(entry.substr(equals + 1));
    }
    begin = end + 1;
  }
  return paths;
}

struct NamedInput
{
  Identity Id;
  std::string Parameter, Path;
};

/// Every existing path the command line's inputs name (any parameter but the file outputs), by
/// identity; and the file outputs, by parameter.
void CollectPaths(const ModuleDescription& description, const std::map<std::string, std::string>& values,
  const std::map<std::string, std::vector<std::string>>& multiple, std::vector<NamedInput>& inputs,
  std::vector<std::pair<std::string, std::string>>& outputs)
{
  for (const auto& group : description.Groups)
  {
    for (const auto& p : group.Parameters)
    {
      const auto given = values.find(p.GetName());
      if (given == values.end() || given->second.empty())
      {
        continue;
      }
      if (IsOutputFile(p))
      {
        outputs.emplace_back(p.DisplayName(), given->second);
        continue;
      }
      const auto all = multiple.find(p.GetName());
      for (const std::string& value : all != multiple.end() ? all->second : std::vector<std::string>{ given->second })
      {
        for (const std::string& path : PathsIn(value))
        {
          struct stat info{};
          if (!path.empty() && ::stat(path.c_str(), &info) == 0)
          {
            inputs.push_back({ { info.st_dev, info.st_ino }, p.DisplayName(), path });
          }
        }
      }
    }
  }
}

/// Refuses a symbolic link as an output unless the user made it or its owner owns its target:
/// a link another user planted at a system file is not followed, even by root.
void RefusePlantedLink(const std::string& parameter, const std::string& path, const struct stat& link, const struct stat* target)
{
  const bool ours = link.st_uid == ::geteuid();
  const bool ownersTarget = target && target->st_uid == link.st_uid;
  if (S_ISLNK(link.st_mode) && !ours && !ownersTarget)
  {
    throw InputError(parameter, "'" + path + "' is a symbolic link made by another user to a file that is not theirs: "
      "not written through");
  }
}
} // namespace

void RefuseOutputsOverInputs(const ModuleDescription& description, const std::map<std::string, std::string>& values,
  const std::map<std::string, std::vector<std::string>>& multiple, const std::string& returnParameterFile)
{
  std::vector<NamedInput> inputs;
  std::vector<std::pair<std::string, std::string>> outputs; // parameter, path
  CollectPaths(description, values, multiple, inputs, outputs);
  if (!returnParameterFile.empty())
  {
    outputs.emplace_back("--returnparameterfile", returnParameterFile);
  }
  std::set<Identity> written;
  for (const auto& [parameter, path] : outputs)
  {
    struct stat link{}, target{};
    if (::lstat(path.c_str(), &link) != 0)
    {
      continue; // a new file: it can replace nothing
    }
    const bool reaches = ::stat(path.c_str(), &target) == 0;
    RefusePlantedLink(parameter, path, link, reaches ? &target : nullptr);
    if (!reaches)
    {
      continue; // a link to a new file: it can replace nothing
    }
    const Identity id{ target.st_dev, target.st_ino };
    for (const NamedInput& in : inputs)
    {
      if (in.Id == id)
      {
        throw InputError(parameter, "'" + path + "' is also an input (" + in.Parameter + " " + in.Path +
          "): an output never replaces an input; name another file");
      }
    }
    if (!written.insert(id).second)
    {
      throw InputError(parameter, "'" + path + "' is named by another output too");
    }
  }
}
} // namespace cli
} // namespace vp
