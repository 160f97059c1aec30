// vesselproximity: the host program. Like Slicer's launcher it knows no computation itself: it
// loads the modules on its module path and hands each command to the module that declares it.
#include "vpLoadableModuleApi.h"
#include "vpModuleLoader.h"

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
const char* Usage = "usage: vesselproximity [--module-path DIR[:DIR...]] COMMAND [options]   (COMMAND --help for its options)\n";
const char* ExitCodes =
  "module path: --module-path, else VP_MODULE_PATH, else lib/vesselproximity-modules (installed:\n"
  "             lib/Slicer-X.Y/vesselproximity-modules) beside the program's folder\n"
  "exit codes: 0 success, 1 bad input (one line on stderr names the file and the problem),\n"
  "            2 bad usage, 3 internal error, 4 no usable Vulkan device (z-buffer engine),\n"
  "            5 no usable module on the module path\n";

/// Slicer writes several values in one field separated by ';'; listed here one per ", ".
std::string Listed(const char* text)
{
  std::string out = text ? text : "";
  for (std::size_t at = out.find(';'); at != std::string::npos; at = out.find(';', at))
  {
    out.replace(at, 1, ", ");
  }
  return out;
}

/// Text wrapped at 96 columns, each line indented.
void PrintWrapped(const char* text, const char* indent)
{
  std::string line;
  std::string word;
  auto flush = [&] {
    std::cout << indent << line << "\n";
    line.clear();
  };
  for (const char* c = text ? text : "";; ++c)
  {
    if (*c == ' ' || *c == '\n' || *c == '\0')
    {
      if (!word.empty())
      {
        if (!line.empty() && line.size() + 1 + word.size() > 92)
        {
          flush();
        }
        line += (line.empty() ? "" : " ") + word;
        word.clear();
      }
      if ((*c == '\n' || *c == '\0') && !line.empty())
      {
        flush();
      }
      if (*c == '\0')
      {
        break;
      }
    }
    else
    {
      word += *c;
    }
  }
}

void PrintHelp(const std::vector<vp::LoadedModule>& modules)
{
  std::cout << Usage << "\nloaded modules:\n";
  for (const vp::LoadedModule& m : modules)
  {
    const vpModuleDescriptor& d = *m.Descriptor;
    std::cout << "  " << d.Title << " " << d.Version << "  (module " << d.Name << ", category " << Listed(d.Categories)
              << ")\n    library: " << m.Library << "\n    contributors: " << Listed(d.Contributors) << "\n";
    PrintWrapped(d.HelpText, "    ");
    std::cout << "    acknowledgement:\n";
    PrintWrapped(d.Acknowledgement, "      ");
  }
  std::cout << "\ncommands:\n";
  for (const vp::LoadedModule& m : modules)
  {
    for (int c = 0; c < m.Descriptor->NumberOfCommands; ++c)
    {
      const vpModuleCommand& command = m.Descriptor->Commands[c];
      std::cout << "  " << command.Name << std::string(command.Name && std::strlen(command.Name) < 10 ? 10 - std::strlen(command.Name) : 1, ' ')
                << " " << command.Summary << "\n";
    }
  }
  std::cout << ExitCodes;
}

/// Takes a leading --module-path DIR (or --module-path=DIR) off args into modulePath; false
/// (after saying why) when it names no folder.
bool TakeModulePath(std::vector<std::string>& args, std::string& modulePath)
{
  if (args.empty() || !(args[0] == "--module-path" || args[0].rfind("--module-path=", 0) == 0))
  {
    return true;
  }
  const bool separate = args[0] == "--module-path";
  if (separate && args.size() < 2)
  {
    std::cerr << "vesselproximity: error: --module-path: a folder is required\n";
    return false;
  }
  modulePath = separate ? args[1] : args[0].substr(std::strlen("--module-path="));
  args.erase(args.begin(), args.begin() + (separate ? 2 : 1));
  if (modulePath.empty())
  {
    std::cerr << "vesselproximity: error: --module-path: a folder is required\n";
    return false;
  }
  return true;
}

/// The command of that name in any loaded module, or null.
const vpModuleCommand* FindCommand(const std::vector<vp::LoadedModule>& modules, const std::string& name)
{
  for (const vp::LoadedModule& m : modules)
  {
    for (int c = 0; c < m.Descriptor->NumberOfCommands; ++c)
    {
      if (name == m.Descriptor->Commands[c].Name)
      {
        return &m.Descriptor->Commands[c];
      }
    }
  }
  return nullptr;
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string modulePath;
  if (!TakeModulePath(args, modulePath))
  {
    return 2;
  }
  if (!args.empty() && args[0] == "--version")
  {
    std::cout << "vesselproximity " VP_VERSION "\n";
    return 0;
  }
  std::vector<vp::LoadedModule> modules;
  try
  {
    modules = vp::ModuleLoader::Load(vp::ModuleLoader::SearchPath(modulePath));
  }
  catch (const vp::ModuleLoadError& e)
  {
    std::cerr << "vesselproximity: error: " << e.what() << "\n";
    return 5;
  }
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help")
  {
    PrintHelp(modules);
    return args.empty() ? 2 : 0;
  }
  const vpModuleCommand* command = FindCommand(modules, args[0]);
  if (!command)
  {
    std::cerr << "vesselproximity: error: unknown command '" << args[0] << "' (see vesselproximity --help)\n";
    return 2;
  }
  std::vector<const char*> commandArgv;
  for (const std::string& a : args)
  {
    commandArgv.push_back(a.c_str());
  }
  return command->Run(static_cast<int>(commandArgv.size()), commandArgv.data());
}
