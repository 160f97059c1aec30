#include "vpDcmtkFile.h"

#include <dcmtk/dcmdata/dcdeftag.h>

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

ImageIdentity IdentityOf(DcmItem& data)
{
  ImageIdentity identity;
  auto get = [&](const DcmTagKey& tag) {
    OFString text;
    return data.findAndGetOFString(tag, text).good() ? std::string(text.c_str()) : std::string();
  };
  identity.PatientId = get(DCM_PatientID);
  identity.PatientName = get(DCM_PatientName);
  identity.StudyUid = get(DCM_StudyInstanceUID);
  identity.FrameOfReferenceUid = get(DCM_FrameOfReferenceUID);
  return identity;
}
} // namespace vp
