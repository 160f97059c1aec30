#include "vpSegmentationImport.h"

#include "vpDicomSegReader.h"
#include "vpInputError.h"
#include "vpLabelmapFileReader.h"

#include <filesystem>

namespace fs = std::filesystem;

namespace vp
{
void PrepareConcurrentImports()
{
  DicomSegReader::PrepareForThreads();
}

LabelStructures ImportSegmentation(const std::string& input, const StructureFilter& wanted)
{
  std::error_code ec;
  if (!fs::exists(input, ec))
  {
    throw InputError(input, "no such file or folder");
  }
  if (fs::is_directory(input, ec))
  {
    return DicomLabelSeriesReader::ReadFolder(input, wanted);
  }
  if (!fs::is_regular_file(input, ec))
  {
    // Before anything opens it: a FIFO with no writer would block the open, /dev/zero never ends.
    throw InputError(input, "is not a regular file (a device, pipe or socket) nor a DICOM series folder");
  }
  if (LabelmapFileReader::Handles(input))
  {
    return LabelmapFileReader::Read(input);
  }
  if (DicomLabelSeriesReader::IsDicomFile(input))
  {
    return DicomSegReader::Read(input, wanted);
  }
  throw InputError(input,
    "not a labelmap this program reads (a DICOM series folder, DICOM SEG, .nrrd, .seg.nrrd, .nii or .nii.gz)");
}
} // namespace vp
