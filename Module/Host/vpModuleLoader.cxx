#include "vpModuleLoader.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

namespace fs = std::filesystem;

namespace vp
{
namespace
{
std::vector<std::string> SplitPath(const std::string& text)
{
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= text.size())
  {
    const std::size_t end = std::min(text.find(':', start), text.size());
    if (end > start)
    {
      parts.push_back(text.substr(start, end - start));
    }
    start = end + 1;
  }
  return parts;
}

std::string ProgramFolder()
{
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : exe.parent_path().string();
}

std::string OneLine(std::string text)
{
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

/// lib<Name>Module.so, as Slicer tells its loadable modules (lib qSlicer<Name>Module.so) from the
/// libraries beside them: installed, the module's folder also holds the logic library it links.
bool IsModuleLibrary(const fs::path& file)
{
  const std::string name = file.filename().string();
  const std::string suffix = "Module.so";
  return name.size() > 3 + suffix.size() && name.compare(0, 3, "lib") == 0 &&
    name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}
} // namespace

std::vector<std::string> ModuleLoader::SearchPath(const std::string& explicitPath)
{
  if (!explicitPath.empty())
  {
    return SplitPath(explicitPath);
  }
  const char* env = std::getenv("VP_MODULE_PATH");
  if (env && *env)
  {
    return SplitPath(env);
  }
  // The build tree's folder, else the installed tree's (VP_INSTALLED_MODULE_DIR, relative to bin/).
  const fs::path program = ProgramFolder();
  const fs::path built = (program / ".." / "lib" / "vesselproximity-modules").lexically_normal();
#ifdef VP_INSTALLED_MODULE_DIR
  const fs::path installed = (program / VP_INSTALLED_MODULE_DIR).lexically_normal();
  std::error_code ec;
  if (!fs::is_directory(built, ec) && fs::is_directory(installed, ec))
  {
    return { installed.string() };
  }
#endif
  return { built.string() };
}

std::vector<LoadedModule> ModuleLoader::Load(const std::vector<std::string>& folders)
{
  std::vector<LoadedModule> modules;
  std::set<std::string> names;
  for (const std::string& folder : folders)
  {
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
    {
      throw ModuleLoadError("module path " + folder + ": no such folder");
    }
    std::vector<fs::path> libraries;
    for (const auto& entry : fs::directory_iterator(folder, ec))
    {
      if (entry.is_regular_file(ec) && IsModuleLibrary(entry.path()))
      {
        libraries.push_back(entry.path());
      }
    }
    std::sort(libraries.begin(), libraries.end());
    for (const fs::path& library : libraries)
    {
      void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle)
      {
        const char* why = dlerror();
        throw ModuleLoadError(library.string() + ": cannot load module library: " + OneLine(why ? why : "unknown error"));
      }
      auto entry = reinterpret_cast<vpGetLoadableModuleFunction>(dlsym(handle, VP_MODULE_ENTRY_POINT));
      if (!entry)
      {
        throw ModuleLoadError(library.string() + ": not a VesselProximity module (no " VP_MODULE_ENTRY_POINT " entry point)");
      }
      const vpModuleDescriptor* descriptor = entry();
      if (!descriptor || descriptor->ApiVersion != VP_MODULE_API_VERSION)
      {
        throw ModuleLoadError(library.string() + ": module API version " +
          (descriptor ? std::to_string(descriptor->ApiVersion) : std::string("(none)")) + ", this program needs " +
          std::to_string(VP_MODULE_API_VERSION));
      }
      if (!descriptor->Name || !names.insert(descriptor->Name).second)
      {
        throw ModuleLoadError(library.string() + ": a module named '" + std::string(descriptor->Name ? descriptor->Name : "") +
          "' is already loaded");
      }
      modules.push_back({ library.string(), descriptor });
    }
  }
  if (modules.empty())
  {
    std::string joined;
    for (const auto& folder : folders)
    {
      joined += (joined.empty() ? "" : ":") + folder;
    }
    throw ModuleLoadError("module path " + joined + ": no loadable module there (lib*Module.so exporting " VP_MODULE_ENTRY_POINT ")");
  }
  return modules;
}
} // namespace vp
