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
  /// A gap's square in tiles (gx² + gy², an integer) and, per such square, the entries whose
  /// square is no larger: Within() in constant time. A batch asks it for every tip and class, and
  /// a binary search over thousands of gaps, a mispredicted branch a step, was a quarter of the
  /// ceilings' time.
  std::vector<std::uint32_t> EntriesUpToSquare;
  double EdgePx = 0.0, PixelMm = 0.0;

  /// The entries within searchMm of any tip in the centre tile: a prefix of the table (those
  /// whose GapMm is at most searchMm; all of them for NaN, as std::upper_bound).
  std::uint32_t Within(double searchMm) const;
  /// The gap, in mm, of the entries whose squared gap in tiles is square (GapMm holds these).
  double GapOfSquare(std::int64_t square) const;
};

/// The order of the tiles within rangeMm, for tiles of edgePx pixels of pixelMm, on a grid
/// tilesAcross tiles wide at most.
TileOrder NearestFirst(double rangeMm, double edgePx, double pixelMm, int tilesAcross);

/// Coarse tiles across a row of tiles (zbuffer::CoarseTiles of them each).
int CoarseAcross(int tiles);
} // namespace vp

#endif
