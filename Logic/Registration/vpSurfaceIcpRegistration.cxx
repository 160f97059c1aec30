#include "vpSurfaceIcpRegistration.h"

#include "vpInputError.h"
#include "vpPairedPointRegistration.h"
#include "vpQuantile.h"

#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkCellLocator.h>

#include <algorithm>
#include <cmath>
#include <utility>

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

// What every fit needs: a surface, enough points, and the locator over the surface (built
// serially, so that the same fit comes on every run: the threaded build of vtkStaticCellLocator
// orders equal candidates differently from run to run).
vtkSmartPointer<vtkCellLocator> IcpLocator(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints)
{
  if (!modelSurface || modelSurface->GetNumberOfCells() == 0)
  {
    throw InputError("ICP", "the model surface is empty");
  }
  if (worldPoints.size() < 6)
  {
    throw InputError("ICP", "at least 6 measured surface points are needed, got " + std::to_string(worldPoints.size()));
  }
  if (SpreadOffLineMm(worldPoints) < 1e-3)
  {
    // Points on one line (or at one point) leave the turn about it, and the slide along it, open:
    // any pose would fit them with no residual.
    throw InputError("ICP", "the measured points lie on one line, so they cannot fix the pose");
  }
  auto locator = vtkSmartPointer<vtkCellLocator>::New();
  locator->SetDataSet(modelSurface);
  locator->CacheCellBoundsOn();
  locator->BuildLocator();
  return locator;
}

SurfaceRegistration FitFromStart(vtkPolyData* modelSurface, vtkCellLocator* locator, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& initialModelToWorld, int maximumIterations)
{
  // Point-to-plane ICP (Chen and Medioni): each measured point is pulled onto the tangent plane
  // of its closest surface point, not onto the point itself, so the fit may slide along the
  // surface; it needs far fewer iterations than point-to-point ICP (VTK's
  // vtkIterativeClosestPointTransform) once close. Both stop in the same local minima when the
  // guess is too far off.
  Matrix4 worldToModel = InvertTransform(initialModelToWorld);
  SurfaceRegistration result;
  double meanResidual = 0.0;
  std::vector<double> residuals(worldPoints.size());
  for (int iteration = 0; iteration <= maximumIterations; ++iteration)
  {
    double normal[6][6] = {};
    double rhs[6] = {};
    double sum = 0.0;
    for (std::size_t i = 0; i < worldPoints.size(); ++i)
    {
      const Point3 p = TransformPoint(worldToModel, worldPoints[i]);
      double closest[3], squared = 0.0, n[3];
      vtkIdType cell = -1;
      int subId = 0;
      locator->FindClosestPoint(p.data(), closest, cell, subId, squared);
      residuals[i] = std::sqrt(squared);
      sum += residuals[i];
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
  result.MedianResidualMm = Quantile(residuals, 0.5);
  result.P95ResidualMm = Quantile(residuals, 0.95);
  int far = 0;
  for (const double r : residuals)
  {
    far += r > SurfaceRegistration::FarResidualFactor * result.MedianResidualMm ? 1 : 0;
  }
  result.FarFraction = static_cast<double>(far) / static_cast<double>(residuals.size());
  result.ResidualsMm = std::move(residuals);
  return result;
}

} // namespace

SurfaceRegistration RegisterSurfaceIcp(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& initialModelToWorld, int maximumIterations)
{
  return FitFromStart(modelSurface, IcpLocator(modelSurface, worldPoints), worldPoints, initialModelToWorld, maximumIterations);
}

std::vector<Matrix4> IcpStarts(const std::vector<Point3>& worldPoints, const Matrix4& guess, const std::vector<double>& turnsDeg,
  const std::vector<double>& shiftsMm)
{
  // The measured points' centroid and principal axes: a thin instrument's wrong minima lie along
  // and about its long axis.
  Point3 centroid{ 0.0, 0.0, 0.0 };
  for (const Point3& w : worldPoints)
  {
    for (int a = 0; a < 3; ++a)
    {
      centroid[a] += w[a] / static_cast<double>(worldPoints.size());
    }
  }
  double covariance[3][3] = {};
  for (const Point3& w : worldPoints)
  {
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        covariance[i][j] += (w[i] - centroid[i]) * (w[j] - centroid[j]);
      }
    }
  }
  double* rows[3] = { covariance[0], covariance[1], covariance[2] };
  double values[3], vectors[3][3];
  double* vectorRows[3] = { vectors[0], vectors[1], vectors[2] };
  vtkMath::Jacobi(rows, values, vectorRows); // eigenvectors in the columns
  std::vector<Matrix4> starts{ guess };
  for (int a = 0; a < 3; ++a)
  {
    const Point3 axis{ vectors[0][a], vectors[1][a], vectors[2][a] };
    for (const double turnDeg : turnsDeg)
    {
      // A turn about the centroid: rotate, then put the centroid back where it was.
      Matrix4 turn = RotationAboutAxis(axis, turnDeg * vtkMath::Pi() / 180.0, { 0.0, 0.0, 0.0 });
      const Point3 moved = TransformPoint(turn, centroid);
      for (int k = 0; k < 3; ++k)
      {
        turn[4 * k + 3] = centroid[k] - moved[k];
      }
      starts.push_back(MultiplyTransforms(turn, guess));
    }
    for (const double shiftMm : shiftsMm)
    {
      const Point3 offset{ shiftMm * axis[0], shiftMm * axis[1], shiftMm * axis[2] };
      starts.push_back(MultiplyTransforms(RotationAboutAxis({ 1.0, 0.0, 0.0 }, 0.0, offset), guess));
    }
  }
  return starts;
}

