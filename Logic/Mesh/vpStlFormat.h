#ifndef vpStlFormat_h
#define vpStlFormat_h

#include "vpInputError.h"

#include <cstddef>
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

/// Encodes triangles (9 floats each) as binary STL with "SPACE=<space>" in the header.
std::string EncodeBinaryStl(const std::vector<float>& coordinates, MeshSpace space);
} // namespace vp

#endif
