#ifndef vpDicomLabelSeriesWriter_h
#define vpDicomLabelSeriesWriter_h

#include "vpLabelStructure.h"

#include <string>

namespace vp
{
/// Writes a label grid as a DICOM image series, one file per slice, in the layout of 3D-IRCADb's
/// masks: CT Image Storage, 8 or 16 bits, with ImagePositionPatient, ImageOrientationPatient and
/// PixelSpacing on every slice (Secondary Capture would lose them), one study, series and frame
/// of reference (the grid's Identity's study and frame when set, so that a patient's structures
/// written one series each share them; new ones otherwise). For phantoms and tests; the reader is
/// DicomLabelSeriesReader.
class DicomLabelSeriesWriter
{
public:
  /// Writes folder/<prefix><n> for every slice; fileOrder[k] is the number in the name of slice k
  /// (empty: slice k is file k), so tests can name files against the slice order. The grid's
  /// matrix must have orthogonal columns (no shear). Throws vp::InputError naming the folder.
  static void Write(const LabelGrid& grid, const std::string& folder, const std::string& seriesName,
    const std::vector<int>& fileOrder = {}, const std::string& prefix = "image_");
  /// A new study and frame of reference for one patient's structures, and the patient's name.
  static ImageIdentity NewIdentity(const std::string& patientName);
};
} // namespace vp

#endif