namespace
{
// ICP from each start for a few iterations on a subset of the points (enough to rank the
// starts, at a fraction of the cost: the closest-point search is all of it), the best few of
// those refined to convergence on all the points; the least mean residual of those.
SurfaceRegistration BestOfStarts(vtkPolyData* modelSurface, vtkCellLocator* locator, const std::vector<Point3>& worldPoints,
  const std::vector<Matrix4>& starts, int coarseIterations, std::size_t refined)
{
  constexpr std::size_t rankingPoints = 100;
  std::vector<Point3> subset;
  const std::size_t stride = (worldPoints.size() + rankingPoints - 1) / rankingPoints;
  for (std::size_t i = 0; i < worldPoints.size(); i += stride)
  {
    subset.push_back(worldPoints[i]);
  }
  std::vector<SurfaceRegistration> coarse;
  for (const Matrix4& start : starts)
  {
    coarse.push_back(FitFromStart(modelSurface, locator, subset, start, coarseIterations));
  }
  std::stable_sort(coarse.begin(), coarse.end(),
    [](const SurfaceRegistration& a, const SurfaceRegistration& b) { return a.MeanResidualMm < b.MeanResidualMm; });
  SurfaceRegistration best;
  int iterations = 0;
  for (std::size_t k = 0; k < std::min(refined, coarse.size()); ++k)
  {
    SurfaceRegistration fine = FitFromStart(modelSurface, locator, worldPoints, coarse[k].ModelToWorld, 300);
    iterations += coarse[k].Iterations + fine.Iterations;
    if (k == 0 || fine.MeanResidualMm < best.MeanResidualMm)
    {
      best = std::move(fine);
    }
  }
  best.Iterations = iterations;
  best.Starts = static_cast<int>(starts.size());
  return best;
}
} // namespace

SurfaceRegistration RegisterSurfaceIcpMultiStart(vtkPolyData* modelSurface, const std::vector<Point3>& worldPoints,
  const std::array<double, 16>& guessModelToWorld)
{
  // One locator for every start: the surface does not change.
  const vtkSmartPointer<vtkCellLocator> locator = IcpLocator(modelSurface, worldPoints);
  SurfaceRegistration best = BestOfStarts(modelSurface, locator, worldPoints,
    IcpStarts(worldPoints, guessModelToWorld, { -20.0, -10.0, 10.0, 20.0 }, { -10.0, -5.0, 5.0, 10.0 }), 30, 3);
  // A thin instrument has wrong minima a millimetre or a degree beside the right one (the blade
  // slid a little along its shaft, a residual two or three times the right one's), which the
  // wide starts can land in. Hop to a neighbouring minimum while one explains the points better.
  int starts = best.Starts, iterations = best.Iterations;
  for (int round = 0; round < 4; ++round)
  {
    SurfaceRegistration hop = BestOfStarts(modelSurface, locator, worldPoints,
      IcpStarts(worldPoints, best.ModelToWorld, { -4.0, -2.0, 2.0, 4.0 }, { -3.0, -1.5, 1.5, 3.0 }), 10, 1);
    starts += hop.Starts;
    iterations += hop.Iterations;
    if (!(hop.MeanResidualMm < 0.99 * best.MeanResidualMm))
    {
      break;
    }
    best = std::move(hop);
  }
  best.Starts = starts;
  best.Iterations = iterations;
  return best;
}
} // namespace vp
