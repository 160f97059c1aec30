#include "vpNumericCsv.h"

#include "vpDecimal.h"
#include "vpInputError.h"
#include "vpRegularFile.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

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

NumericCsvReader::NumericCsvReader(const std::string& fileName, const std::string& what)
  : Name(fileName)
  , What(what)
{
  RegularFileSize(fileName, "cannot open as " + what, "is not a regular file (a device, pipe or socket), cannot open as " + what);
  this->In.open(fileName);
  if (!this->In)
  {
    throw InputError(fileName, "cannot open as " + what);
  }
}

bool NumericCsvReader::Next(NumericRow& row)
{
  while (std::getline(this->In, this->Line))
  {
    ++this->LineNumber;
    const std::size_t first = this->Line.find_first_not_of(" \t\r");
    if (first == std::string::npos || this->Line[first] == '#')
    {
      continue;
    }
    row.Line = this->LineNumber;
    std::string problem;
    if (!ParseNumbers(this->Line, row.Values, problem))
    {
      if (this->Rows == 0 && ScanDecimal(this->Line.c_str() + first) == this->Line.c_str() + first)
      {
        continue; // a header: its first field is no number at all
      }
      throw InputError(this->Name, "line " + std::to_string(this->LineNumber) + ": " + problem);
    }
    ++this->Rows;
    return true;
  }
  if (this->Rows == 0)
  {
    throw InputError(this->Name, "nothing in it: expected " + this->What);
  }
  return false;
}

std::vector<NumericRow> ReadNumericCsv(const std::string& fileName, const std::string& what)
{
  NumericCsvReader reader(fileName, what);
  std::vector<NumericRow> rows;
  NumericRow row;
  while (reader.Next(row))
  {
    rows.push_back(row);
  }
  return rows;
}
} // namespace vp
