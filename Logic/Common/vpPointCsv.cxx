#include "vpPointCsv.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"
#include "vpPhysicalLimits.h"

namespace vp
{
std::array<double, 3> ParsePoint(const std::string& text, const std::string& source)
{
  std::vector<double> values;
  std::string problem;
  if (!ParseNumbers(text, values, problem))
  {
    throw InputError(source, "expected X,Y,Z: " + problem);
  }
  if (values.size() != 3)
  {
    throw InputError(source, "expected X,Y,Z (3 numbers), got " + std::to_string(values.size()));
  }
  CheckCoordinates(values.data(), source, "the point");
  return { values[0], values[1], values[2] };
}

std::vector<std::array<double, 3>> ReadPointCsv(const std::string& fileName)
{
  std::vector<std::array<double, 3>> points;
  NumericCsvReader reader(fileName, "a point list (one x,y,z per line)"); // a row at a time: only the points are kept
  for (NumericRow row; reader.Next(row);)
  {
    if (row.Values.size() != 3)
    {
      throw InputError(fileName, "line " + std::to_string(row.Line) + ": expected x,y,z (3 numbers), got " +
          std::to_string(row.Values.size()));
    }
    CheckCoordinates(row.Values.data(), fileName, "line " + std::to_string(row.Line));
    points.push_back({ row.Values[0], row.Values[1], row.Values[2] });
  }
  return points;
}
} // namespace vp
