#include "vpPairedPointRegistration.h"

#include "vpInputError.h"

#include <vtkLandmarkTransform.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <cmath>

namespace vp
{
double SpreadOffLineMm(const std::vector<Point3>& points)
{
  // The line through a point farthest from the first and the point farthest from that one: on
  // points that lie on one line it is that line, and it takes one pass, not one per pair.
  const auto farthestFrom = [&](const Point3& from) {
    std::size_t best = 0;
    double longest = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const double d = std::hypot(points[i][0] - from[0], points[i][1] - from[1], points[i][2] - from[2]);
      if (d > longest)
      {
        longest = d;
        best = i;
      }
    }
    return std::make_pair(best, longest);
  };
  if (points.empty())
  {
    return 0.0;
  }
  const std::size_t a = farthestFrom(points[0]).first;
  const auto [b, longest] = farthestFrom(points[a]);
  if (longest == 0.0)
  {
    return 0.0;
  }
  const Point3 u{ (points[b][0] - points[a][0]) / longest, (points[b][1] - points[a][1]) / longest,
    (points[b][2] - points[a][2]) / longest };
  double spread = 0.0;
  for (const Point3& p : points)
  {
    const Point3 d{ p[0] - points[a][0], p[1] - points[a][1], p[2] - points[a][2] };
    const double along = d[0] * u[0] + d[1] * u[1] + d[2] * u[2];
    spread = std::max(spread, std::sqrt(std::max(0.0, d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along)));
  }
  return spread;
}

RigidRegistration RegisterPairedPoints(const std::vector<Point3>& modelPoints, const std::vector<Point3>& worldPoints)
{
  if (modelPoints.size() != worldPoints.size())
  {
    throw InputError("landmarks", std::to_string(modelPoints.size()) + " model points but " +
        std::to_string(worldPoints.size()) + " world points; they must pair up");
  }
  if (modelPoints.size() < 3)
  {
    throw InputError("landmarks", "at least 3 pairs are needed, got " + std::to_string(modelPoints.size()));
  }
  if (SpreadOffLineMm(modelPoints) < 1e-3 || SpreadOffLineMm(worldPoints) < 1e-3)
  {
    throw InputError("landmarks", "the points lie on one line, so the rotation about it is undetermined");
  }
  vtkNew<vtkPoints> source, target;
  source->SetDataTypeToDouble(); // float points would cost micrometres at 300 mm
  target->SetDataTypeToDouble();
  for (std::size_t i = 0; i < modelPoints.size(); ++i)
  {
    source->InsertNextPoint(modelPoints[i].data());
    target->InsertNextPoint(worldPoints[i].data());
  }
  vtkNew<vtkLandmarkTransform> fit;
  fit->SetModeToRigidBody();
  fit->SetSourceLandmarks(source);
  fit->SetTargetLandmarks(target);
  fit->Update();
  RigidRegistration result;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      result.ModelToWorld[4 * r + c] = fit->GetMatrix()->GetElement(r, c);
    }
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < modelPoints.size(); ++i)
  {
    const Point3 moved = TransformPoint(result.ModelToWorld, modelPoints[i]);
    const double e = std::hypot(moved[0] - worldPoints[i][0], moved[1] - worldPoints[i][1], moved[2] - worldPoints[i][2]);
    result.PointErrorsMm.push_back(e);
    sum += e * e;
  }
  result.RmsErrorMm = std::sqrt(sum / static_cast<double>(modelPoints.size()));
  return result;
}
} // namespace vp
