#ifndef vpDwellPoints_h
#define vpDwellPoints_h

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace vp
{
/// Where a tracked tip rested on a landmark, PLUS's way of recording landmarks: the user holds the
/// stylus tip on the point for about a second and pivots the shaft about it.
struct DwellPoint
{
  std::array<double, 3> PointMm{}; ///< the mean tip position over the dwell
  double StartS = 0.0, EndS = 0.0;
  std::size_t Poses = 0;
  double TipSpreadMm = 0.0;    ///< the farthest tip from the mean
  double ShaftMotionMm = 0.0;  ///< how far the tool's origin moved meanwhile
};

/// How a dwell is told from the rest (PLUS's landmark detection, vtkPlusLandmarkDetectionAlgo):
/// the tip within TipRadiusMm of its mean for at least MinimumS, while the tool's origin moves at
/// least ShaftMotionMm (the stylus pivots on the point; a stylus lying still on the table is no
/// landmark). Runs interrupted by a jitter and resumed within MergeMm are one dwell.
struct DwellSettings
{
  double MinimumS = 1.0;
  double TipRadiusMm = 1.5;
  double ShaftMotionMm = 20.0;
  double MergeMm = 3.0;
};

/// The dwells of a recording, in time order. timesS and toolPoses (tool-to-world, row-major) are
/// its poses in order; tipToTool places the tip in the tool's coordinates.
std::vector<DwellPoint> FindDwellPoints(const std::vector<double>& timesS, const std::vector<std::array<double, 16>>& toolPoses,
  const std::array<double, 16>& tipToTool, const DwellSettings& settings = {});

/// A 4x4 transform from a text file: 16 numbers, row-major, separated by blanks, commas or line
/// breaks ('#' starts a comment). Throws InputError naming the file otherwise.
std::array<double, 16> ReadMatrixText(const std::string& fileName);
} // namespace vp

#endif
