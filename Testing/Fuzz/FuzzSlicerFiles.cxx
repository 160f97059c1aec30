// libFuzzer target for the small files 3D Slicer hands a CLI, which we do not control: a colour
// table (.ctbl) and a point list (.fcsv or markups JSON). The first byte picks the parser ('C':
// colour table, 'F': fcsv, anything else: markups JSON), the rest is the file. Any byte
// string must give what the parser promises or be refused with vp::InputError: label values from
// 1 to 1,000,000 with names, or points within vp::limits; never a crash, a hang or another error.
#include "vpColorTableFile.h"
#include "vpInputError.h"
#include "vpMarkupsFile.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1)
  {
    return 0;
  }
  const char kind = static_cast<char>(data[0]);
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try
  {
    if (kind == 'C')
    {
      for (const auto& [value, name] : vp::ParseColorTableNames(text, "fuzz.ctbl"))
      {
        if (value < 1 || value > 1000000 || name.empty())
        {
          __builtin_trap();
        }
      }
    }
    else
    {
      const auto points = vp::ParseMarkupsPoints(text, kind == 'F', "fuzz");
      for (const vp::MarkupsPoint& p : points)
      {
        for (double c : p.PositionLps)
        {
          if (!(std::abs(c) <= 1e6))
          {
            __builtin_trap();
          }
        }
      }
      if (points.empty())
      {
        __builtin_trap();
      }
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
