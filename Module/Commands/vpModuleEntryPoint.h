#ifndef vpModuleEntryPoint_h
#define vpModuleEntryPoint_h

#include "vpCommandTable.h"
#include "vpLoadableModuleApi.h"

#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// The C side of a loadable module: its descriptor (metadata from ModuleClass, commands from
/// Table) and one C trampoline per command, so that no C++ type or exception ever crosses the
/// library boundary. Each module's entry point returns ModuleEntryPoint<...>::Descriptor().
template <class ModuleClass, const std::vector<CommandEntry>& (*Table)()>
class ModuleEntryPoint
{
public:
  static const vpModuleDescriptor* Descriptor() { return &Record().Descriptor; }

private:
  static std::string Joined(const std::vector<std::string>& items)
  {
    std::string out;
    for (const auto& item : items)
    {
      out += (out.empty() ? "" : ";") + item;
    }
    return out;
  }

  /// A C function pointer cannot carry state: the table index is a template argument.
  template <std::size_t Index>
  static int RunCommand(int argc, const char* const* argv)
  {
    const std::vector<std::string> args(argc > 1 ? argv + 1 : argv, argc > 1 ? argv + argc : argv);
    return RunCommandReportingErrors(Table()[Index], args, Record().Module);
  }

  template <std::size_t... Index>
  static std::vector<vpModuleCommandFunction> Trampolines(std::index_sequence<Index...>)
  {
    return { &RunCommand<Index>... };
  }

  /// Everything the descriptor points into, alive as long as the library is loaded.
  struct ModuleRecord
  {
    ModuleClass Module;
    std::string Name = Module.Name(), Title = Module.Title(), Categories = Joined(Module.Categories()),
                Contributors = Joined(Module.Contributors()), Help = Module.HelpText(),
                Acknowledgement = Module.AcknowledgementText(), Version = Module.Version();
    std::vector<std::string> Summaries; // each command's title, from its description
    std::vector<vpModuleCommand> Commands;
    vpModuleDescriptor Descriptor{};

    ModuleRecord()
    {
      constexpr std::size_t MaxCommands = 32; // more than a table holds; the host tests list them all
      const auto run = Trampolines(std::make_index_sequence<MaxCommands>());
      const auto& table = Table();
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

  static const ModuleRecord& Record()
  {
    static const ModuleRecord record;
    return record;
  }
};
} // namespace vp

#endif
