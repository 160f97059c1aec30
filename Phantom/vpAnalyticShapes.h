#ifndef vpAnalyticShapes_h
#define vpAnalyticShapes_h

#include <vtkSmartPointer.h>

#include <vtkPolyData.h>

namespace vp
{
/// Closed, consistently outward-wound triangle meshes of analytic shapes whose every vertex lies
/// on the analytic surface. Built in a local frame whose z axis is the shape's axis, then placed
/// at `center` with z turned onto `axis` (need not be unit; null means +z).
///
/// They serve as test shapes with known distances and as the built-in vessels of the phantom.

/// UV sphere: `rings` latitude bands (>= 3), `segments` longitudes (>= 3).
vtkSmartPointer<vtkPolyData> MakeSphere(const double center[3], double radiusMm, int rings, int segments);
/// Cylinder of the given radius and length along its axis, closed by flat caps at +-length/2.
vtkSmartPointer<vtkPolyData> MakeCappedCylinder(
  const double center[3], const double* axis, double radiusMm, double lengthMm, int segments);
/// Torus: tube radius `tubeRadiusMm` around a circle of radius `ringRadiusMm` in the plane
/// normal to its axis.
vtkSmartPointer<vtkPolyData> MakeTorus(const double center[3], const double* axis, double ringRadiusMm,
  double tubeRadiusMm, int ringSegments, int tubeSegments);
/// A rotation matrix (row-major) turning +z onto axis; identity for null.
void RotationFromZ(const double* axis, double rotation[3][3]);
} // namespace vp

#endif
