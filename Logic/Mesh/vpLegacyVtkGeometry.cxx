#include "vpLegacyVtkGeometry.h"

#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>

namespace vp
{
namespace
{
bool Is(std::string_view token, std::string_view keyword)
{
  return token.size() == keyword.size() &&
    std::equal(token.begin(), token.end(), keyword.begin(),
      [](char a, char b) { return std::toupper(static_cast<unsigned char>(a)) == b; });
}

/// Bytes per value of a legacy VTK type name; 0 when unknown.
std::size_t TypeSize(std::string_view type)
{
  if (Is(type, "UNSIGNED_CHAR") || Is(type, "CHAR") || Is(type, "BIT"))
  {
    return 1;
  }
  if (Is(type, "UNSIGNED_SHORT") || Is(type, "SHORT"))
  {
    return 2;
  }
  if (Is(type, "UNSIGNED_INT") || Is(type, "INT") || Is(type, "FLOAT") || Is(type, "VTKIDTYPE"))
  {
    return 4;
  }
  if (Is(type, "UNSIGNED_LONG") || Is(type, "LONG") || Is(type, "DOUBLE") || Is(type, "VTKTYPEINT64") ||
    Is(type, "VTKTYPEUINT64"))
  {
    return 8;
  }
  return 0;
}

/// A decimal number as a C++ stream reads one: sign, digits, point, exponent; no words (nan, inf).
bool IsNumber(std::string_view t)
{
  std::size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-'))
  {
    ++i;
  }
  bool digits = false;
  while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])))
  {
    ++i;
    digits = true;
  }
  if (i < t.size() && t[i] == '.')
  {
    ++i;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])))
    {
      ++i;
      digits = true;
    }
  }
  if (!digits)
  {
    return false;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E'))
  {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-'))
    {
      ++i;
    }
    const std::size_t exponent = i;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])))
    {
      ++i;
    }
    if (i == exponent)
    {
      return false;
    }
  }
  return i == t.size();
}

/// Whether a C++ stream reads the number into a type of typeSize bytes without failing: an
/// integer type's range (for whole numbers), a float's or double's range without over- or
/// underflow (VTK's reader crashed after a failed read).
bool InRange(std::string_view t, std::size_t typeSize)
{
  const std::string text(t);
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (errno == ERANGE || !std::isfinite(v))
  {
    return false;
  }
  const double a = std::abs(v);
  if (typeSize == 4 && a != 0.0 && (a > FLT_MAX || a < FLT_MIN))
  {
    return false; // a float, or an int whose fraction we do not know: the float's limits serve both
  }
  return a == 0.0 || a >= DBL_MIN;
}

class Walker
{
public:
  Walker(const std::string& bytes, const std::string& fileName)
    : Bytes(bytes)
    , FileName(fileName)
  {
  }

  std::size_t Walk()
  {
    this->SkipLine(); // # vtk DataFile Version x.y
    this->SkipLine(); // title
    const std::string_view format = this->Token();
    this->Binary = Is(format, "BINARY");
    if (!this->Binary && !Is(format, "ASCII"))
    {
      this->Fail("expected ASCII or BINARY on line 3, got '" + std::string(format) + "'");
    }
    if (!Is(this->Token(), "DATASET") || !Is(this->Token(), "POLYDATA"))
    {
      this->Fail("expected DATASET POLYDATA");
    }
    for (;;)
    {
      const std::size_t at = this->SkipSpace();
      const std::string_view keyword = this->Token();
      if (keyword.empty())
      {
        return this->Bytes.size();
      }
      if (Is(keyword, "POINT_DATA") || Is(keyword, "CELL_DATA"))
      {
        return at;
      }
      if (Is(keyword, "POINTS"))
      {
        const std::uint64_t n = this->Count("POINTS");
        this->Values(n, 3, "POINTS", this->TypeOf("POINTS"));
        this->HavePoints = true;
      }
      else if (Is(keyword, "VERTICES") || Is(keyword, "LINES") || Is(keyword, "POLYGONS") || Is(keyword, "TRIANGLE_STRIPS"))
      {
        this->Cells(std::string(keyword));
      }
      else if (Is(keyword, "METADATA"))
      {
        // Text blocks ending with an empty line, in either format.
        const std::size_t end = this->Bytes.find("\n\n", this->Pos);
        this->Pos = end == std::string::npos ? this->Bytes.size() : end + 2;
      }
      else if (Is(keyword, "FIELD"))
      {
        this->Fail("field data before the geometry is not read: save the mesh without it");
      }
      else
      {
        this->Fail("unexpected '" + std::string(keyword.substr(0, 40)) + "' where a geometry section should begin");
      }
    }
  }

private:
  [[noreturn]] void Fail(const std::string& problem) const { throw InputError(this->FileName, problem); }

