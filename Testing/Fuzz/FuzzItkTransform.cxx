// libFuzzer target for the registrations users bring from 3D Slicer as ITK's text transform files
// (.tfm/.txt: a format we do not control, parsed by ITK), through vp::ReadTrackerRegistration as
// a user reaches it: any byte string must give a finite tracker-to-patient transform, the inverse
// of the file's rigid one, or be refused with vp::InputError; never a crash, a hang or another
// exception escaping. (It found ITK 5.2 reading past a TranslationTransform's parameters, and
// letting std::out_of_range through on a truncated type name.)
#include "vpInputError.h"
#include "vpItkTransformFile.h"
#include "vpRegistrationFile.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file =
    std::filesystem::temp_directory_path().string() + "/vp_fuzz_" + std::to_string(getpid()) + ".tfm";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    const vp::TrackerRegistration registration = vp::ReadTrackerRegistration(file);
    for (const double v : registration.TrackerToPatient)
    {
      if (!std::isfinite(v))
      {
        __builtin_trap();
      }
    }
    // Taken as it was given: rigid as the file holds it, inverted to within rounding.
    const vp::Matrix4 fromParent = vp::ReadItkLinearTransform(file);
    if (!vp::RigidTransformProblem(fromParent).empty())
    {
      __builtin_trap();
    }
    const vp::Matrix4 identity = vp::MultiplyTransforms(registration.TrackerToPatient, fromParent);
    for (int i = 0; i < 16; ++i)
    {
      if (!(std::abs(identity[i] - (i % 5 == 0 ? 1.0 : 0.0)) <= 1e-6 * (i % 4 == 3 ? 1e6 : 1.0)))
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
