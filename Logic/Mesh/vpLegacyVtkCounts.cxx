#include "vpLegacyVtkCounts.h"

#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

namespace
{
std::vector<std::string_view> Tokens(std::string_view line, std::size_t most)
{
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (out.size() < most)
  {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i])))
    {
      ++i;
    }
    if (i == line.size())
    {
      break;
    }
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i])))
    {
      ++i;
    }
    out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool Is(std::string_view token, std::string_view keyword)
{
  return token.size() == keyword.size() &&
    std::equal(token.begin(), token.end(), keyword.begin(),
      [](char a, char b) { return std::toupper(static_cast<unsigned char>(a)) == b; });
}

/// A count token: digits only (VTK reads a sign or a fraction as something else and fails).
bool Count(std::string_view token, std::uint64_t& value)
{
  if (token.empty() || token.size() > 19)
  {
    return false;
  }
  value = 0;
  for (char c : token)
  {
    if (c < '0' || c > '9')
    {
      return false;
    }
    value = value * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return true;
}

bool IsTypeName(std::string_view token)
{
  for (std::string_view type : { "BIT", "UNSIGNED_CHAR", "CHAR", "UNSIGNED_SHORT", "SHORT", "UNSIGNED_INT", "INT",
         "UNSIGNED_LONG", "LONG", "FLOAT", "DOUBLE", "VTKIDTYPE", "VTKTYPEINT64", "VTKTYPEUINT64", "STRING" })
  {
    if (Is(token, type))
    {
      return true;
    }
  }
  return false;
}

/// a x b, saturating.
std::uint64_t Times(std::uint64_t a, std::uint64_t b)
{
  return b != 0 && a > std::numeric_limits<std::uint64_t>::max() / b ? std::numeric_limits<std::uint64_t>::max() : a * b;
}
} // namespace

namespace vp
{
void CheckLegacyVtkCounts(const std::string& bytes, const std::string& fileName)
{
  const std::uint64_t size = bytes.size();
  std::uint64_t attributes = 0; // the count of the last POINT_DATA or CELL_DATA
  std::size_t lineNumber = 0;
  for (std::size_t start = 0; start < bytes.size();)
  {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos)
    {
      end = bytes.size();
    }
    ++lineNumber;
    // Keyword lines are short; a long line is data (only its first tokens are looked at).
    const std::string_view line(bytes.data() + start, std::min<std::size_t>(end - start, 256));
    start = end + 1;
    const std::vector<std::string_view> t = Tokens(line, 5);
    if (t.empty() || !std::isalpha(static_cast<unsigned char>(t[0][0])))
    {
      continue;
    }
    std::uint64_t a = 0, b = 0, values = 0;
    std::string what;
    if (Is(t[0], "POINTS") && t.size() >= 2 && Count(t[1], a))
    {
      values = Times(a, 3);
      what = "POINTS declares " + std::string(t[1]) + " points";
    }
    else if ((Is(t[0], "VERTICES") || Is(t[0], "LINES") || Is(t[0], "POLYGONS") || Is(t[0], "TRIANGLE_STRIPS")) &&
      t.size() >= 3 && Count(t[1], a) && Count(t[2], b))
    {
      values = a + b;
      what = std::string(t[0]) + " declares " + std::string(t[1]) + " cells of " + std::string(t[2]) + " values";
    }
    else if ((Is(t[0], "POINT_DATA") || Is(t[0], "CELL_DATA")) && t.size() >= 2 && Count(t[1], a))
    {
      attributes = a;
      values = a;
      what = std::string(t[0]) + " declares " + std::string(t[1]) + " values";
    }
    else if (Is(t[0], "SCALARS") && t.size() >= 3)
    {
      std::uint64_t components = 1;
      if (t.size() >= 4)
      {
        Count(t[3], components);
      }
      values = Times(attributes, components);
      what = "SCALARS declares " + std::to_string(components) + " components of " + std::to_string(attributes) + " values";
    }
    else if (Is(t[0], "COLOR_SCALARS") && t.size() >= 3 && Count(t[2], a))
    {
      values = Times(attributes, a);
      what = "COLOR_SCALARS declares " + std::string(t[2]) + " components of " + std::to_string(attributes) + " values";
    }
    else if (Is(t[0], "VECTORS") || Is(t[0], "NORMALS") || Is(t[0], "TENSORS") || Is(t[0], "TENSORS6"))
    {
      values = Times(attributes, Is(t[0], "TENSORS") ? 9 : Is(t[0], "TENSORS6") ? 6 : 3);
      what = std::string(t[0]) + " for " + std::to_string(attributes) + " values";
    }
    else if (Is(t[0], "TEXTURE_COORDINATES") && t.size() >= 3 && Count(t[2], a))
    {
      values = Times(attributes, a);
      what = "TEXTURE_COORDINATES declares " + std::string(t[2]) + " components of " + std::to_string(attributes) + " values";
    }
    else if (Is(t[0], "LOOKUP_TABLE") && t.size() >= 3 && Count(t[2], a))
    {
      values = Times(a, 4);
      what = "LOOKUP_TABLE declares " + std::string(t[2]) + " colours";
    }
    else if (t.size() == 4 && Count(t[1], a) && Count(t[2], b) && IsTypeName(t[3]))
    {
      values = Times(a, b); // a field array: name, components, tuples, type
      what = "field array " + std::string(t[0]) + " declares " + std::string(t[1]) + " x " + std::string(t[2]) + " values";
    }
    else
    {
      continue;
    }
    if (values > size)
    {
      throw InputError(fileName, "line " + std::to_string(lineNumber) + ": " + what + ", more than its " +
          std::to_string(size) + " bytes can hold");
    }
  }
}
} // namespace vp
