#include "vpCusaHandpiece.h"

#include <vtkCellArray.h>
#include <vtkPoints.h>

#include <cmath>
#include <utility>
#include <vector>

namespace vp
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr int Sectors = 48;

/// Rounding of the tip's rim and of the back's edge: smooth silhouettes, no sharp rims for the
/// distance engines to snag on.
constexpr double TipRimRadiusMm = 0.4;
constexpr double BackRimRadiusMm = 2.0;
constexpr int RimSteps = 4;
constexpr int TaperSteps = 8;

/// The profile from the tip to the back as (z, radius) pairs, both poles excluded.
std::vector<std::pair<double, double>> Profile()
{
  using D = CusaHandpieceDimensions;
  std::vector<std::pair<double, double>> profile;
  // Tip face rim: a quarter circle from the flat face to the tube's side.
  for (int s = 0; s <= RimSteps; ++s)
  {
    const double a = 0.5 * Pi * s / RimSteps;
    profile.emplace_back(
      -TipRimRadiusMm + TipRimRadiusMm * std::cos(a), D::TipRadiusMm - TipRimRadiusMm + TipRimRadiusMm * std::sin(a));
  }
  // Tube, then the taper as a half cosine (tangent to the tube and to the body at both ends).
  const double taperStart = -D::TipLengthMm;
  for (int s = 0; s <= TaperSteps; ++s)
  {
    const double t = static_cast<double>(s) / TaperSteps;
    profile.emplace_back(taperStart - D::TaperLengthMm * t,
      D::TipRadiusMm + (D::BodyRadiusMm - D::TipRadiusMm) * 0.5 * (1.0 - std::cos(Pi * t)));
  }
  // Body, then the back face's rounded edge.
  const double back = -D::TotalLengthMm;
  for (int s = 0; s <= RimSteps; ++s)
  {
    const double a = 0.5 * Pi * s / RimSteps;
    profile.emplace_back(back + BackRimRadiusMm - BackRimRadiusMm * std::sin(a),
      D::BodyRadiusMm - BackRimRadiusMm + BackRimRadiusMm * std::cos(a));
  }
  return profile;
}
} // namespace

vtkSmartPointer<vtkPolyData> MakeCusaHandpiece()
{
  const std::vector<std::pair<double, double>> profile = Profile();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  const vtkIdType tipPole = points->InsertNextPoint(0.0, 0.0, 0.0);
  std::vector<double> cosines(Sectors), sines(Sectors);
  for (int j = 0; j < Sectors; ++j)
  {
    cosines[j] = std::cos(2 * Pi * j / Sectors);
    sines[j] = std::sin(2 * Pi * j / Sectors);
  }
  const vtkIdType firstRing = points->GetNumberOfPoints();
  for (const auto& [z, r] : profile)
  {
    for (int j = 0; j < Sectors; ++j)
    {
      points->InsertNextPoint(r * cosines[j], r * sines[j], z);
    }
  }
  const vtkIdType backPole = points->InsertNextPoint(0.0, 0.0, -CusaHandpieceDimensions::TotalLengthMm);

  auto ring = [&](std::size_t i, int j) { return firstRing + static_cast<vtkIdType>(i) * Sectors + (j % Sectors); };
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto triangle = [&](vtkIdType a, vtkIdType b, vtkIdType c)
  {
    const vtkIdType ids[3] = { a, b, c };
    polys->InsertNextCell(3, ids);
  };
  // Walking the profile backwards (-z) and the sectors counter-clockwise about +z, (along the
  // profile) x (around) points outward.
  for (int j = 0; j < Sectors; ++j)
  {
    triangle(tipPole, ring(0, j), ring(0, j + 1));
  }
  for (std::size_t i = 0; i + 1 < profile.size(); ++i)
  {
    for (int j = 0; j < Sectors; ++j)
    {
      triangle(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      triangle(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
  }
  for (int j = 0; j < Sectors; ++j)
  {
    triangle(ring(profile.size() - 1, j), backPole, ring(profile.size() - 1, j + 1));
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(polys);
  return mesh;
}
} // namespace vp
