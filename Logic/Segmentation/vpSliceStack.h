#ifndef vpSliceStack_h
#define vpSliceStack_h

#include <array>
#include <string>
#include <vector>

namespace vp
{
/// Where one image plane lies, as DICOM places it: ImagePositionPatient (the centre of its first
/// pixel, LPS mm), ImageOrientationPatient (row then column direction cosines) and PixelSpacing
/// (between rows, between columns; mm). Name says which plane it is in messages: a file, a frame.
struct PlanePlacement
{
  std::string Name;
  std::array<double, 3> PositionLps{};
  std::array<double, 6> Orientation{};
  std::array<double, 2> PixelSpacingMm{};
};

/// How planes may fill a stack.
enum class StackRule
{
  /// An image series: every plane is its own slice; no two at one position, none missing, one
  /// spacing throughout.
  Contiguous,
  /// Frames of a DICOM SEG: frames of different segments share a position, and frames without a
  /// voxel of any segment are left out, so slices may be missing; they are empty.
  Sparse
};

/// Planes stacked into one voxel grid.
struct SliceStack
{
  std::array<double, 16> IjkToLps{}; ///< row-major; index i along rows, j down columns, k slices
  std::vector<int> SliceOfPlane;     ///< the slice index k of each plane, in the order given
  int NumberOfSlices = 0;
};

/// Stacks planes along their common normal, ordered by position along it (never by name).
/// Refuses, with vp::InputError naming where: orientation cosines that are not two orthogonal unit
/// vectors, planes of different orientations or pixel spacings, planes offset sideways (a tilted
/// gantry, which is not resampled), and what the rule forbids (see StackRule). With Sparse, the
/// slice spacing is spacingHintMm (SpacingBetweenSlices) when every gap is a whole multiple of
/// it, else the smallest gap; positions off that grid are refused. One lone plane gets
/// spacingHintMm, or 1 mm without one.
SliceStack StackPlanes(const std::string& where, const std::vector<PlanePlacement>& planes, StackRule rule,
  double spacingHintMm = 0.0);
} // namespace vp

#endif
