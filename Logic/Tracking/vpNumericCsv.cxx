#include "vpNumericCsv.h"

#include "vpDecimal.h"
#include "vpInputError.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

namespace vp
{
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
    const char* end = ScanDecimal(p);
    char* read = nullptr;
    const double v = std::strtod(p, &read);
    if (end == p && read != p && !std::isfinite(v))
    {
      problem = "NaN or infinite value";
      return false;
    }
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

std::vector<NumericRow> ReadNumericCsv(const std::string& fileName, const std::string& what)
{
  struct stat info;
  if (stat(fileName.c_str(), &info) != 0)
  {
    throw InputError(fileName, errno == ENOENT ? "no such file" : std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode))
  {
    // Checked before opening: a FIFO with no writer would block the open, /dev/zero never ends.
    throw InputError(fileName, S_ISDIR(info.st_mode) ? "cannot open as " + what
                                                     : "is not a regular file (a device, pipe or socket), cannot open as " + what);
  }
  std::ifstream in(fileName);
  if (!in)
  {
    throw InputError(fileName, "cannot open as " + what);
  }
  std::vector<NumericRow> rows;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line))
  {
    ++number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#')
    {
      continue;
    }
    NumericRow row;
    row.Line = number;
    std::string problem;
    if (!ParseNumbers(line, row.Values, problem))
    {
      if (rows.empty() && ScanDecimal(line.c_str() + first) == line.c_str() + first)
      {
        continue; // a header: its first field is no number at all
      }
      throw InputError(fileName, "line " + std::to_string(number) + ": " + problem);
    }
    rows.push_back(std::move(row));
  }
  if (rows.empty())
  {
    throw InputError(fileName, "nothing in it: expected " + what);
  }
  return rows;
}
} // namespace vp
