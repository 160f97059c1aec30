#include "vpTileOrder.h"

#include "vpZBufferShaderLayout.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace vp
{
std::uint32_t TileOrder::Within(double searchMm) const
{
  return static_cast<std::uint32_t>(std::upper_bound(this->GapMm.begin(), this->GapMm.end(), searchMm) - this->GapMm.begin());
}

int CoarseAcross(int tiles)
{
  return (tiles + zbuffer::CoarseTiles - 1) / zbuffer::CoarseTiles;
}

TileOrder NearestFirst(double rangeMm, double edgePx, double pixelMm, int tilesAcross)
{
  TileOrder order;
  order.Reach = static_cast<int>(std::min(std::ceil(rangeMm / (edgePx * pixelMm)) + 1.0, static_cast<double>(tilesAcross)));
  for (int dy = -order.Reach; dy <= order.Reach; ++dy)
  {
    for (int dx = -order.Reach; dx <= order.Reach; ++dx)
    {
      order.Offsets.push_back({ dx, dy });
    }
  }
  auto gap = [](const std::array<std::int32_t, 2>& o) {
    const int gx = std::max(0, std::abs(o[0]) - 1), gy = std::max(0, std::abs(o[1]) - 1);
    return std::make_pair(gx * gx + gy * gy, o[0] * o[0] + o[1] * o[1]);
  };
  std::stable_sort(
    order.Offsets.begin(), order.Offsets.end(), [&](const auto& a, const auto& b) { return gap(a) < gap(b); });
  for (const auto& o : order.Offsets)
  {
    order.GapMm.push_back(std::sqrt(static_cast<double>(gap(o).first)) * edgePx * pixelMm);
  }
  return order;
}
} // namespace vp
