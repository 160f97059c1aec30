#ifndef vpDicomLabelSeriesReader_h
#define vpDicomLabelSeriesReader_h

#include "vpLabelStructure.h"

#include <string>
#include <vector>

namespace vp
{
/// Reads labelmaps stored as DICOM image series (through DCMTK), in the two layouts hospitals and
/// data sets use:
///  - a root folder with one sub-folder per structure, each a series whose non-zero voxels are
///    the structure (3D-IRCADb's MASKS_DICOM: files without extension, foreground 255 or 1); the
///    structure is named after its folder;
///  - one folder holding one series of several label values: one structure per value, named
///    "label N" (or after the folder when there is a single value).
/// Geometry comes from the headers, never from file names: slices are ordered by their position
/// along the slice normal, and the index-to-LPS matrix is built from ImageOrientationPatient,
/// ImagePositionPatient and PixelSpacing. Stored pixel values are the labels (a rescale, when
/// present, is ignored: labels are not Hounsfield units).
///
/// Everything that would give a wrong model is refused with one line naming the folder: no DICOM
/// files, more than one series in a folder, compressed pixel data DCMTK cannot decode (JPEG 2000),
/// multi-frame or colour images, slices of different size, spacing or orientation, slices not
/// stacked along their normal, two slices at one position, a missing slice, uneven spacing, and
/// a series that is an image rather than labels (negative values or more than 256 distinct ones:
/// a CT or MR). Throws vp::InputError.
class DicomLabelSeriesReader
{
public:
  /// True for a DICOM Part 10 file (the "DICM" marker after the 128-byte preamble).
  static bool IsDicomFile(const std::string& path);

  /// Reads a folder in either layout; wanted decides which structures are read, the others are
  /// listed with a null Grid.Labels (not wanted structures are not even opened). A folder with
  /// no DICOM file in it or in its sub-folders is refused.
  static LabelStructures ReadFolder(const std::string& folder, const StructureFilter& wanted);

  /// Reads one series: the DICOM files directly inside folder.
  static LabelGrid ReadSeries(const std::string& folder);
};
} // namespace vp

#endif
