#include "vpSurfaceSamples.h"

#include "vpEdgeSplitting.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

namespace vp
{
SurfaceSamples SurfaceSamples::Of(std::vector<std::array<double, 3>> points,
  std::vector<std::array<std::int32_t, 3>> triangles, double spacingMm, double clusterMm)
{
  if (!(spacingMm > 0.0) || !(clusterMm > 0.0))
  {
    throw std::invalid_argument("vp::SurfaceSamples: the spacing and the cluster size must be positive");
  }
  SplitLongEdges(points, triangles, spacingMm * std::sqrt(3.0));
  std::vector<char> used(points.size(), 0);
  for (const auto& t : triangles)
  {
    for (std::int32_t i : t)
    {
      used[static_cast<std::size_t>(i)] = 1;
    }
  }
  // Clusters: the cubes of clusterMm the points fall in, in a stable order.
  std::map<std::tuple<long long, long long, long long>, std::vector<std::size_t>> cubes;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (used[i])
    {
      const auto& p = points[i];
      cubes[{ static_cast<long long>(std::floor(p[0] / clusterMm)), static_cast<long long>(std::floor(p[1] / clusterMm)),
        static_cast<long long>(std::floor(p[2] / clusterMm)) }]
        .push_back(i);
    }
  }
  SurfaceSamples out;
  out.SpacingMm = spacingMm;
  for (const auto& cube : cubes)
  {
    Cluster c;
    c.First = static_cast<std::uint32_t>(out.Points.size());
    c.Count = static_cast<std::uint32_t>(cube.second.size());
    std::array<double, 3> lo = points[cube.second.front()], hi = lo;
    for (std::size_t i : cube.second)
    {
      out.Points.push_back(points[i]);
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], points[i][k]);
        hi[k] = std::max(hi[k], points[i][k]);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      c.CentreMm[k] = 0.5 * (lo[k] + hi[k]);
    }
    for (std::size_t i : cube.second)
    {
      const auto& p = points[i];
      const double dx = p[0] - c.CentreMm[0], dy = p[1] - c.CentreMm[1], dz = p[2] - c.CentreMm[2];
      c.RadiusMm = std::max(c.RadiusMm, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    c.RadiusMm += 1e-9; // rounding of the transform must not put a point outside
    out.Clusters.push_back(c);
  }
  return out;
}
} // namespace vp
