#include "vpObjIndices.h"

#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string_view>

namespace vp
{
namespace
{
bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/// A whole number with an optional sign, at most 18 digits.
bool WholeNumber(std::string_view text, std::int64_t& value)
{
  std::size_t i = 0;
  const bool negative = !text.empty() && (text[0] == '-' || text[0] == '+') ? text[0] == '-' : false;
  if (!text.empty() && (text[0] == '-' || text[0] == '+'))
  {
    i = 1;
  }
  if (i == text.size() || text.size() - i > 18)
  {
    return false;
  }
  value = 0;
  for (; i < text.size(); ++i)
  {
    if (!std::isdigit(static_cast<unsigned char>(text[i])))
    {
      return false;
    }
    value = value * 10 + (text[i] - '0');
  }
  value = negative ? -value : value;
  return true;
}
/// One entry of a face, line or point (where: "line N: face"): v, v/vt, v//vn or v/vt/vn, of the
/// line's form (form: -1 before its first entry), each index nonzero and defined before it.
void CheckEntry(std::string_view entry, int& form, const std::int64_t defined[3], const std::string& where, const std::string& fileName)
{
  static const char* const Kinds[3] = { "vertex", "texture coordinate", "normal" };
  // v, v/vt, v//vn or v/vt/vn, the same in every entry of the line: VTK's reader crashed on
  // a trailing slash (2/) beside other forms.
  const std::size_t slashes = static_cast<std::size_t>(std::count(entry.begin(), entry.end(), '/'));
  const std::size_t firstSlash = entry.find('/');
  const bool hasTexture = slashes >= 1 && firstSlash + 1 < entry.size() && entry[firstSlash + 1] != '/';
  const bool hasNormal = slashes == 2 && entry.back() != '/';
  if (slashes > 2 || (slashes == 1 && !hasTexture) || (slashes == 2 && !hasNormal))
  {
    throw InputError(fileName, where + " entry '" + std::string(entry) +
        "' is not v, v/vt, v//vn or v/vt/vn");
  }
  const int entryForm = (hasTexture ? 1 : 0) | (hasNormal ? 2 : 0);
  if (form >= 0 && entryForm != form)
  {
    throw InputError(fileName, where + " entry '" + std::string(entry) +
        "' is not of the same form as the first");
  }
  form = entryForm;
  std::size_t part = 0, from = 0;
  for (;;)
  {
    const std::size_t slash = entry.find('/', from);
    const std::string_view text = entry.substr(from, slash == std::string_view::npos ? std::string_view::npos : slash - from);
    if (part > 2)
    {
      throw InputError(fileName, where + " entry '" + std::string(entry) +
          "' has more than v/vt/vn");
    }
    if (!text.empty() || part == 0)
    {
      std::int64_t index = 0;
      if (!WholeNumber(text, index) || index == 0)
      {
        throw InputError(fileName, where + " entry '" + std::string(entry) +
            "' is not a nonzero whole-number index");
      }
      if (index > defined[part] || -index > defined[part])
      {
        throw InputError(fileName, where + " names " + Kinds[part] + " " +
            std::to_string(index) + ", but " + std::to_string(defined[part]) + " are defined before it");
      }
    }
    if (slash == std::string_view::npos)
    {
      break;
    }
    from = slash + 1;
    ++part;
  }
}
} // namespace

void CheckObjIndices(const std::string& bytes, const std::string& fileName)
{
  std::int64_t defined[3] = { 0, 0, 0 }; // v, vt, vn so far
  std::size_t lineNumber = 0;
  for (std::size_t start = 0; start < bytes.size();)
  {
    std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos)
    {
      end = bytes.size();
    }
    ++lineNumber;
    std::string_view line(bytes.data() + start, end - start);
    start = end + 1;
    std::size_t i = 0;
    while (i < line.size() && IsSpace(line[i]))
    {
      ++i;
    }
    std::size_t j = i;
    while (j < line.size() && !IsSpace(line[j]))
    {
      ++j;
    }
    const std::string_view keyword = line.substr(i, j - i);
    if (keyword == "v" || keyword == "vt" || keyword == "vn")
    {
      ++defined[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
      continue;
    }
    if (keyword != "f" && keyword != "l" && keyword != "p")
    {
      continue;
    }
    const std::string what = keyword == "f" ? "face" : keyword == "l" ? "line" : "point";
    int form = -1; // the first entry's: which of vt and vn it has (bits 1 and 2)
    for (std::size_t k = j; k < line.size();)
    {
      while (k < line.size() && IsSpace(line[k]))
      {
        ++k;
      }
      std::size_t e = k;
      while (e < line.size() && !IsSpace(line[e]))
      {
        ++e;
      }
      if (e == k)
      {
        break;
      }
      const std::string_view entry = line.substr(k, e - k);
      k = e;
      CheckEntry(entry, form, defined, "line " + std::to_string(lineNumber) + ": " + what, fileName);
    }
  }
}
} // namespace vp
