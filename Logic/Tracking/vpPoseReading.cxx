#include "vpPoseReading.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"

#include <algorithm>
#include <cctype>

namespace vp
{
const char* PoseSpaceName(PoseSpace space)
{
  return space == PoseSpace::RAS ? "RAS" : "LPS";
}

namespace
{
std::string Lower(std::string text)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}
} // namespace

void ApplyPoseDeclaration(const std::string& line, const std::string& source, PoseReading& declared)
{
  const std::size_t separator = line.find_first_of(":=");
  if (separator == std::string::npos)
  {
    return;
  }
  const std::string key = Lower(TrimBlanks(line.substr(0, separator)));
  const std::string value = TrimBlanks(line.substr(separator + 1));
  const std::string lower = Lower(value);
  auto refuse = [&](const char* expected) {
    throw InputError(source, "declares " + key + " '" + Printable(value) + "'; expected " + expected);
  };
  if (key == "pose-space" || key == "space")
  {
    if (lower != "lps" && lower != "ras")
    {
      refuse("LPS or RAS");
    }
    declared.Space = lower == "ras" ? PoseSpace::RAS : PoseSpace::LPS;
  }
  else if (key == "pose-units" || key == "units")
  {
    if (lower != "mm" && lower != "m")
    {
      refuse("mm or m");
    }
    declared.MillimetresPerUnit = lower == "m" ? 1000.0 : 1.0;
  }
  else if (key == "time-units" || key == "time_units")
  {
    if (lower != "s" && lower != "ms")
    {
      refuse("s or ms");
    }
    declared.SecondsPerUnit = lower == "ms" ? 0.001 : 1.0;
  }
}
} // namespace vp
