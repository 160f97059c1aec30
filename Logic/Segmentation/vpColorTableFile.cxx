#include "vpColorTableFile.h"

#include "vpDecimal.h"
#include "vpInputError.h"
#include "vpRegularFile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <vector>

namespace vp
{
std::map<int, std::string> ParseColorTableNames(const std::string& text, const std::string& source)
{
  std::map<int, std::string> names;
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);)
  {
    ++number;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
    {
      line.erase(0, 3); // a byte order mark
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (std::any_of(line.begin(), line.end(), [](char c) { return c != '\t' && std::iscntrl(static_cast<unsigned char>(c)); }))
    {
      throw InputError(source, where + "control characters: not a colour table");
    }
    if (line.rfind("# Color procedural file", 0) == 0)
    {
      throw InputError(source, where + "a procedural colour file names no label values");
    }
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t") == std::string::npos)
    {
      continue;
    }
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string field; fields >> field;)
    {
      f.push_back(field);
    }
    if (f.size() < 5 || f.size() > 6)
    {
      throw InputError(source, where + "expected 'value name r g b a', got " + std::to_string(f.size()) + " field(s)");
    }
    double value = 0.0;
    if (!ParseDecimal(f[0], value) || value != std::floor(value) || value < 0 || value > 1000000)
    {
      throw InputError(source, where + "the label value '" + f[0] + "' is not an integer from 0 to 1000000");
    }
    for (std::size_t c = 2; c < f.size(); ++c)
    {
      double channel = 0.0;
      if (!ParseDecimal(f[c], channel) || channel < 0.0 || channel > 255.0)
      {
        throw InputError(source, where + "the colour component '" + f[c] + "' is not a number from 0 to 255");
      }
    }
    const int label = static_cast<int>(value);
    std::string name = f[1] == "_" ? std::string() : f[1];
    std::replace(name.begin(), name.end(), '_', ' ');
    if (names.count(label))
    {
      throw InputError(source, where + "label value " + f[0] + " is named twice");
    }
    if (label != 0 && !name.empty())
    {
      names[label] = name;
    }
  }
  return names;
}

std::map<int, std::string> ReadColorTableNames(const std::string& fileName)
{
  // Slicer's largest bundled tables (GenericAnatomyColors) are about 20 kB.
  return ParseColorTableNames(ReadSmallFile(fileName, "colour table", 16u << 20), fileName);
}
} // namespace vp
