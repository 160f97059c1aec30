#include "vpRegistrationFile.h"

#include "vpInputError.h"
#include "vpItkTransformFile.h"
#include "vpJsonFile.h"
#include "vpPhysicalLimits.h"
#include "vpText.h"

#include <cmath>

namespace vp
{
Matrix4 ReadModelToWorld(const std::string& fileName, const std::string& what)
{
  const nlohmann::json root = ReadJsonFile(fileName, what);
  if (root.is_object() && root.contains("method") && root.at("method") == "pivot")
  {
    throw InputError(fileName, "is a pivot calibration (the tip in the tool's coordinates), not " + what +
        ": give it as the scalpel's tip definition (the JSON beside its model)");
  }
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
  const double translation[3] = { m[3], m[7], m[11] };
  CheckCoordinates(translation, fileName, "model_to_world's translation");
  return m;
}

TrackerRegistration ReadTrackerRegistration(const std::string& fileName)
{
  TrackerRegistration registration;
  registration.FileName = fileName;
  Matrix4 patientToTracker{};
  std::string notRigid; // the refusal's words, each file's own
  if (IsItkTransformFileName(fileName))
  {
    // Slicer's tracker-to-RAS is F * inverse(fromParent) * F (F: x and y negated, ITK's LPS to
    // RAS); from the tracker's numbers as RAS to the patient's LPS that is F * it * F, so the
    // Fs cancel and only the inversion of ITK's resampling sense remains.
    patientToTracker = ReadItkLinearTransform(fileName);
    notRigid = "the transform is not rigid";
    registration.TrackerSpace = PoseSpace::RAS;
    registration.Kind = "a 3D Slicer transform";
  }
  else if (EndsWith(LowerCase(fileName), ".json"))
  {
    patientToTracker = ReadModelToWorld(fileName, "a registration (register's RESULT.json)");
    notRigid = "model_to_world is not a rigid transform";
    registration.TrackerSpace = PoseSpace::LPS;
    registration.Kind = "register's result";
  }
  else
  {
    throw InputError(fileName, "not a registration: expected register's RESULT.json or a 3D Slicer transform (.h5, .tfm, .txt)");
  }
  const std::string problem = RigidTransformProblem(patientToTracker);
  if (!problem.empty())
  {
    throw InputError(fileName, notRigid + ": " + problem);
  }
  registration.TrackerToPatient = InvertTransform(patientToTracker);
  return registration;
}
} // namespace vp
