#include "vpScalpelTipFinder.h"

#include "vpInputError.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkMath.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <cmath>
#include <cstdio>

namespace vp
{
namespace
{
/// Fraction of the length, at each end, whose spread about the axis decides which end is the tip.
constexpr double EndFraction = 0.10;
/// Surface this close to the extreme counts as the tip point.
constexpr double TipSlabMm = 0.25;

/// Calls visit(area, centre) for each triangle of a triangulated mesh.
template <typename Visit>
void ForEachTriangle(vtkPolyData* mesh, Visit visit)
{
  vtkPoints* points = mesh->GetPoints();
  const vtkIdType* ids = nullptr;
  vtkIdType n = 0;
  auto polys = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    polys->GetCurrentCell(n, ids);
    if (n != 3)
    {
      continue;
    }
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      points->GetPoint(ids[k], p[k]);
    }
    double e1[3], e2[3], c[3];
    vtkMath::Subtract(p[1], p[0], e1);
    vtkMath::Subtract(p[2], p[0], e2);
    vtkMath::Cross(e1, e2, c);
    const double centre[3] = { (p[0][0] + p[1][0] + p[2][0]) / 3, (p[0][1] + p[1][1] + p[2][1]) / 3,
      (p[0][2] + p[1][2] + p[2][2]) / 3 };
    visit(0.5 * vtkMath::Norm(c), centre);
  }
}

/// Area-weighted centroid and principal axis of the surface: the triangles' areas, not the vertex
/// count, so a finely meshed handle does not outweigh a coarse blade.
void PrincipalAxis(vtkPolyData* mesh, double centroid[3], double axis[3])
{
  double total = 0.0;
  double sum[3] = { 0, 0, 0 };
  double second[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  ForEachTriangle(mesh, [&](double area, const double m[3]) {
    total += area;
    for (int i = 0; i < 3; ++i)
    {
      sum[i] += area * m[i];
      for (int j = 0; j < 3; ++j)
      {
        second[i][j] += area * m[i] * m[j];
      }
    }
  });
  if (!(total > 0))
  {
    throw std::domain_error("no area");
  }
  double cov[3][3];
  for (int i = 0; i < 3; ++i)
  {
    centroid[i] = sum[i] / total;
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      cov[i][j] = second[i][j] / total - centroid[i] * centroid[j];
    }
  }
  double* rows[3] = { cov[0], cov[1], cov[2] };
  double values[3], vectors[3][3];
  double* columns[3] = { vectors[0], vectors[1], vectors[2] };
  vtkMath::Jacobi(rows, values, columns); // sorted decreasing; eigenvectors in columns
  for (int i = 0; i < 3; ++i)
  {
    axis[i] = vectors[i][0];
  }
}

/// Each point of the model with its position s along the axis from the centroid.
template <typename Visit>
void ForEachPointAlong(vtkPoints* points, const double centroid[3], const double axis[3], Visit&& visit)
{
  const vtkIdType count = points->GetNumberOfPoints();
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    visit(p, (p[0] - centroid[0]) * axis[0] + (p[1] - centroid[1]) * axis[1] + (p[2] - centroid[2]) * axis[2]);
  }
}
} // namespace

ScalpelTipEstimate FindScalpelTip(vtkPolyData* model, const std::string& source)
{
  if (!model || !model->GetPoints() || model->GetNumberOfPolys() == 0)
  {
    throw InputError(source, "the instrument model has no surface to find a tip on");
  }
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputData(model);
  triangles->PassLinesOff();
  triangles->PassVertsOff();
  triangles->Update();
  vtkPolyData* mesh = triangles->GetOutput();
  double centroid[3], axis[3];
  try
  {
    PrincipalAxis(mesh, centroid, axis);
  }
  catch (const std::domain_error&)
  {
    throw InputError(source, "the instrument model has no area (all its triangles are degenerate)");
  }

  // Extent along the axis and each point's distance from it.
  vtkPoints* points = mesh->GetPoints();
  double low = VTK_DOUBLE_MAX, high = -VTK_DOUBLE_MAX;
  ForEachPointAlong(points, centroid, axis, [&](const double*, double s) {
    low = std::min(low, s);
    high = std::max(high, s);
  });
  const double length = high - low;
  if (!(length > 0))
  {
    throw InputError(source, "the instrument model has no length to find a tip along");
  }
  // Surface area and its RMS distance from the axis within each end's last EndFraction of the
  // length: a working end tapers, so it holds little surface; a handle ends in a cap or a grip.
  double area[2] = { 0, 0 };
  double spread[2] = { 0, 0 };
  ForEachTriangle(mesh, [&](double a, const double m[3]) {
    double d[3];
    vtkMath::Subtract(m, centroid, d);
    const double s = vtkMath::Dot(d, axis);
    const double r2 = std::max(0.0, vtkMath::Dot(d, d) - s * s);
    const double fromEnd[2] = { s - low, high - s };
    for (int e = 0; e < 2; ++e)
    {
      if (fromEnd[e] <= EndFraction * length)
      {
        area[e] += a;
        spread[e] += a * r2;
      }
    }
  });
  // The tip point: the centre of the surface points at the very extreme of the chosen end.
  double tipSum[2][3] = { { 0, 0, 0 }, { 0, 0, 0 } };
  int inTip[2] = { 0, 0 };
  ForEachPointAlong(points, centroid, axis, [&](const double* p, double s) {
    const double fromEnd[2] = { s - low, high - s };
    for (int e = 0; e < 2; ++e)
    {
      if (fromEnd[e] <= TipSlabMm)
      {
        for (int a = 0; a < 3; ++a)
        {
          tipSum[e][a] += p[a];
        }
        ++inTip[e];
      }
    }
  });
  double width[2];
  for (int e = 0; e < 2; ++e)
  {
    width[e] = area[e] > 0 ? std::sqrt(spread[e] / area[e]) : 0.0;
  }
  const int tipEnd = area[0] < area[1] ? 0 : 1; // 0: the low end, 1: the high end

  ScalpelTipEstimate estimate;
  for (int a = 0; a < 3; ++a)
  {
    estimate.TipMm[a] = tipSum[tipEnd][a] / inTip[tipEnd]; // the extreme point itself is always in
    estimate.Axis[a] = tipEnd == 1 ? axis[a] : -axis[a];
    estimate.CentroidMm[a] = centroid[a];
  }
  estimate.LengthMm = length;
  estimate.TipEndWidthMm = width[tipEnd];
  estimate.OtherEndWidthMm = width[1 - tipEnd];
  estimate.TipEndAreaMm2 = area[tipEnd];
  estimate.OtherEndAreaMm2 = area[1 - tipEnd];
  estimate.Ambiguous = area[tipEnd] > 0.8 * area[1 - tipEnd];
  char text[320];
  std::snprintf(text, sizeof(text),
    "tip found automatically at (%.2f, %.2f, %.2f) mm, axis (%.3f, %.3f, %.3f): the narrower end of the model's "
    "principal axis (length %.1f mm; its last 10%% holds %.0f mm2 of surface, the other end's %.0f mm2)%s",
    estimate.TipMm[0], estimate.TipMm[1], estimate.TipMm[2], estimate.Axis[0], estimate.Axis[1], estimate.Axis[2],
    length, estimate.TipEndAreaMm2, estimate.OtherEndAreaMm2,
    estimate.Ambiguous ? "; the ends are alike, so this is a guess" : "");
  estimate.Description = text;
  return estimate;
}
} // namespace vp
