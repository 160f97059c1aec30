// The C entry point of the VesselProximity module library: the host program finds it with
// dlsym and learns the module's metadata and commands from the descriptor, so no C++ type or
// exception ever crosses the library boundary.
#include "vpCommandTable.h"
#include "vpLoadableModuleApi.h"
#include "vpVesselProximityModule.h"

#include <string>
#include <utility>
#include <vector>

namespace
{
std::string Joined(const std::vector<std::string>& items)
{
  std::string out;
  for (const auto& item : items)
  {
    out += (out.empty() ? "" : ";") + item;
  }
  return out;
}

struct ModuleRecord;
const ModuleRecord& Record();

/// One C trampoline per command: the table index is a template argument, since a C function
/// pointer cannot carry state. The command runs in the module, which creates its logic.
template <std::size_t Index>
int RunCommand(int argc, const char* const* argv);

template <std::size_t... Index>
std::vector<vpModuleCommandFunction> Trampolines(std::index_sequence<Index...>)
{
  return { &RunCommand<Index>... };
}

/// Everything the descriptor points into, alive as long as the library is loaded.
struct ModuleRecord
{
  vpVesselProximityModule Module;
  std::string Name = Module.Name(), Title = Module.Title(), Categories = Joined(Module.Categories()),
              Contributors = Joined(Module.Contributors()), Help = Module.HelpText(),
              Acknowledgement = Module.AcknowledgementText(), Version = Module.Version();
  std::vector<std::string> Summaries; // each command's title, from its description
  std::vector<vpModuleCommand> Commands;
  vpModuleDescriptor Descriptor{};

  ModuleRecord()
  {
    constexpr std::size_t MaxCommands = 32; // more than the table holds; the host tests list them all
    const auto run = Trampolines(std::make_index_sequence<MaxCommands>());
    const auto& table = vp::CommandTable();
    for (std::size_t i = 0; i < table.size() && i < MaxCommands; ++i)
    {
      this->Summaries.push_back(table[i].Describe().Title);
    }
    for (std::size_t i = 0; i < this->Summaries.size(); ++i)
    {
      this->Commands.push_back({ table[i].Name, this->Summaries[i].c_str(), run[i] });
    }
    this->Descriptor = { VP_MODULE_API_VERSION, this->Name.c_str(), this->Title.c_str(), this->Categories.c_str(),
      this->Contributors.c_str(), this->Help.c_str(), this->Acknowledgement.c_str(), this->Version.c_str(),
      this->Commands.data(), static_cast<int>(this->Commands.size()) };
  }
};
const ModuleRecord& Record()
{
  static const ModuleRecord record;
  return record;
}

template <std::size_t Index>
int RunCommand(int argc, const char* const* argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  return vp::RunCommandReportingErrors(vp::CommandTable()[Index], args, Record().Module);
}
} // namespace

extern "C" __attribute__((visibility("default"))) const vpModuleDescriptor* vpGetLoadableModule(void)
{
  return &Record().Descriptor;
}
