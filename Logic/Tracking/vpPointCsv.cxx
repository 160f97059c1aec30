#include "vpPointCsv.h"

#include "vpInputError.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

namespace vp
{
namespace
{
/// Splits on commas (and surrounding blanks); each field must be one number.
bool ParseNumbers(const std::string& text, std::vector<double>& values, std::string& problem)
{
  values.clear();
  const char* p = text.c_str();
  while (true)
  {
    while (*p == ' ' || *p == '\t' || *p == '\r')
    {
      ++p;
    }
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p)
    {
      problem = "'" + text.substr(0, 40) + "' is not a list of numbers";
      return false;
    }
    if (!std::isfinite(v))
    {
      problem = "NaN or infinite value";
      return false;
    }
    values.push_back(v);
    p = end;
    while (*p == ' ' || *p == '\t' || *p == '\r')
    {
      ++p;
    }
    if (*p == '\0')
    {
      return true;
    }
    if (*p != ',')
    {
      problem = "'" + text.substr(0, 40) + "' is not a list of numbers";
      return false;
    }
    ++p;
  }
}
} // namespace

std::array<double, 3> ParsePoint(const std::string& text, const std::string& source)
{
  std::vector<double> values;
  std::string problem;
  if (!ParseNumbers(text, values, problem))
  {
    throw InputError(source, "expected X,Y,Z: " + problem);
  }
  if (values.size() != 3)
  {
    throw InputError(source, "expected X,Y,Z (3 numbers), got " + std::to_string(values.size()));
  }
  return { values[0], values[1], values[2] };
}

std::vector<std::array<double, 3>> ReadPointCsv(const std::string& fileName)
{
  struct stat info;
  if (stat(fileName.c_str(), &info) != 0)
  {
    throw InputError(fileName, errno == ENOENT ? "no such file" : std::strerror(errno));
  }
  std::ifstream in(fileName);
  if (!in || S_ISDIR(info.st_mode))
  {
    throw InputError(fileName, "cannot open as a point list");
  }
  std::vector<std::array<double, 3>> points;
  std::string line;
  std::size_t number = 0;
  std::vector<double> values;
  while (std::getline(in, line))
  {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    std::string problem;
    if (!ParseNumbers(line, values, problem))
    {
      char* end = nullptr;
      std::strtod(line.c_str() + first, &end);
      if (points.empty() && end == line.c_str() + first)
      {
        continue; // a header: its first field is no number at all
      }
      throw InputError(fileName, "line " + std::to_string(number) + ": " + problem);
    }
    if (values.size() != 3)
    {
      throw InputError(fileName, "line " + std::to_string(number) + ": expected x,y,z (3 numbers), got " +
          std::to_string(values.size()));
    }
    points.push_back({ values[0], values[1], values[2] });
  }
  if (points.empty())
  {
    throw InputError(fileName, "no points (expected one x,y,z per line)");
  }
  return points;
}
} // namespace vp
