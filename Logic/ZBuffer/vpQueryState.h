#ifndef vpQueryState_h
#define vpQueryState_h

#include "vpDepthLayerGrid.h"
#include "vpZBufferShaderLayout.h"

#include <cstdint>

namespace vp
{
namespace zbuffer
{
// A point and class's answer, as the query leaves it in its state words (QueryProximityCommon.glsl):
// [1] the ray's parity, [2] the directional distance, [3] the chosen record (all ones: none within
// the search), [4] its cell's distance, [5] its pixel, [6] its depth in slices, [8...] the
// paper's distance bits.

/// The float whose bits a state word holds.
float Bits(std::uint32_t word);

/// The query's parameters for a search of searchMm on the grid, the order table's entries and
/// the distance bits (bins over binWidth each; 0: none); the stage and entry fields are the
/// caller's.
QueryParameters MakeQueryParameters(const DepthLayerGrid& grid, double searchMm, double binWidth, int bins,
  std::uint32_t orderCount, bool paper, std::uint32_t classes, int directionalLanes);

/// The chosen cell's distance, mm; infinite when nothing lies within the search.
double ChosenCellMm(const std::uint32_t* state);

/// The distance the answer reports: the nearest marked cell is at most a cell diagonal nearer
/// than the surface it holds, so its distance plus half a diagonal is within half a diagonal of
/// the truth; with the paper's bits on, the middle of the first bin set instead.
double ReportedDistanceMm(const std::uint32_t* state, double cellMm, double halfDiagonalMm, int bins, double binWidthMm);

/// The point of the chosen cell nearest the tip across its pixel, at the cell's depth.
void ClosestPointInChosenCell(const DepthLayerGrid& grid, const double* tip, const std::uint32_t* state, double point[3]);
} // namespace zbuffer
} // namespace vp

#endif
