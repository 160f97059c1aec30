#include "vpClearViewCamera.h"

#include <vtkCamera.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace vp
{
namespace
{
using Vec = std::array<double, 3>;

Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vec Unit(const Vec& v)
{
  const double n = std::sqrt(Dot(v, v));
  return n > 0.0 ? Vec{ v[0] / n, v[1] / n, v[2] / n } : Vec{ 0.0, 0.0, 0.0 };
}

/// A unit vector across the axis: toward the closest point where it is off the axis, else any.
Vec Across(const Vec& axis, const Vec& toClosest)
{
  Vec side = Cross(axis, toClosest);
  if (Dot(side, side) < 1e-12)
  {
    side = Cross(axis, std::abs(axis[2]) < 0.9 ? Vec{ 0.0, 0.0, 1.0 } : Vec{ 0.0, 1.0, 0.0 });
  }
  return Unit(side);
}

/// The depth-buffer value a point at world position p has, and its display position.
Vec DisplayOf(vtkRenderer* renderer, const Vec& p)
{
  renderer->SetWorldPoint(p[0], p[1], p[2], 1.0);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  return { d[0], d[1], d[2] };
}
} // namespace

bool PointInPlainSight(vtkRenderer* renderer, const double point[3], double toleranceMm)
{
  const Vec p{ point[0], point[1], point[2] };
  const Vec d = DisplayOf(renderer, p);
  const int* origin = renderer->GetOrigin();
  const int* size = renderer->GetSize();
  const int x = static_cast<int>(std::lround(d[0])), y = static_cast<int>(std::lround(d[1]));
  if (x < origin[0] || y < origin[1] || x >= origin[0] + size[0] || y >= origin[1] + size[1] || d[2] < 0.0 || d[2] > 1.0)
  {
    return false;
  }
  // Depth is not linear in distance: the tolerance is taken at the point, moved toward the eye.
  double eye[3];
  renderer->GetActiveCamera()->GetPosition(eye);
  const Vec toEye = Unit({ eye[0] - p[0], eye[1] - p[1], eye[2] - p[2] });
  const Vec nearer = DisplayOf(renderer, { p[0] + toleranceMm * toEye[0], p[1] + toleranceMm * toEye[1], p[2] + toleranceMm * toEye[2] });
  return renderer->GetZ(x, y) >= nearer[2];
}

bool PlaceClearViewCamera(
  vtkRenderer* renderer, const double tip[3], const double axis[3], const double* closest, double tipDepthMm)
{
  const Vec t{ tip[0], tip[1], tip[2] };
  const Vec a = Unit({ axis[0], axis[1], axis[2] });
  const Vec c = closest ? Vec{ closest[0], closest[1], closest[2] } : t;
  const Vec gap{ c[0] - t[0], c[1] - t[1], c[2] - t[2] };
  const Vec focus{ (t[0] + c[0]) / 2, (t[1] + c[1]) / 2, (t[2] + c[2]) / 2 };
  const double back = std::max(80.0, 4.0 * std::sqrt(Dot(gap, gap)));
  const Vec first = Across(a, gap);
  const Vec second = Cross(a, first); // with first and a, a frame turning about the axis
  // Tilted first toward the side of the wall the tip is on (so the closest point is seen from
  // outside its vessel), then level, then toward the tip's end and its handle's.
  const Vec outward = tipDepthMm > 0.0 || Dot(gap, gap) < 1e-12 ? a : Unit({ -gap[0], -gap[1], -gap[2] });
  const std::array<Vec, 4> tilts = { Vec{ 0.35 * outward[0], 0.35 * outward[1], 0.35 * outward[2] }, Vec{ 0.0, 0.0, 0.0 },
    Vec{ 0.35 * a[0], 0.35 * a[1], 0.35 * a[2] }, Vec{ -0.35 * a[0], -0.35 * a[1], -0.35 * a[2] } };
  // A tip inside its vessel is behind that vessel's wall: in sight when nothing else is in front.
  const double tipTolerance = 3.0 + std::max(0.0, tipDepthMm);
  vtkCamera* camera = renderer->GetActiveCamera();
  for (const Vec& tilt : tilts)
  {
    for (int step = 0; step < 12; ++step)
    {
      // 0, 180, 30, 210, 60, ...: each side of the gap before turning further.
      const double angle = (step % 2 ? M_PI : 0.0) + (step / 2) * M_PI / 6.0;
      Vec d;
      for (int k = 0; k < 3; ++k)
      {
        d[k] = std::cos(angle) * first[k] + std::sin(angle) * second[k] + tilt[k];
      }
      d = Unit(d);
      camera->SetFocalPoint(focus[0], focus[1], focus[2]);
      camera->SetPosition(focus[0] + back * d[0], focus[1] + back * d[1], focus[2] + back * d[2]);
      camera->SetViewUp(-a[0], -a[1], -a[2]);
      camera->OrthogonalizeViewUp();
      renderer->ResetCameraClippingRange();
      renderer->GetRenderWindow()->Render();
      if (PointInPlainSight(renderer, tip, tipTolerance) && (!closest || PointInPlainSight(renderer, closest)))
      {
        return true;
      }
    }
  }
  return false;
}
} // namespace vp
