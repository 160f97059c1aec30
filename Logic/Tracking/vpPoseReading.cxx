#include "vpPoseReading.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"
#include "vpText.h"

#include <algorithm>
#include <cctype>

namespace vp
{
namespace
{
/// Which setting a declaration's key names: 0 space, 1 units, 2 time units, -1 none.
int DeclaredSetting(const std::string& key)
{
  const std::string k = LowerCase(key);
  return k == "pose-space" || k == "space" ? 0 : k == "pose-units" || k == "units" ? 1 : k == "time-units" || k == "time_units" ? 2 : -1;
}
} // namespace

bool IsPoseDeclarationKey(const std::string& key)
{
  return DeclaredSetting(key) >= 0;
}

void ApplyPoseDeclaration(const std::string& line, const std::string& source, PoseReading& declared)
{
  const std::size_t separator = line.find_first_of(":=");
  if (separator == std::string::npos)
  {
    return;
  }
  const std::string key = LowerCase(TrimBlanks(line.substr(0, separator)));
  const std::string value = TrimBlanks(line.substr(separator + 1));
  const std::string lower = LowerCase(value);
  auto refuse = [&](const char* expected) {
    throw InputError(source, "declares " + key + " '" + Printable(value) + "'; expected " + expected);
  };
  const int setting = DeclaredSetting(key);
  if (setting == 0)
  {
    if (lower != "lps" && lower != "ras")
    {
      refuse("LPS or RAS");
    }
    declared.Space = lower == "ras" ? PoseSpace::RAS : PoseSpace::LPS;
  }
  else if (setting == 1)
  {
    if (lower != "mm" && lower != "m")
    {
      refuse("mm or m");
    }
    declared.MillimetresPerUnit = lower == "m" ? 1000.0 : 1.0;
  }
  else if (setting == 2)
  {
    if (lower != "s" && lower != "ms")
    {
      refuse("s or ms");
    }
    declared.SecondsPerUnit = lower == "ms" ? 0.001 : 1.0;
  }
}
} // namespace vp
