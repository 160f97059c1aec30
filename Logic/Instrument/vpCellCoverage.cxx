#include "vpCellCoverage.h"

#include <algorithm>
#include <cmath>

namespace vp
{
double CubeFractionBelowPlane(const double n[3], double offset)
{
  // Reflect the cube so every component is positive and sort them: the unit cube [0,1]^3 then lies
  // below m·u = alpha wherever the centred one did below n·y = offset. The closed form sums the
  // corners' cubes over 6 m1 m2 m3; a component too small to divide by (the wall square to an
  // axis or an edge) drops a dimension, the plane taken at its mean over that axis (off by its
  // square).
  double m[3] = { std::abs(n[0]), std::abs(n[1]), std::abs(n[2]) };
  std::sort(m, m + 3, [](double a, double b) { return a > b; });
  double alpha = offset + 0.5 * (m[0] + m[1] + m[2]);
  constexpr double Small = 1e-3;
  int dims = 3;
  while (dims > 1 && m[dims - 1] < Small)
  {
    alpha -= 0.5 * m[dims - 1];
    --dims;
  }
  double sum = 0.0;
  for (int a = 0; a < dims; ++a)
  {
    sum += m[a];
  }
  if (alpha <= 0.0)
  {
    return 0.0;
  }
  if (alpha >= sum)
  {
    return 1.0;
  }
  if (dims == 1)
  {
    return alpha / m[0];
  }
  double volume = 0.0, scale = dims == 2 ? 2.0 * m[0] * m[1] : 6.0 * m[0] * m[1] * m[2];
  for (int corner = 0; corner < (1 << dims); ++corner)
  {
    double reach = alpha;
    int bits = 0;
    for (int a = 0; a < dims; ++a)
    {
      if (corner & (1 << a))
      {
        reach -= m[a];
        ++bits;
      }
    }
    if (reach > 0.0)
    {
      volume += (bits % 2 ? -1.0 : 1.0) * (dims == 2 ? reach * reach : reach * reach * reach);
    }
  }
  return std::clamp(volume / scale, 0.0, 1.0);
}

double CellShareInside(const WallPlane& wall, double cellMm)
{
  return CubeFractionBelowPlane(wall.OutwardNormal, wall.OffsetMm / cellMm);
}

double CellShareInsideBoth(const WallPlane& a, const WallPlane& b, double cellMm)
{
  constexpr int Columns = 8;
  const WallPlane* walls[2] = { &a, &b };
  double share = 0.0;
  for (int i = 0; i < Columns; ++i)
  {
    for (int j = 0; j < Columns; ++j)
    {
      const double x = (i + 0.5) / Columns - 0.5, y = (j + 0.5) / Columns - 0.5;
      // Along z in the unit cell each wall keeps one side of a point: z below or above it.
      double low = -0.5, high = 0.5;
      for (const WallPlane* w : walls)
      {
        const double* n = w->OutwardNormal;
        const double room = w->OffsetMm / cellMm - n[0] * x - n[1] * y; // inside where n_z z < room
        if (std::abs(n[2]) < 1e-12)
        {
          high = room > 0.0 ? high : low;
        }
        else if (n[2] > 0.0)
        {
          high = std::min(high, room / n[2]);
        }
        else
        {
          low = std::max(low, room / n[2]);
        }
      }
      share += std::max(0.0, high - low);
    }
  }
  return share / (Columns * Columns);
}
} // namespace vp
