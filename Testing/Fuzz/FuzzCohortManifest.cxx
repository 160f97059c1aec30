// libFuzzer target for cohort manifests (a researcher's CSV, written by hand or by a script we do
// not control): any byte string must give cases whose names are safe folder names, each once,
// each with a segmentation, or be refused with vp::InputError; never a crash or a hang.
#include "vpCohortManifest.h"
#include "vpInputError.h"

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file =
    std::filesystem::temp_directory_path().string() + "/vp_fuzz_manifest_" + std::to_string(getpid()) + ".csv";
  std::ofstream(file, std::ios::binary | std::ios::trunc)
    .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    const auto cases = vp::ReadCohortManifest(file);
    std::set<std::string> names;
    for (const vp::CohortCase& c : cases)
    {
      bool safe = !c.Name.empty() && c.Name.size() <= 64 && c.Name[0] != '.' && c.Name[0] != '-';
      for (const char ch : c.Name)
      {
        const auto u = static_cast<unsigned char>(ch);
        safe = safe && u < 128 && (std::isalnum(u) || ch == '_' || ch == '-' || ch == '.');
      }
      std::string folded = c.Name;
      for (char& ch : folded)
      {
        ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      }
      if (!safe || !names.insert(folded).second || c.Segmentation.empty() || cases.empty())
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
