// libFuzzer target for NRRD and Slicer .seg.nrrd labelmaps: ITK parses the header, we read the
// Segment<N>_* keys, layers and values. Any byte string must import or be refused with
// vp::InputError; never a crash, a hang or an allocation the header merely claims.
#include "vpInputError.h"
#include "vpLabelmapFileReader.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file =
    std::filesystem::temp_directory_path().string() + "/vp_fuzz_" + std::to_string(getpid()) + ".seg.nrrd";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    for (const auto& s : vp::LabelmapFileReader::Read(file, std::size_t(1) << 20))
    {
      if (!s.Grid.Labels || !(s.Grid.VoxelVolumeMm3() >= 0.0))
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
