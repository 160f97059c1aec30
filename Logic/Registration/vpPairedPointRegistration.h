#ifndef vpPairedPointRegistration_h
#define vpPairedPointRegistration_h

#include "vpRigidTransform.h"

#include <array>
#include <vector>

namespace vp
{
/// A rigid model-to-world transform found from data, with its error as IGT tools report it.
struct RigidRegistration
{
  std::array<double, 16> ModelToWorld{}; ///< row-major
  std::vector<double> PointErrorsMm;     ///< per landmark: |T(model) - world|
  double RmsErrorMm = 0.0;               ///< fiducial registration error (FRE): RMS of the above
};

/// The largest distance (mm) of any point from the line through the two points farthest apart:
/// zero for points on one line (or all at one point), which leave a rotation about that line
/// undetermined.
double SpreadOffLineMm(const std::vector<Point3>& points);

/// Rigid least-squares fit of landmarks given in model coordinates to the same landmarks measured
/// in world coordinates (Horn's closed form, through vtkLandmarkTransform). Needs at least three
/// pairs that do not lie on one line; throws vp::InputError("landmarks", ...) otherwise.
RigidRegistration RegisterPairedPoints(const std::vector<Point3>& modelPoints, const std::vector<Point3>& worldPoints);
} // namespace vp

#endif
