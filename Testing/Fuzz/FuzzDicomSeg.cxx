// libFuzzer target for DICOM SEG import: DCMTK's dcmseg and dcmfg parse the file; we place the
// frames, unpack the bits and build the grids. Any byte string must import or be refused with
// vp::InputError; never a crash, a hang or an allocation the header merely claims.
#include "vpDicomSegReader.h"
#include "vpInputError.h"

#include <vtkImageData.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::string file =
    std::filesystem::temp_directory_path().string() + "/vp_fuzz_seg_" + std::to_string(getpid()) + ".dcm";
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    for (const auto& s : vp::DicomSegReader::Read(file, nullptr, std::size_t(1) << 20))
    {
      if (!s.Grid.Labels || s.Grid.Labels->GetNumberOfPoints() <= 0 || !(s.Grid.VoxelVolumeMm3() > 0.0))
      {
        __builtin_trap(); // a structure was returned, so its grid must be usable
      }
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
