#ifndef vpPivotCalibration_h
#define vpPivotCalibration_h

#include "vpRigidTransform.h"

#include <array>
#include <vector>

namespace vp
{
/// The result of a pivot calibration: where the tip is on the tool, and the point it pivoted on.
struct PivotCalibration
{
  Point3 TipInToolMm{};    ///< the tip offset, in the tracked tool's coordinates
  Point3 PivotInWorldMm{}; ///< the fixed point the tip rested on
  double RmseMm = 0.0;     ///< RMS over poses of |pose(tip) - pivot|
  double RotationSpreadDeg = 0.0; ///< the largest rotation between the first pose and any other
  std::vector<double> PoseErrorsMm; ///< each pose's |pose(tip) - pivot|, in their order
};

/// Pivot calibration as SlicerIGT does it: the tool is tracked while its tip rests on one point
/// and the tool swings about it; the least-squares solution of R_i tip + t_i = pivot over all
/// poses (tool-to-world, row-major 4x4) gives both points. Throws vp::InputError("pivot poses",
/// ...) for fewer than minimumPoses poses, for poses turning less than minimumRotationDeg from the
/// first, and for rotations about a single axis (the tip could slide along it unseen).
PivotCalibration CalibratePivot(const std::vector<std::array<double, 16>>& toolToWorld, std::size_t minimumPoses = 6,
  double minimumRotationDeg = 10.0);
} // namespace vp

#endif
