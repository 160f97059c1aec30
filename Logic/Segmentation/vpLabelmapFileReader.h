#ifndef vpLabelmapFileReader_h
#define vpLabelmapFileReader_h

#include "vpLabelStructure.h"

#include <cstddef>
#include <string>

namespace vp
{
/// Reads labelmap files through ITK: NRRD (.nrrd, .nhdr), 3D Slicer's segmentation NRRD
/// (.seg.nrrd: segment names, label values, layers and terminology from its Segment<N>_* keys;
/// each layer of a 4D file is its own grid, so overlapping segments stay apart) and NIfTI (.nii,
/// .nii.gz). Geometry is the file's, in LPS (ITK converts NIfTI's RAS). Without segment keys, each
/// non-zero value is a structure "label N" (a single value takes the file's name).
/// A file that is not a labelmap gets one line naming it (vp::InputError): unreadable, not 3D,
/// non-integer or negative values or more than 256 distinct ones (a CT), empty.
class LabelmapFileReader
{
public:
  /// True for the file name endings this reader takes.
  static bool Handles(const std::string& fileName);
  /// maximumVoxels (voxels x layers) guards against a header that claims more than memory holds:
  /// larger files are refused before anything is allocated. The default, 2^28, is a 512 x 512 x
  /// 1024 volume.
  static LabelStructures Read(const std::string& fileName, std::size_t maximumVoxels = std::size_t(1) << 28);
};
} // namespace vp

#endif
