#ifndef vpDcmtkFile_h
#define vpDcmtkFile_h

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "vpLabelStructure.h"

#include <string>

namespace vp
{
/// Opens a DICOM file for one of our readers: DCMTK's own log is silenced (a bad file gets our
/// one line, which names it, not DCMTK's several), an unreadable file and pixel data in an
/// encapsulated (compressed) transfer syntax, which we do not decode, are refused with
/// vp::InputError naming where.
void LoadDicomFile(DcmFileFormat& file, const std::string& path, const std::string& where);

/// Whose image a DICOM data set is: PatientID, PatientName, StudyInstanceUID and
/// FrameOfReferenceUID, each empty when absent.
ImageIdentity IdentityOf(DcmItem& data);
} // namespace vp

#endif
