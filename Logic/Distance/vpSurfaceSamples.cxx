#include "vpSurfaceSamples.h"

#include "vpEdgeSplitting.h"

#include <algorithm>
#include <cmath>
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
  // Clusters: the cubes of clusterMm the points fall in, in a stable order (sorted by cube, then
  // by point: a million points sort in a fraction of what a tree of cubes takes).
  struct Keyed
  {
    std::array<long long, 3> Cube;
    std::size_t Point;
    bool operator<(const Keyed& o) const { return std::tie(this->Cube, this->Point) < std::tie(o.Cube, o.Point); }
  };
  std::vector<Keyed> keyed;
  keyed.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (used[i])
    {
      const auto& p = points[i];
      keyed.push_back({ { static_cast<long long>(std::floor(p[0] / clusterMm)), static_cast<long long>(std::floor(p[1] / clusterMm)),
                          static_cast<long long>(std::floor(p[2] / clusterMm)) },
        i });
    }
  }
  std::sort(keyed.begin(), keyed.end());
  SurfaceSamples out;
  out.SpacingMm = spacingMm;
  out.Points.reserve(keyed.size());
  for (std::size_t first = 0; first < keyed.size();)
  {
    std::size_t last = first;
    while (last < keyed.size() && keyed[last].Cube == keyed[first].Cube)
    {
      ++last;
    }
    Cluster c;
    c.First = static_cast<std::uint32_t>(out.Points.size());
    c.Count = static_cast<std::uint32_t>(last - first);
    std::array<double, 3> lo = points[keyed[first].Point], hi = lo;
    for (std::size_t j = first; j < last; ++j)
    {
      const auto& p = points[keyed[j].Point];
      out.Points.push_back(p);
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    for (int k = 0; k < 3; ++k)
    {
      c.CentreMm[k] = 0.5 * (lo[k] + hi[k]);
    }
    for (std::size_t j = c.First; j < out.Points.size(); ++j)
    {
      const auto& p = out.Points[j];
      const double dx = p[0] - c.CentreMm[0], dy = p[1] - c.CentreMm[1], dz = p[2] - c.CentreMm[2];
      c.RadiusMm = std::max(c.RadiusMm, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    c.RadiusMm += 1e-9; // rounding of the transform must not put a point outside
    out.Clusters.push_back(c);
    first = last;
  }
  return out;
}
} // namespace vp
