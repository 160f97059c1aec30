#include "vpEdgeSplitting.h"

#include <unordered_map>

namespace vp
{
namespace
{
double Length2(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}
} // namespace

std::size_t SplitLongEdges(std::vector<std::array<double, 3>>& points,
  std::vector<std::array<std::int32_t, 3>>& triangles, double maxEdgeMm)
{
  const double limit2 = maxEdgeMm * maxEdgeMm;
  const std::size_t before = triangles.size();
  std::unordered_map<std::uint64_t, std::int32_t> midpoints;
  std::vector<std::array<std::int32_t, 3>> pending;
  std::vector<std::array<std::int32_t, 3>> done;
  done.reserve(triangles.size());
  for (const auto& t : triangles)
  {
    pending.push_back(t);
    while (!pending.empty())
    {
      const auto tri = pending.back();
      pending.pop_back();
      int longest = 0;
      double best = -1.0;
      for (int e = 0; e < 3; ++e)
      {
        const double l = Length2(points[tri[e]], points[tri[(e + 1) % 3]]);
        if (l > best)
        {
          best = l;
          longest = e;
        }
      }
      if (best <= limit2)
      {
        done.push_back(tri);
        continue;
      }
      const std::int32_t a = tri[longest], b = tri[(longest + 1) % 3], c = tri[(longest + 2) % 3];
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
      auto found = midpoints.find(key);
      std::int32_t m;
      if (found == midpoints.end())
      {
        const auto& pa = points[a];
        const auto& pb = points[b];
        m = static_cast<std::int32_t>(points.size());
        points.push_back({ 0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2]) });
        midpoints.emplace(key, m);
      }
      else
      {
        m = found->second;
      }
      pending.push_back({ a, m, c });
      pending.push_back({ m, b, c });
    }
  }
  triangles.swap(done);
  return triangles.size() - before;
}
} // namespace vp
