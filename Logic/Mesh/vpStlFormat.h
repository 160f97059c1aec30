#ifndef vpStlFormat_h
#define vpStlFormat_h

#include "vpInputError.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vp
{
/// Coordinate system named in a mesh file header, as 3D Slicer writes it ("SPACE=LPS" or
/// "SPACE=RAS" in the 80-byte binary STL header, in the ASCII solid name, or in the VTK header).
enum class MeshSpace
{
  Unspecified,
  LPS,
  RAS
};
const char* MeshSpaceName(MeshSpace space);
/// Finds "SPACE=LPS" / "SPACE=RAS" in a header text; Unspecified when absent.
MeshSpace ParseSpaceTag(const std::string& header);

/// A triangle soup as the STL file holds it: 9 floats per triangle, in file order.
struct StlSoup
{
  std::vector<float> Coordinates;
  MeshSpace Space = MeshSpace::Unspecified;
  bool Binary = true;
};

/// Parses binary or ASCII STL held in memory. Throws InputError(sourceName, problem) for an empty
/// or truncated file, a triangle count that runs past the end, malformed ASCII, non-finite
/// coordinates or no triangles at all. Never reads outside [data, data + size).
StlSoup ParseStl(const char* data, std::size_t size, const std::string& sourceName);

/// What the start of an STL file of fileSize bytes can tell, checked before the file is read
/// whole, so that a file that cannot be a mesh is refused at once (a gigabyte of zeros, of text):
/// a binary header declaring no triangles or more than the file holds, an ASCII text whose first
/// lines are not STL (the same messages, with the same line numbers, as ParseStl). data: the
/// file's first bytes (the reader passes up to 1 MiB).
void CheckStlStart(const char* data, std::size_t size, std::uint64_t fileSize, const std::string& sourceName);

/// Encodes triangles (9 floats each) as binary STL with "SPACE=<space>" in the header.
std::string EncodeBinaryStl(const std::vector<float>& coordinates, MeshSpace space);
} // namespace vp

#endif
