#include "vpStlFormat.h"

#include "vpPhysicalLimits.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace vp
{
namespace
{
constexpr std::size_t HeaderBytes = 80;
constexpr std::size_t FacetBytes = 50; // normal, 3 vertices (12 floats), 2-byte attribute

std::uint32_t ReadUint32LE(const char* p)
{
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(b[0]) | (std::uint32_t(b[1]) << 8) | (std::uint32_t(b[2]) << 16) |
    (std::uint32_t(b[3]) << 24);
}

float ReadFloatLE(const char* p)
{
  const std::uint32_t bits = ReadUint32LE(p);
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

void AppendUint32LE(std::string& out, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
  {
    out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
  }
}

void AppendFloatLE(std::string& out, float f)
{
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  AppendUint32LE(out, bits);
}

bool StartsWithSolid(const char* data, std::size_t size)
{
  std::size_t i = 0;
  while (i < size && (data[i] == ' ' || data[i] == '\t' || data[i] == '\r' || data[i] == '\n'))
  {
    ++i;
  }
  return size - i >= 5 && std::strncmp(data + i, "solid", 5) == 0;
}

void CheckFinite(const std::vector<float>& coords, const std::string& sourceName)
{
  for (std::size_t i = 0; i < coords.size(); ++i)
  {
    if (!std::isfinite(coords[i]))
    {
      throw InputError(sourceName,
        "triangle " + std::to_string(i / 9 + 1) + " has a NaN or infinite coordinate");
    }
  }
}

/// The three numbers after "vertex" (p just past the keyword) appended to coordinates; returns
/// where they end. Throws InputError naming the line when they are not three numbers.
const char* ReadVertex(const char* p, std::size_t line, const std::string& sourceName, std::vector<float>& coordinates)
{
  for (int k = 0; k < 3; ++k)
  {
    char* numberEnd = nullptr;
    errno = 0;
    const double value = std::strtod(p, &numberEnd);
    if (numberEnd == p || (*numberEnd != ' ' && *numberEnd != '\t' && *numberEnd != '\r' &&
                            *numberEnd != '\n' && *numberEnd != '\0'))
    {
      throw InputError(sourceName,
        "line " + std::to_string(line) + ": expected three numbers after 'vertex'");
    }
    coordinates.push_back(static_cast<float>(value));
    p = numberEnd;
  }
  return p;
}

/// A whole ASCII STL: a "solid", whole facets, and an "endsolid" after any.
void CheckAsciiStlEnds(const StlSoup& soup, bool sawSolid, bool sawEndSolid, const std::string& sourceName)
{
  if (!sawSolid)
  {
    throw InputError(sourceName, "not an STL file (no 'solid' keyword)");
  }
  if (soup.Coordinates.size() % 9 != 0)
  {
    throw InputError(sourceName, "ASCII STL ends inside a facet (vertex count " +
        std::to_string(soup.Coordinates.size() / 3) + " is not a multiple of 3)");
  }
  if (!sawEndSolid && !soup.Coordinates.empty())
  {
    throw InputError(sourceName, "ASCII STL is truncated (no 'endsolid')");
  }
}

/// ASCII STL: only the "vertex x y z" lines carry geometry; facet normals are recomputed from
/// the winding, as every reader of STL that wants consistent normals does.
// wholeFile false: data is the start of a longer file, cut at a line's end; only what it holds
// is checked (no end, no facet left open, no "solid" needed yet).
StlSoup ParseAsciiStl(const char* data, std::size_t size, const std::string& sourceName, bool wholeFile = true)
{
  StlSoup soup;
  soup.Binary = false;
  // A private, NUL-terminated copy so that strtod can never run past the end of the buffer.
  const std::string text(data, size);
  const char* p = text.c_str();
  const char* end = p + text.size();
  std::size_t line = 1;
  bool sawSolid = false;
  bool sawEndSolid = false;
  while (p < end)
  {
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r'))
    {
      ++p;
    }
    if (p < end && *p == '\n')
    {
      ++line;
      ++p;
      continue;
    }
    const char* wordBegin = p;
    while (p < end && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n')
    {
      ++p;
    }
    const std::string word(wordBegin, p);
    if (word.empty())
    {
      continue;
    }
    if (word == "solid" && !sawSolid)
    {
      sawSolid = true;
      const char* lineEnd = p;
      while (lineEnd < end && *lineEnd != '\n')
      {
        ++lineEnd;
      }
      soup.Space = ParseSpaceTag(std::string(p, lineEnd));
      p = lineEnd;
      continue;
    }
    if (word == "vertex")
    {
      p = ReadVertex(p, line, sourceName, soup.Coordinates);
      continue;
    }
    if (word == "endsolid")
    {
      sawEndSolid = true;
      break;
    }
    if (word == "facet" || word == "normal" || word == "outer" || word == "loop" ||
      word == "endloop" || word == "endfacet")
    {
      continue;
    }
    // Numbers after "normal" are skipped here: they follow a keyword we accept.
    char* numberEnd = nullptr;
    std::strtod(wordBegin, &numberEnd);
    if (numberEnd == p)
    {
      continue;
    }
    throw InputError(sourceName,
      "line " + std::to_string(line) + ": unexpected '" + word.substr(0, 32) + "' in ASCII STL");
  }
  if (wholeFile)
  {
    CheckAsciiStlEnds(soup, sawSolid, sawEndSolid, sourceName);
  }
  return soup;
}
} // namespace

const char* MeshSpaceName(MeshSpace space)
{
  switch (space)
  {
    case MeshSpace::LPS:
      return "LPS";
    case MeshSpace::RAS:
      return "RAS";
    default:
      return "unspecified";
  }
}

MeshSpace ParseSpaceTag(const std::string& header)
{
  const std::size_t at = header.find("SPACE=");
  if (at == std::string::npos || at + 9 > header.size())
  {
    return MeshSpace::Unspecified;
  }
  const std::string value = header.substr(at + 6, 3);
  if (value == "LPS")
  {
    return MeshSpace::LPS;
  }
  if (value == "RAS")
  {
    return MeshSpace::RAS;
  }
  return MeshSpace::Unspecified;
}

namespace
{
// Whether an STL file of fileSize bytes starting with data (size bytes of it) is ASCII: it begins
// with "solid" and no NUL, and its size is not exactly what a binary header declares (many binary
// headers also begin with "solid": the size check decides first).
bool IsAsciiStl(const char* data, std::size_t size, std::uint64_t fileSize)
{
  const bool exactBinarySize = size >= HeaderBytes + 4 &&
    HeaderBytes + 4 + std::uint64_t(ReadUint32LE(data + HeaderBytes)) * FacetBytes == fileSize;
  return !exactBinarySize && StartsWithSolid(data, size) &&
    std::memchr(data, '\0', std::min<std::size_t>(size, HeaderBytes + 4)) == nullptr;
}

// A binary STL's triangle count, checked against the file's size.
std::uint64_t BinaryStlCount(const char* data, std::size_t size, std::uint64_t fileSize, const std::string& sourceName)
{
  if (size < HeaderBytes + 4)
  {
    throw InputError(sourceName,
      "too short for a binary STL (" + std::to_string(size) + " bytes, the header alone is 84)");
  }
  const std::uint64_t count = ReadUint32LE(data + HeaderBytes);
  const std::uint64_t available = (fileSize - HeaderBytes - 4) / FacetBytes;
  if (count > available)
  {
    throw InputError(sourceName,
      "binary STL declares " + std::to_string(count) + " triangles but the file holds only " +
        std::to_string(available));
  }
  if (count == 0)
  {
    throw InputError(sourceName, "STL file has no triangles");
  }
  if (static_cast<double>(count) > limits::MaxModelTriangles)
  {
    // Known from the header, before the file is read.
    throw InputError(sourceName, "binary STL of " + std::to_string(count) + " triangles: a model holds at most " +
        NumberText(limits::MaxModelTriangles) + " (decimate it first)");
  }
  return count;
}
} // namespace

void CheckStlStart(const char* data, std::size_t size, std::uint64_t fileSize, const std::string& sourceName)
{
  if (fileSize == 0)
  {
    throw InputError(sourceName, "file is empty");
  }
  if (!IsAsciiStl(data, size, fileSize))
  {
    BinaryStlCount(data, size, fileSize, sourceName);
    return;
  }
  const char* lastLine = static_cast<const char*>(memrchr(data, '\n', size));
  if (lastLine)
  {
    ParseAsciiStl(data, static_cast<std::size_t>(lastLine - data) + 1, sourceName, false);
  }
}

StlSoup ParseStl(const char* data, std::size_t size, const std::string& sourceName)
{
  if (size == 0)
  {
    throw InputError(sourceName, "file is empty");
  }
  if (IsAsciiStl(data, size, size))
  {
    StlSoup soup = ParseAsciiStl(data, size, sourceName);
    CheckFinite(soup.Coordinates, sourceName);
    if (soup.Coordinates.empty())
    {
      throw InputError(sourceName, "STL file has no triangles");
    }
    return soup;
  }
  const std::uint64_t count = BinaryStlCount(data, size, size, sourceName);
  StlSoup soup;
  soup.Binary = true;
  soup.Space = ParseSpaceTag(std::string(data, HeaderBytes));
  soup.Coordinates.resize(count * 9);
  const char* facet = data + HeaderBytes + 4;
  for (std::uint64_t t = 0; t < count; ++t, facet += FacetBytes)
  {
    for (int k = 0; k < 9; ++k)
    {
      soup.Coordinates[t * 9 + k] = ReadFloatLE(facet + 12 + 4 * k);
    }
  }
  CheckFinite(soup.Coordinates, sourceName);
  return soup;
}

std::string EncodeBinaryStl(const std::vector<float>& coordinates, MeshSpace space)
{
  const std::size_t count = coordinates.size() / 9;
  std::string out;
  out.reserve(HeaderBytes + 4 + count * FacetBytes);
  std::string header = std::string("SPACE=") + MeshSpaceName(space);
  header.resize(HeaderBytes, ' ');
  out += header;
  AppendUint32LE(out, static_cast<std::uint32_t>(count));
  for (std::size_t t = 0; t < count; ++t)
  {
    const float* v = coordinates.data() + 9 * t;
    // Facet normal from the winding, in double to keep thin triangles' normals stable.
    const double e1[3] = { double(v[3]) - v[0], double(v[4]) - v[1], double(v[5]) - v[2] };
    const double e2[3] = { double(v[6]) - v[0], double(v[7]) - v[1], double(v[8]) - v[2] };
    double n[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& c : n)
    {
      c = length > 0 ? c / length : 0.0;
    }
    for (double c : n)
    {
      AppendFloatLE(out, static_cast<float>(c));
    }
    for (int k = 0; k < 9; ++k)
    {
      AppendFloatLE(out, v[k]);
    }
    out.push_back('\0');
    out.push_back('\0');
  }
  return out;
}
} // namespace vp
