#include "vpDcmtkFile.h"

#include "vpInputError.h"

#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/oflog/oflog.h>

namespace vp
{
void LoadDicomFile(DcmFileFormat& file, const std::string& path, const std::string& where)
{
  static const bool quiet = [] {
    OFLog::configure(OFLogger::OFF_LOG_LEVEL);
    return true;
  }();
  (void)quiet;
  if (file.loadFile(path.c_str()).bad())
  {
    throw InputError(where, "not a readable DICOM file");
  }
  const DcmXfer xfer(file.getDataset()->getOriginalXfer());
  if (xfer.isEncapsulated())
  {
    throw InputError(where, std::string("compressed pixel data (") + xfer.getXferName() + ", " + xfer.getXferID() +
        ") that this reader cannot decode; export the labelmap uncompressed");
  }
}
} // namespace vp
