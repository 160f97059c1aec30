#include "vpSurfaceSamples.h"

#include "vpEdgeSplitting.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vp
{
namespace
{
/// The bits of v (below 2^21) spread to every third bit.
std::uint64_t Spread(std::uint64_t v)
{
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

/// The node's sphere: the centre of its points' box, and the farthest of them from it.
void Enclose(SurfaceSamples::Node& node, const std::vector<std::array<double, 3>>& points)
{
  std::array<double, 3> lo = points[node.First], hi = lo;
  for (std::size_t j = node.First; j < node.First + node.Count; ++j)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], points[j][k]);
      hi[k] = std::max(hi[k], points[j][k]);
    }
  }
  double r2 = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    node.CentreMm[k] = 0.5 * (lo[k] + hi[k]);
  }
  for (std::size_t j = node.First; j < node.First + node.Count; ++j)
  {
    const auto& p = points[j];
    const double dx = p[0] - node.CentreMm[0], dy = p[1] - node.CentreMm[1], dz = p[2] - node.CentreMm[2];
    r2 = std::max(r2, dx * dx + dy * dy + dz * dz);
  }
  node.RadiusMm = std::sqrt(r2) + 1e-9; // rounding of the transform must not put a point outside
}
/// A used point and its leaf's Morton code.
struct Keyed
{
  std::uint64_t Code;
  std::size_t Point;
  bool operator<(const Keyed& o) const { return this->Code != o.Code ? this->Code < o.Code : this->Point < o.Point; }
};

/// The points some triangle uses, sorted by their leaf's Morton code, then by point (a stable
/// order): every cube of any level is then one run.
std::vector<Keyed> InLeafOrder(const std::vector<std::array<double, 3>>& points,
  const std::vector<std::array<std::int32_t, 3>>& triangles, double clusterMm)
{
  std::vector<char> used(points.size(), 0);
  for (const auto& t : triangles)
  {
    for (std::int32_t i : t)
    {
      used[static_cast<std::size_t>(i)] = 1;
    }
  }
  auto cubeOf = [clusterMm](const std::array<double, 3>& p, int k) { return static_cast<long long>(std::floor(p[k] / clusterMm)); };
  std::array<long long, 3> lowest{ { 0, 0, 0 } };
  bool any = false;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    for (int k = 0; used[i] && k < 3; ++k)
    {
      lowest[k] = any ? std::min(lowest[k], cubeOf(points[i], k)) : cubeOf(points[i], k);
    }
    any = any || used[i];
  }
  if (!any)
  {
    throw std::invalid_argument("vp::SurfaceSamples: the surface has no triangles");
  }
  std::vector<Keyed> keyed;
  keyed.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!used[i])
    {
      continue;
    }
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k)
    {
      const long long cube = cubeOf(points[i], k) - lowest[k];
      if (cube >= (1 << 21))
      {
        throw std::invalid_argument("vp::SurfaceSamples: the surface spans more than 2^21 clusters along an axis");
      }
      code |= Spread(static_cast<std::uint64_t>(cube)) << k;
    }
    keyed.push_back({ code, i });
  }
  std::sort(keyed.begin(), keyed.end());
  return keyed;
}

/// A node of the level being built: its cube's code at that level, and its place in Nodes.
struct Placed
{
  std::uint64_t Code;
  std::uint32_t Node;
};

/// The leaves, one per run of equal codes, with their points in that order.
std::vector<Placed> AddLeaves(SurfaceSamples& out, const std::vector<std::array<double, 3>>& points, const std::vector<Keyed>& keyed)
{
  std::vector<Placed> level;
  out.Points.reserve(keyed.size());
  for (std::size_t first = 0; first < keyed.size();)
  {
    std::size_t last = first;
    SurfaceSamples::Node leaf;
    leaf.First = static_cast<std::uint32_t>(out.Points.size());
    for (; last < keyed.size() && keyed[last].Code == keyed[first].Code; ++last)
    {
      out.Points.push_back(points[keyed[last].Point]);
    }
    leaf.Count = static_cast<std::uint32_t>(last - first);
    Enclose(leaf, out.Points);
    level.push_back({ keyed[first].Code, static_cast<std::uint32_t>(out.Nodes.size()) });
    out.Nodes.push_back(leaf);
    first = last;
  }
  out.NumberOfLeaves = out.Nodes.size();
  return level;
}

/// The levels above, each of cubes twice as large, up to a single node: the root, made last.
void AddLevels(SurfaceSamples& out, std::vector<Placed> level)
{
  while (level.size() > 1)
  {
    std::vector<Placed> above;
    for (std::size_t first = 0; first < level.size();)
    {
      const std::uint64_t code = level[first].Code >> 3;
      std::size_t last = first;
      while (last < level.size() && level[last].Code >> 3 == code)
      {
        ++last;
      }
      if (last - first == 1)
      {
        above.push_back({ code, level[first].Node }); // a cube holding one cube: that cube
      }
      else
      {
        SurfaceSamples::Node node;
        node.First = out.Nodes[level[first].Node].First;
        node.FirstChild = static_cast<std::uint32_t>(out.Children.size());
        node.ChildCount = static_cast<std::uint32_t>(last - first);
        for (std::size_t j = first; j < last; ++j)
        {
          out.Children.push_back(level[j].Node);
          node.Count += out.Nodes[level[j].Node].Count;
        }
        Enclose(node, out.Points);
        above.push_back({ code, static_cast<std::uint32_t>(out.Nodes.size()) });
        out.Nodes.push_back(node);
      }
      first = last;
    }
    level.swap(above);
  }
}
} // namespace

SurfaceSamples SurfaceSamples::Of(std::vector<std::array<double, 3>> points,
  std::vector<std::array<std::int32_t, 3>> triangles, double spacingMm, double clusterMm)
{
  if (!(spacingMm > 0.0) || !(clusterMm > 0.0))
  {
    throw std::invalid_argument("vp::SurfaceSamples: the spacing and the cluster size must be positive");
  }
  SplitLongEdges(points, triangles, spacingMm * std::sqrt(3.0));
  SurfaceSamples out;
  out.SpacingMm = spacingMm;
  AddLevels(out, AddLeaves(out, points, InLeafOrder(points, triangles, clusterMm)));
  return out; // the last node made is the root (a single leaf when there is one)
}
} // namespace vp
