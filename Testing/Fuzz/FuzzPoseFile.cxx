// libFuzzer target for tracked pose files (a tracker's export, which we do not control), CSV and
// JSON: any byte string must give rigid poses in increasing time or be refused with
// vp::InputError; never a crash or a hang, never a position or a time beyond vp::limits. The first
// byte picks the form.
#include "vpInputError.h"
#include "vpPoseFile.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string base =
    std::filesystem::temp_directory_path().string() + "/vp_fuzz_poses_" + std::to_string(getpid());
  const std::string file = base + (size > 0 && data[0] == '{' ? ".json" : ".csv");
  std::ofstream(file, std::ios::binary | std::ios::trunc)
    .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    const auto poses = vp::ReadPoseFile(file);
    for (std::size_t i = 0; i < poses.size(); ++i)
    {
      const auto& m = poses[i].ModelToWorld;
      // The reader promised rigid matrices and increasing times.
      const double det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
        m[2] * (m[4] * m[9] - m[5] * m[8]);
      // And every number within the bounds of a patient and a clock (issue 29).
      const bool bounded = std::abs(m[3]) <= 1e6 && std::abs(m[7]) <= 1e6 && std::abs(m[11]) <= 1e6 &&
        std::abs(poses[i].TimeS) <= 1e12;
      if (poses.empty() || !(std::abs(det - 1.0) < 1e-2) || m[15] != 1.0 || !bounded ||
        (i > 0 && !(poses[i].TimeS > poses[i - 1].TimeS)))
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
