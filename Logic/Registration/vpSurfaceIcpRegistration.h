#ifndef vpSurfaceIcpRegistration_h
#define vpSurfaceIcpRegistration_h

#include "vpRigidTransform.h"

#include <array>
#include <vector>

class vtkPolyData;

namespace vp
{
/// The result of fitting a model surface to measured points.
struct SurfaceRegistration
{
  std::array<double, 16> ModelToWorld{}; ///< row-major
  double MeanResidualMm = 0.0;           ///< mean distance from each measured point to the placed surface
  int Iterations = 0;
};

/// Rigid ICP of a model surface (model coordinates) to points measured on it in world
/// coordinates, from an initial model-to-world guess (from landmarks, say). Point-to-plane
/// (Chen and Medioni), linearised and solved each iteration, until the fit moves less than 0.1
/// micrometre or maximumIterations. ICP converges to the nearest fit, so the guess must be within
/// a few millimetres and degrees. Throws vp::InputError for fewer than 6 points or an empty
/// surface (which must be triangles).
SurfaceRegistration RegisterSurfaceIcp(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& initialModelToWorld, int maximumIterations = 100);
} // namespace vp

#endif
