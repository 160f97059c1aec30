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

bool NumericCsvReader::ReadLine()
{
  // A line of numbers is short: one far longer is refused when it passes the limit, before it
  // takes the machine's memory (std::getline would hold a line of any length).
  this->Line.clear();
  std::streambuf* in = this->In.rdbuf();
  int c = in->sbumpc();
  if (c == std::char_traits<char>::eof())
  {
    return false;
  }
  for (; c != std::char_traits<char>::eof() && c != '\n'; c = in->sbumpc())
  {
    if (this->Line.size() >= MaxLineCharacters)
    {
      throw InputError(this->Name, "line " + std::to_string(this->LineNumber + 1) + ": longer than " +
          std::to_string(MaxLineCharacters) + " characters, not " + this->What);
    }
    this->Line.push_back(static_cast<char>(c));
  }
  if (this->LineNumber == 0 && this->Line.compare(0, 3, "\xEF\xBB\xBF") == 0)
  {
    this->Line.erase(0, 3); // a UTF-8 byte order mark (spreadsheets write one) is not data
  }
  return true;
}

bool NumericCsvReader::Next(NumericRow& row)
{
  while (this->ReadLine())
  {
    ++this->LineNumber;
    const std::size_t first = this->Line.find_first_not_of(" \t\r");
    if (first == std::string::npos)
    {
      continue;
    }
    if (this->Line[first] == '#')
    {
      if (this->Rows == 0)
      {
        this->Comments.push_back(TrimBlanks(this->Line.substr(first + 1)));
      }
      continue;
    }
    row.Line = this->LineNumber;
    std::string problem;
    if (!ParseNumbers(this->Line, row.Values, problem))
    {
      if (this->Rows == 0 && ScanDecimal(this->Line.c_str() + first) == this->Line.c_str() + first)
      {
        // A header: its first field is no number at all.
        this->HeaderFields.clear();
        std::size_t start = 0;
        for (std::size_t comma = this->Line.find(','); ; comma = this->Line.find(',', start))
        {
          this->HeaderFields.push_back(TrimBlanks(this->Line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
          if (comma == std::string::npos)
          {
            break;
          }
          start = comma + 1;
        }
        continue;
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

bool ParseSeparatedNumbers(const std::string& text, std::vector<double>& values, std::string& problem)
{
  std::string joined;
  bool separator = true;
  for (const char c : text)
  {
    const bool blank = c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ',';
    if (!blank && separator && !joined.empty())
    {
      joined += ',';
    }
    if (!blank)
    {
      joined += c;
    }
    separator = blank;
  }
  return ParseNumbers(joined, values, problem);
}

std::string TrimBlanks(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos)
  {
    return std::string();
  }
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
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
