#include "vpRegistrationFile.h"

#include "vpInputError.h"
#include "vpJsonFile.h"

#include <cmath>

namespace vp
{
Matrix4 ReadModelToWorld(const std::string& fileName, const std::string& what)
{
  const nlohmann::json root = ReadJsonFile(fileName, what);
  if (!root.is_object() || !root.contains("model_to_world") || !root.at("model_to_world").is_array() ||
    root.at("model_to_world").size() != 16)
  {
    throw InputError(fileName, "expected \"model_to_world\": an array of 16 numbers (row-major 4x4)");
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
  return m;
}

Matrix4 ReadTrackerToPatient(const std::string& fileName)
{
  const Matrix4 m = ReadModelToWorld(fileName, "a registration (register's RESULT.json)");
  const std::string problem = RigidTransformProblem(m);
  if (!problem.empty())
  {
    throw InputError(fileName, "model_to_world is not a rigid transform: " + problem);
  }
  return InvertTransform(m);
}
} // namespace vp
