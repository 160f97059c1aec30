#ifndef vpTileOrder_h
#define vpTileOrder_h

#include <array>
#include <cstdint>
#include <vector>

namespace vp
{
/// Offsets from a centre tile, nearest first: by the least distance from any point of the centre
/// tile (the square root of the first of the pair, in tiles), then from the centre. The query
/// visits a tip's tiles in this order, so that its running best shrinks early and far tiles skip
/// their work. Reach: the tiles within the range, and no more than the grid is wide (so a range
/// of 1e9 mm asks for no more); GapMm: each offset's least distance, ascending, so that a shorter
/// search needs a prefix.
struct TileOrder
{
  std::vector<std::array<std::int32_t, 2>> Offsets;
  std::vector<double> GapMm;
  int Reach = 0;

  /// The entries within searchMm of any tip in the centre tile: a prefix of the table.
  std::uint32_t Within(double searchMm) const;
};

/// The order of the tiles within rangeMm, for tiles of edgePx pixels of pixelMm, on a grid
/// tilesAcross tiles wide at most.
TileOrder NearestFirst(double rangeMm, double edgePx, double pixelMm, int tilesAcross);

/// Coarse tiles across a row of tiles (zbuffer::CoarseTiles of them each).
int CoarseAcross(int tiles);
} // namespace vp

#endif
