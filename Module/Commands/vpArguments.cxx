#include "vpArguments.h"

#include "vpText.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"

#include <cctype>

namespace vp
{
cli::Parameter Option(cli::ParameterType type, const std::string& longFlag, const std::string& description)
{
  return cli::Parameter(type, CamelCase(longFlag, false)).SetLongFlag(longFlag).SetDescription(description);
}

cli::Parameter Switch(const std::string& longFlag, const std::string& description)
{
  return Option(cli::ParameterType::Boolean, longFlag, description).SetDefault("false");
}

cli::Parameter OutputFolderOption(const std::string& description)
{
  return Option(cli::ParameterType::Directory, "output", description)
    .SetFlag("o")
    .SetChannel(cli::Channel::Output)
    .SetPlaceholder("OUTDIR");
}

cli::Parameter VesselsOption()
{
  return Option(cli::ParameterType::String, "vessels",
    "The vessel surface models by class (portal_vein, hepatic_artery, hepatic_vein, or any name): STL, VTK, VTP or "
    "OBJ; a SPACE=RAS/LPS header tag is honoured, untagged files are LPS.")
    .SetPlaceholder("CLASS=FILE[,CLASS=FILE...]")
    .SetLogicName("Vessels");
}

cli::Parameter RepairSwitch()
{
  return Switch("repair",
    "Merge coincident points, drop duplicated triangles and fins, fill holes up to 30 mm and make the winding "
    "consistent before building (vtkVesselSurfaceRepair; no point moves), saying per class on stderr what "
    "changed; an open surface's inside is otherwise a vote of five rays.");
}

bool WantsHelp(const std::vector<std::string>& args)
{
  for (const auto& a : args)
  {
    if (a == "--help" || a == "-h")
    {
      return true;
    }
  }
  return false;
}

std::vector<std::string> SplitList(const std::string& text, char separator)
{
  std::vector<std::string> items;
  std::size_t start = 0;
  for (std::size_t at = text.find(separator); at != std::string::npos; at = text.find(separator, start))
  {
    items.push_back(text.substr(start, at - start));
    start = at + 1;
  }
  items.push_back(text.substr(start));
  return items;
}

std::vector<std::pair<std::string, std::string>> ParsePairs(const std::string& text, const std::string& option)
{
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& entry : SplitList(text, ','))
  {
    const std::size_t eq = entry.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == entry.size())
    {
      throw InputError(option, "expected CLASS=FILE, got '" + entry + "'");
    }
    // Blanks around a name or a path are the list's layout, never part of them.
    pairs.emplace_back(TrimBlanks(entry.substr(0, eq)), TrimBlanks(entry.substr(eq + 1)));
    if (pairs.back().first.empty() || pairs.back().second.empty())
    {
      throw InputError(option, "expected CLASS=FILE, got '" + entry + "'");
    }
  }
  return pairs;
}
} // namespace vp