  std::size_t SkipSpace()
  {
    while (this->Pos < this->Bytes.size() && std::isspace(static_cast<unsigned char>(this->Bytes[this->Pos])))
    {
      ++this->Pos;
    }
    return this->Pos;
  }
  void SkipLine()
  {
    const std::size_t end = this->Bytes.find('\n', this->Pos);
    this->Pos = end == std::string::npos ? this->Bytes.size() : end + 1;
  }
  /// The end of a binary section's header line. VTK's reader takes the rest of the line (up to
  /// 255 characters) and then the values; with anything else on that line, or no line break at
  /// all, its stream failed and the reader went on to read a keyword from the stream it had just
  /// closed (a null pointer: found by fuzz_vtk_reader, "POLYGONS 0 0 vtkCompos..." at the end).
  void EndHeaderLine(const std::string& section)
  {
    const std::size_t end = this->Bytes.find('\n', this->Pos);
    const bool blank = end != std::string::npos && end - this->Pos < 200 &&
      std::all_of(this->Bytes.begin() + static_cast<std::ptrdiff_t>(this->Pos),
        this->Bytes.begin() + static_cast<std::ptrdiff_t>(end), [](char c) { return c == ' ' || c == '\t' || c == '\r'; });
    if (!blank)
    {
      this->Fail(section + ": its header line does not end before its binary values");
    }
    this->Pos = end + 1;
  }
  std::string_view Token()
  {
    this->SkipSpace();
    const std::size_t start = this->Pos;
    while (this->Pos < this->Bytes.size() && !std::isspace(static_cast<unsigned char>(this->Bytes[this->Pos])))
    {
      ++this->Pos;
    }
    return std::string_view(this->Bytes).substr(start, this->Pos - start);
  }
  /// A count: digits only, and no more than the file has bytes.
  std::uint64_t Count(const std::string& section)
  {
    const std::string_view t = this->Token();
    std::uint64_t value = 0;
    if (t.empty() || t.size() > 18 || !std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; }))
    {
      this->Fail(section + ": expected a count, got '" + std::string(t.substr(0, 40)) + "'");
    }
    for (char c : t)
    {
      value = value * 10 + static_cast<std::uint64_t>(c - '0');
    }
    if (value > this->Bytes.size())
    {
      this->Fail(section + " declares " + std::string(t) + " values, more than the file's " + std::to_string(this->Bytes.size()) +
        " bytes can hold");
    }
    return value;
  }
  std::size_t TypeOf(const std::string& section)
  {
    const std::string_view t = this->Token();
    const std::size_t size = TypeSize(t);
    if (size == 0)
    {
      this->Fail(section + ": unknown type '" + std::string(t.substr(0, 40)) + "'");
    }
    return size;
  }
  /// Skips count x per values of typeSize bytes (binary) or tokens (ASCII).
  void Values(std::uint64_t count, std::uint64_t per, const std::string& section, std::size_t typeSize)
  {
    const std::uint64_t values = count * per;
    if (values > this->Bytes.size())
    {
      this->Fail(section + " declares " + std::to_string(count) + " x " + std::to_string(per) + " values, more than the file's " +
        std::to_string(this->Bytes.size()) + " bytes can hold");
    }
    if (this->Binary)
    {
      this->EndHeaderLine(section);
      if (values * typeSize > this->Bytes.size() - this->Pos)
      {
        this->Fail(section + " ends past the end of the file");
      }
      this->Pos += static_cast<std::size_t>(values * typeSize);
      return;
    }
    for (std::uint64_t i = 0; i < values; ++i)
    {
      // Each a number, as VTK's stream reads it: a keyword here means the section is short, and
      // VTK's reader then crashed on what followed.
      const std::string_view t = this->Token();
      if (t.empty())
      {
        this->Fail(section + " ends past the end of the file");
      }
      if (!IsNumber(t) || !InRange(t, typeSize))
      {
        this->Fail(section + ": value " + std::to_string(i + 1) + " of " + std::to_string(values) + " is '" +
          std::string(t.substr(0, 40)) + "', not a number its type holds");
      }
    }
  }
  /// The next integer of a section: an ASCII token or a big-endian binary value.
  std::int64_t Integer(const std::string& section, std::size_t typeSize)
  {
    if (this->Binary)
    {
      if (typeSize > this->Bytes.size() - this->Pos)
      {
        this->Fail(section + " ends past the end of the file");
      }
      std::uint64_t v = 0;
      for (std::size_t k = 0; k < typeSize; ++k)
      {
        v = (v << 8) | static_cast<unsigned char>(this->Bytes[this->Pos + k]);
      }
      this->Pos += typeSize;
      // Sign-extend: a negative count or offset must read as one.
      if (typeSize < 8 && (v >> (8 * typeSize - 1)) & 1u)
      {
        v |= ~std::uint64_t(0) << (8 * typeSize);
      }
      return static_cast<std::int64_t>(v);
    }
    const std::string_view t = this->Token();
    if (t.empty())
    {
      this->Fail(section + " ends past the end of the file");
    }
    std::size_t i = t[0] == '-' || t[0] == '+' ? 1 : 0;
    if (i == t.size() || t.size() > 18)
    {
      this->Fail(section + ": expected an integer, got '" + std::string(t.substr(0, 40)) + "'");
    }
    std::int64_t v = 0;
    for (; i < t.size(); ++i)
    {
      if (t[i] < '0' || t[i] > '9')
      {
        this->Fail(section + ": expected an integer, got '" + std::string(t.substr(0, 40)) + "'");
      }
      v = v * 10 + (t[i] - '0');
    }
    // A stream read of an int fails past its range, and VTK's reader crashed after that.
    if (typeSize <= 4 && v > std::numeric_limits<std::int32_t>::max())
    {
      this->Fail(section + ": '" + std::string(t.substr(0, 40)) + "' is past a 32-bit integer's range");
    }
    return t[0] == '-' ? -v : v;
  }
  void Cells(const std::string& section)
  {
    const std::uint64_t n = this->Count(section);
    const std::uint64_t size = this->Count(section);
    const std::size_t mark = this->Pos;
    if (Is(this->Token(), "OFFSETS"))
    {
      // 5.1: n offsets (one more than the cells), then CONNECTIVITY with size ids.
      const std::size_t offsetSize = this->TypeOf(section + " OFFSETS");
      if (this->Binary)
      {
        this->EndHeaderLine(section + " OFFSETS");
      }
      std::int64_t previous = 0;
      for (std::uint64_t i = 0; i < n; ++i)
      {
        const std::int64_t offset = this->Integer(section + " OFFSETS", offsetSize);
        if ((i == 0 && offset != 0) || offset < previous || static_cast<std::uint64_t>(offset) > size)
        {
          this->Fail(section + ": offset " + std::to_string(i + 1) + " (" + std::to_string(offset) +
            ") does not run from 0 up to the connectivity's " + std::to_string(size));
        }
        previous = offset;
      }
      if (n > 0 && static_cast<std::uint64_t>(previous) != size)
      {
        this->Fail(section + ": the last offset (" + std::to_string(previous) + ") is not the connectivity's size (" +
          std::to_string(size) + ")");
      }
      if (!Is(this->Token(), "CONNECTIVITY"))
      {
        this->Fail(section + ": expected CONNECTIVITY after the offsets");
      }
      const std::size_t idSize = this->TypeOf(section + " CONNECTIVITY");
      if (this->Binary)
      {
        this->Values(size, 1, section + " CONNECTIVITY", idSize);
        return;
      }
      for (std::uint64_t i = 0; i < size; ++i)
      {
        this->Integer(section + " CONNECTIVITY", idSize); // whole numbers: a fraction would split in VTK's stream
      }
      return;
    }
    this->Pos = mark;
    if (this->Binary)
    {
      this->EndHeaderLine(section);
    }
    // Classic: per cell its point count, then the points; the counts fill the section exactly.
    std::uint64_t used = 0;
    for (std::uint64_t c = 0; c < n; ++c)
    {
      if (used >= size)
      {
        this->Fail(section + ": declares " + std::to_string(n) + " cells but its " + std::to_string(size) +
          " values end at cell " + std::to_string(c + 1));
      }
      const std::int64_t points = this->Integer(section, 4);
      ++used;
      if (points < 0 || static_cast<std::uint64_t>(points) > size - used)
      {
        this->Fail(section + ": cell " + std::to_string(c + 1) + " declares " + std::to_string(points) +
          " points, past the section's " + std::to_string(size) + " values");
      }
      for (std::int64_t k = 0; k < points; ++k)
      {
        this->Integer(section, 4);
      }
      used += static_cast<std::uint64_t>(points);
    }
    if (used != size)
    {
      this->Fail(section + ": its cells hold " + std::to_string(used) + " values, not the " + std::to_string(size) + " declared");
    }
  }

  const std::string& Bytes;
  const std::string& FileName;
  std::size_t Pos = 0;
  bool Binary = false;
  bool HavePoints = false;
};
} // namespace

std::size_t CheckLegacyVtkGeometry(const std::string& bytes, const std::string& fileName)
{
  return Walker(bytes, fileName).Walk();
}
} // namespace vp
