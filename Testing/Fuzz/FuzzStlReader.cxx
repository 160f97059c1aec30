// libFuzzer target for the STL parser (a format we do not control): any byte string must either
// parse or be refused with vp::InputError, never crash, hang or read out of bounds; a parsed soup
// must index into a mesh.
#include "vpIndexedMesh.h"
#include "vpInputError.h"
#include "vpStlFormat.h"

#include <vtkPolyData.h>

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  try
  {
    const vp::StlSoup soup = vp::ParseStl(reinterpret_cast<const char*>(data), size, "fuzz.stl");
    if (soup.Coordinates.size() % 9 != 0 || soup.Coordinates.empty())
    {
      __builtin_trap(); // the parser promised whole, non-empty triangles
    }
    std::size_t dropped = 0;
    auto mesh = vp::BuildIndexedMesh(soup.Coordinates.data(), soup.Coordinates.size() / 9, &dropped);
    if (static_cast<std::size_t>(mesh->GetNumberOfPolys()) + dropped != soup.Coordinates.size() / 9)
    {
      __builtin_trap();
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
