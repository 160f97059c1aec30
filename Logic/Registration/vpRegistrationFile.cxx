#include "vpRegistrationFile.h"

#include "vpInputError.h"
#include "vpJsonFile.h"

#include <cmath>

namespace vp
{
Matrix4 ReadTrackerToPatient(const std::string& fileName)
{
  const nlohmann::json root = ReadJsonFile(fileName, "a registration (register's RESULT.json)");
  if (!root.is_object() || !root.contains("model_to_world") || !root.at("model_to_world").is_array() ||
    root.at("model_to_world").size() != 16)
  {
    throw InputError(fileName, "expected \"model_to_world\": an array of 16 numbers (row-major 4x4), as register writes it");
  }
  Matrix4 m{};
  for (int i = 0; i < 16; ++i)
  {
    const auto& v = root.at("model_to_world")[i];
    if (!v.is_number() || !std::isfinite(v.get<double>()))
    {
      throw InputError(fileName, "model_to_world: element " + std::to_string(i) + " is not a finite number");
    }
    m[i] = v.get<double>();
  }
  double worst = std::abs(m[12]) + std::abs(m[13]) + std::abs(m[14]) + std::abs(m[15] - 1.0);
  for (int a = 0; a < 3; ++a)
  {
    for (int b = 0; b < 3; ++b)
    {
      const double dot = m[a] * m[b] + m[4 + a] * m[4 + b] + m[8 + a] * m[8 + b];
      worst = std::max(worst, std::abs(dot - (a == b ? 1.0 : 0.0)));
    }
  }
  if (worst > 1e-3)
  {
    throw InputError(fileName, "model_to_world is not a rigid transform (a rotation and a translation)");
  }
  return InvertTransform(m);
}
} // namespace vp
