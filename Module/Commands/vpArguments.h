#ifndef vpArguments_h
#define vpArguments_h

// The pieces the subcommands' parameter tables are made of, and the text their values share.
// Each command declares its parameters once (cli::ModuleDescription::Subcommand); the same table
// gives its parser and its --help (vpCliDescription.h).

#include "vpCliDescription.h"

#include <string>
#include <utility>
#include <vector>

namespace vp
{
/// An option --long-flag of the given type, named for the flag in camel case ("frame-budget-ms"
/// is read as "frameBudgetMs"), with what it does. Chain the rest: .SetDefault("16.7").
cli::Parameter Option(cli::ParameterType type, const std::string& longFlag, const std::string& description);
/// A switch --long-flag: off unless given.
cli::Parameter Switch(const std::string& longFlag, const std::string& description);
/// -o DIR (also --output): the folder a command writes its run into.
cli::Parameter OutputFolderOption(const std::string& description);
/// --vessels CLASS=FILE[,CLASS=FILE...], read by LoadVesselMeshes(ParsePairs(...)).
cli::Parameter VesselsOption();
/// --repair: vtkVesselSurfaceRepair before building.
cli::Parameter RepairSwitch();

/// True when args ask for help (--help or -h anywhere).
bool WantsHelp(const std::vector<std::string>& args);

/// Splits text at every separator, empty items kept ("a,,b" -> "a", "", "b"; "" -> "").
std::vector<std::string> SplitList(const std::string& text, char separator);

/// Splits "a=b,c=d" into pairs; throws InputError(option, ...) on a malformed entry.
std::vector<std::pair<std::string, std::string>> ParsePairs(const std::string& text, const std::string& option);
} // namespace vp

#endif
