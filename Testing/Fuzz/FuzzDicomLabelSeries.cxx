// libFuzzer target for our reading of DICOM label series: the geometry and pixel checks we wrote
// on top of DCMTK. The input is up to three files, split at "VPSPLIT", written as one series
// folder; the reader must either return a grid that matches its own header or refuse with
// vp::InputError, never crash, hang or read out of bounds.
#include "vpDicomLabelSeriesReader.h"
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
  static const std::string folder = [] {
    const std::string dir = std::filesystem::temp_directory_path().string() + "/vp_fuzz_dicom_" + std::to_string(getpid());
    std::filesystem::create_directories(dir);
    return dir;
  }();
  for (const auto& entry : std::filesystem::directory_iterator(folder))
  {
    std::filesystem::remove(entry.path());
  }
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::size_t begin = 0;
  for (int file = 0; file < 3 && begin <= bytes.size(); ++file)
  {
    std::size_t end = bytes.find("VPSPLIT", begin);
    if (end == std::string::npos)
    {
      end = bytes.size();
    }
    std::ofstream(folder + "/image_" + std::to_string(file), std::ios::binary).write(bytes.data() + begin,
      static_cast<std::streamsize>(end - begin));
    begin = end + 7;
  }
  try
  {
    const vp::LabelGrid grid = vp::DicomLabelSeriesReader::ReadSeries(folder);
    if (!grid.Labels || grid.Labels->GetNumberOfPoints() <= 0 || !(grid.VoxelVolumeMm3() > 0.0))
    {
      __builtin_trap(); // a grid was returned, so it must be a usable one
    }
  }
  catch (const vp::InputError&)
  {
  }
  return 0;
}
