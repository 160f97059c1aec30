#include "vpTileOrder.h"

#include "vpZBufferShaderLayout.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace vp
{
double TileOrder::GapOfSquare(std::int64_t square) const
{
  return std::sqrt(static_cast<double>(square)) * this->EdgePx * this->PixelMm;
}

std::uint32_t TileOrder::Within(double searchMm) const
{
  const auto all = static_cast<std::uint32_t>(this->GapMm.size());
  if (all == 0 || !(searchMm < this->GapMm.back()))
  {
    return all; // beyond the last gap, or NaN
  }
  if (searchMm < 0.0)
  {
    return 0;
  }
  // The largest square whose gap is within the search: from the rounded guess, a step or two.
  const auto last = static_cast<std::int64_t>(this->EntriesUpToSquare.size()) - 1;
  const double tiles = searchMm / (this->EdgePx * this->PixelMm);
  std::int64_t square = std::min(last, static_cast<std::int64_t>(tiles * tiles));
  while (square < last && this->GapOfSquare(square + 1) <= searchMm)
  {
    ++square;
  }
  while (square > 0 && this->GapOfSquare(square) > searchMm)
  {
    --square;
  }
  return this->EntriesUpToSquare[static_cast<std::size_t>(square)];
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
  order.EdgePx = edgePx;
  order.PixelMm = pixelMm;
  for (const auto& o : order.Offsets)
  {
    const int square = gap(o).first;
    order.GapMm.push_back(order.GapOfSquare(square));
    order.EntriesUpToSquare.resize(static_cast<std::size_t>(square) + 1, static_cast<std::uint32_t>(order.GapMm.size() - 1));
    order.EntriesUpToSquare[static_cast<std::size_t>(square)] = static_cast<std::uint32_t>(order.GapMm.size());
  }
  return order;
}
} // namespace vp
