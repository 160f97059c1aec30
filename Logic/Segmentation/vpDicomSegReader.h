#ifndef vpDicomSegReader_h
#define vpDicomSegReader_h

#include "vpLabelStructure.h"

#include <cstddef>
#include <string>

namespace vp
{
/// Reads a DICOM Segmentation object (SEG): one file whose frames hold the segments.
///  - Segmentation Storage, BINARY or FRACTIONAL, through DCMTK's dcmseg. Each segment becomes a
///    structure with its own voxel grid, so overlapping segments stay apart. A FRACTIONAL voxel
///    is inside when its value is at least half of MaximumFractionalValue: probability or
///    occupancy 0.5, the level at which a partial-volume voxel is as much in as out.
///  - Label Map Segmentation Storage (1.2.840.10008.5.1.4.1.1.66.7), whose 8- or 16-bit frames
///    hold segment numbers. DCMTK 3.6.7's dcmseg predates this class and refuses it, so it is read
///    through dcmdata and dcmfg; its segments share one grid (LabelValue = segment number).
///    Segment 0, the background, is not a structure.
/// Structures are named by SegmentLabel and carry the segmented property category and type
/// codes. Geometry comes from the functional groups (plane position, orientation, pixel
/// measures); frames at one position share a slice, and slices no frame covers (SEG leaves empty
/// frames out) are empty. wanted decides which segments' voxels are made.
///
/// Refused with one line naming the file (vp::InputError): a DICOM file of another class (an
/// image slice), compressed pixel data, frames without a position or off one slice grid, frames
/// of several orientations or pixel spacings, pixel data shorter than its frames, a frame that
/// names no listed segment, an empty wanted segment, and a grid of more than maximumVoxels.
class DicomSegReader
{
public:
  /// True for the SOP class UIDs of the two segmentation classes read here.
  static bool IsSegmentationClass(const std::string& sopClassUid);
  /// Makes DCMTK's functional-group factory, which it makes lazily without a lock.
  static void PrepareForThreads();

  static LabelStructures Read(const std::string& path, const StructureFilter& wanted,
    std::size_t maximumVoxels = std::size_t(1) << 28);
};
} // namespace vp

#endif
