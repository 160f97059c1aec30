#include "vpSurfaceIcpRegistration.h"

#include "vpInputError.h"

#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <cmath>

namespace vp
{
namespace
{
// The rigid motion of a small rotation vector (Rodrigues) and a translation.
Matrix4 Motion(const double omega[3], const double tau[3])
{
  const double angle = std::sqrt(omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2]);
  return angle > 0.0 ? RotationAboutAxis({ omega[0], omega[1], omega[2] }, angle, { tau[0], tau[1], tau[2] })
                     : RotationAboutAxis({ 1.0, 0.0, 0.0 }, 0.0, { tau[0], tau[1], tau[2] });
}

// The unit normal of a triangle of the surface.
void TriangleNormal(vtkPolyData* surface, vtkIdType cell, double normal[3])
{
  const vtkIdType* ids = nullptr;
  vtkIdType count = 0;
  surface->GetCellPoints(cell, count, ids);
  double a[3], b[3], c[3];
  surface->GetPoint(ids[0], a);
  surface->GetPoint(ids[1], b);
  surface->GetPoint(ids[2], c);
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  vtkMath::Cross(u, v, normal);
  if (vtkMath::Normalize(normal) == 0.0)
  {
    normal[0] = normal[1] = normal[2] = 0.0;
  }
}
} // namespace

SurfaceRegistration RegisterSurfaceIcp(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& initialModelToWorld, int maximumIterations)
{
  if (!modelSurface || modelSurface->GetNumberOfCells() == 0)
  {
    throw InputError("ICP", "the model surface is empty");
  }
  if (worldPoints.size() < 6)
  {
    throw InputError("ICP", "at least 6 measured surface points are needed, got " + std::to_string(worldPoints.size()));
  }
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(modelSurface);
  locator->BuildLocator();

  // Point-to-plane ICP (Chen and Medioni): each measured point is pulled onto the tangent plane
  // of its closest surface point, not onto the point itself, so the fit may slide along the
  // surface; it needs far fewer iterations than point-to-point ICP (VTK's
  // vtkIterativeClosestPointTransform) once close. Both stop in the same local minima when the
  // guess is too far off.
  Matrix4 worldToModel = InvertTransform(initialModelToWorld);
  SurfaceRegistration result;
  double meanResidual = 0.0;
  for (int iteration = 0; iteration <= maximumIterations; ++iteration)
  {
    double normal[6][6] = {};
    double rhs[6] = {};
    double sum = 0.0;
    for (const Point3& w : worldPoints)
    {
      const Point3 p = TransformPoint(worldToModel, w);
      double closest[3], squared = 0.0, n[3];
      vtkIdType cell = -1;
      int subId = 0;
      locator->FindClosestPoint(p.data(), closest, cell, subId, squared);
      sum += std::sqrt(squared);
      TriangleNormal(modelSurface, cell, n);
      double pxn[3];
      vtkMath::Cross(p.data(), n, pxn);
      const double row[6] = { pxn[0], pxn[1], pxn[2], n[0], n[1], n[2] };
      const double gap = (closest[0] - p[0]) * n[0] + (closest[1] - p[1]) * n[1] + (closest[2] - p[2]) * n[2];
      for (int i = 0; i < 6; ++i)
      {
        for (int j = 0; j < 6; ++j)
        {
          normal[i][j] += row[i] * row[j];
        }
        rhs[i] += row[i] * gap;
      }
    }
    meanResidual = sum / static_cast<double>(worldPoints.size());
    result.Iterations = iteration;
    if (iteration == maximumIterations)
    {
      break;
    }
    // A little damping keeps the step defined for symmetric tools (a stylus spun about its own
    // axis fits equally well at every angle).
    double trace = 0.0;
    for (int i = 0; i < 6; ++i)
    {
      trace += normal[i][i];
    }
    double* rows[6];
    for (int i = 0; i < 6; ++i)
    {
      normal[i][i] += 1e-9 * trace;
      rows[i] = normal[i];
    }
    if (!vtkMath::SolveLinearSystem(rows, rhs, 6))
    {
      break;
    }
    worldToModel = MultiplyTransforms(Motion(rhs, rhs + 3), worldToModel);
    const double step = std::sqrt(rhs[0] * rhs[0] + rhs[1] * rhs[1] + rhs[2] * rhs[2]) * 100.0 +
      std::sqrt(rhs[3] * rhs[3] + rhs[4] * rhs[4] + rhs[5] * rhs[5]);
    if (step < 1e-7) // a movement of 0.1 micrometre at 100 mm
    {
      break;
    }
  }
  result.ModelToWorld = InvertTransform(worldToModel);
  result.MeanResidualMm = meanResidual;
  return result;
}
} // namespace vp
