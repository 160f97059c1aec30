#include "vpHostTileListing.h"

#include "vpZBufferShaderLayout.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace vp
{
namespace
{
using zbuffer::CoarsePixelBits;
using zbuffer::CoarseTiles;
using zbuffer::TilePixelBits;
using zbuffer::TilePx;

// The device rounds to floats and moves its gaps down and its ceilings up by 1e-5 of themselves
// (and 1e-4 mm): the host moves them twice as far, so that it never leaves off a tile the device
// would list.
double Lowered(double mm)
{
  return mm - mm * 2e-5 - 2e-4;
}
double Raised(double mm)
{
  return mm + mm * 2e-5 + 2e-4;
}
// The square that a squared gap must pass for the gap, lowered, to pass best (no root per test).
double Beyond2(double best)
{
  const double mm = (best + 2e-4) / (1.0 - 2e-5);
  return mm * mm;
}

// The tile holding grid coordinate x, clamped to the grid as the shader's CentreTile clamps it,
// in double before the cast (a tip a kilometre away, or NaN, would overflow an int).
int ClampedTile(double x, int tiles)
{
  const double t = std::floor(x / TilePx);
  return t >= 0.0 ? static_cast<int>(std::min(t, static_cast<double>(tiles - 1))) : 0;
}

double AxisGap(double x, double lo, double hi)
{
  return std::max(0.0, std::max(lo - x, x - hi));
}
} // namespace

void HostTileListing::SetTables(const TileOrder& fine, const TileOrder& coarse, const std::vector<std::uint32_t>& entryOf)
{
  this->FineEntries = static_cast<std::uint32_t>(fine.Offsets.size());
  this->Coarse = coarse.Offsets;
  this->CoarseGapMm.clear();
  for (const double gap : coarse.GapMm)
  {
    this->CoarseGapMm.push_back(Lowered(gap));
  }
  this->Reach = fine.Reach;
  this->EntryOf = entryOf;
}

void HostTileListing::SetRanges(
  std::vector<std::uint32_t> words, int tilesX, int tilesY, int classes, double pixelMm, double sliceMm)
{
  this->Ranges = std::move(words);
  this->TilesX = tilesX;
  this->TilesY = tilesY;
  this->Classes = classes;
  this->PixelMm = pixelMm;
  this->SliceMm = sliceMm;
}

double HostTileListing::BoxGap2(const float tipGrid[3], int firstPixelX, int firstPixelY, int edgePx, double lo, double hi) const
{
  const double dx = AxisGap(tipGrid[0], firstPixelX, firstPixelX + edgePx) * this->PixelMm;
  const double dy = AxisGap(tipGrid[1], firstPixelY, firstPixelY + edgePx) * this->PixelMm;
  const double dz = AxisGap(tipGrid[2], std::floor(lo), std::floor(hi) + 1.0) * this->SliceMm;
  return dx * dx + dy * dy + dz * dz;
}

double HostTileListing::TileCeilingMm(
  const float tipGrid[3], int tileX, int tileY, std::uint32_t codeLo, std::uint32_t codeHi) const
{
  double best = std::numeric_limits<double>::infinity();
  for (const std::uint32_t code : { codeLo, codeHi })
  {
    const int px = tileX * TilePx + static_cast<int>(code & 7u);
    const int py = tileY * TilePx + static_cast<int>((code >> 3) & 7u);
    const double slice = static_cast<double>(code >> TilePixelBits);
    const double dx = AxisGap(tipGrid[0], px, px + 1) * this->PixelMm;
    const double dy = AxisGap(tipGrid[1], py, py + 1) * this->PixelMm;
    const double dz = AxisGap(tipGrid[2], slice, slice + 1.0) * this->SliceMm;
    best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  return best;
}

void HostTileListing::List(const float tipGrid[3], int cls, double ceilingMm, std::uint32_t entryEnd,
  std::uint32_t coarseCount, double searchMm, std::vector<std::uint32_t>& entries) const
{
  double best = Raised(std::min(searchMm, ceilingMm));
  double beyond2 = Beyond2(best);
  const int centreX = ClampedTile(tipGrid[0], this->TilesX);
  const int centreY = ClampedTile(tipGrid[1], this->TilesY);
  const int acrossX = (this->TilesX + CoarseTiles - 1) / CoarseTiles;
  const int acrossY = (this->TilesY + CoarseTiles - 1) / CoarseTiles;
  const std::size_t tiles = static_cast<std::size_t>(this->TilesX) * static_cast<std::size_t>(this->TilesY);
  const std::size_t fineWords = 2 * static_cast<std::size_t>(this->Classes) * tiles;
  const std::size_t coarseTiles = static_cast<std::size_t>(acrossX) * static_cast<std::size_t>(acrossY);
  const std::uint32_t end = std::min(entryEnd, this->FineEntries);
  const int width = 2 * this->Reach + 1;
  const std::size_t count = std::min<std::size_t>(coarseCount, this->Coarse.size());
  for (std::size_t c = 0; c < count; ++c)
  {
    if (this->CoarseGapMm[c] > best)
    {
      break; // and every coarse tile after it
    }
    const int coarseX = centreX / CoarseTiles + this->Coarse[c][0];
    const int coarseY = centreY / CoarseTiles + this->Coarse[c][1];
    if (coarseX < 0 || coarseY < 0 || coarseX >= acrossX || coarseY >= acrossY)
    {
      continue;
    }
    const std::size_t t = fineWords +
      2 * (static_cast<std::size_t>(cls) * coarseTiles + static_cast<std::size_t>(coarseY) * acrossX + coarseX);
    const std::uint32_t coarseLo = this->Ranges[t], coarseHi = this->Ranges[t + 1];
    if (coarseLo > coarseHi ||
      BoxGap2(tipGrid, coarseX * TilePx * CoarseTiles, coarseY * TilePx * CoarseTiles, TilePx * CoarseTiles,
        coarseLo >> CoarsePixelBits, coarseHi >> CoarsePixelBits) > beyond2)
    {
      continue; // empty, or no tile of it nearer than the best
    }
    for (int k = 0; k < CoarseTiles * CoarseTiles; ++k)
    {
      const int tileX = coarseX * CoarseTiles + k % CoarseTiles, tileY = coarseY * CoarseTiles + k / CoarseTiles;
      const int ox = tileX - centreX, oy = tileY - centreY;
      if (std::abs(ox) > this->Reach || std::abs(oy) > this->Reach || tileX >= this->TilesX || tileY >= this->TilesY)
      {
        continue; // beyond the range, or the grid
      }
      const std::uint32_t entry = this->EntryOf[static_cast<std::size_t>((oy + this->Reach) * width + ox + this->Reach)];
      if (entry >= end)
      {
        continue;
      }
      const std::size_t f = 2 * (static_cast<std::size_t>(cls) * tiles + static_cast<std::size_t>(tileY) * this->TilesX + tileX);
      const std::uint32_t codeLo = this->Ranges[f], codeHi = this->Ranges[f + 1];
      if (codeLo > codeHi ||
        BoxGap2(tipGrid, tileX * TilePx, tileY * TilePx, TilePx, codeLo >> TilePixelBits, codeHi >> TilePixelBits) > beyond2)
      {
        continue;
      }
      const double ceiling = Raised(this->TileCeilingMm(tipGrid, tileX, tileY, codeLo, codeHi));
      if (ceiling < best)
      {
        best = ceiling;
        beyond2 = Beyond2(best);
      }
      entries.push_back(entry);
    }
  }
}
} // namespace vp
