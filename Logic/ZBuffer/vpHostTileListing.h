#ifndef vpHostTileListing_h
#define vpHostTileListing_h

#include "vpTileOrder.h"

#include <array>
#include <cstdint>
#include <vector>

namespace vp
{
/// The tiles a few tips' answers have to visit, listed on the host as the device's listing stage
/// lists them (SelectAnswerTiles in Shaders/QueryProximity.comp: coarse tiles nearest first,
/// each tile that may hold a nearer cell listed and its ceiling lowering the best before the
/// next), so that a single tip's submission is one dispatch over its listed tiles: the device's
/// own listing is a dispatch more, and the order table without a list starts a workgroup for
/// every tile within the ceiling (thousands per tip), nearly all of which find nothing to do.
///
/// The list holds every tile the device's listing would list, and perhaps a few more: its tests
/// are the shader's, in double precision with margins above the float rounding on the side of
/// listing. A tile listed in excess is visited and gives no better distance, so the answers are
/// the device listing's, bit for bit.
class HostTileListing
{
public:
  /// The order tables as uploaded (the fine one's EntryOf index included).
  void SetTables(const TileOrder& fine, const TileOrder& coarse, const std::vector<std::uint32_t>& entryOf);
  /// The layers' tile ranges as SummarizeTiles.comp leaves them (per class the fine tiles, then
  /// per class the coarse tiles; two words each), and the grid's tiles and cells.
  void SetRanges(std::vector<std::uint32_t> words, int tilesX, int tilesY, int classes, double pixelMm, double sliceMm);
  bool HasRanges() const { return !this->Ranges.empty(); }

  /// Appends to entries the order table's entries answer (tip in grid units: pixels, pixels,
  /// slices; class cls) has to visit: within its ceiling (ceilingMm, and the entries below
  /// entryEnd) and the search (the coarse table's first coarseCount entries, searchMm).
  void List(const float tipGrid[3], int cls, double ceilingMm, std::uint32_t entryEnd, std::uint32_t coarseCount,
    double searchMm, std::vector<std::uint32_t>& entries) const;

private:
  /// The squared gap from the tip to a box of edgePx x edgePx pixels from firstPixel between
  /// slices lo and hi (the shader's BoxGapMm, squared).
  double BoxGap2(const float tipGrid[3], int firstPixelX, int firstPixelY, int edgePx, double lo, double hi) const;
  double TileCeilingMm(const float tipGrid[3], int tileX, int tileY, std::uint32_t codeLo, std::uint32_t codeHi) const;

  std::uint32_t FineEntries = 0; // the order table's length
  std::vector<std::array<std::int32_t, 2>> Coarse;
  std::vector<double> CoarseGapMm; // each coarse entry's gap, lowered as the tests below lower theirs
  std::vector<std::uint32_t> EntryOf;
  int Reach = 0;
  std::vector<std::uint32_t> Ranges;
  int TilesX = 0, TilesY = 0, Classes = 0;
  double PixelMm = 0.0, SliceMm = 0.0;
};
} // namespace vp

#endif
