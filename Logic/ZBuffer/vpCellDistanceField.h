#ifndef vpCellDistanceField_h
#define vpCellDistanceField_h

#include "vpBlockDistanceField.h"
#include "vpDepthLayerGrid.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vp
{
/// Per vessel class, the distance from any point to the vessel's surface as the z-buffer's
/// layers hold it, in constant time: two bounds from one byte. What lets the whole instrument's
/// every sample be asked at every pose, with no GPU round trip per sample.
///
/// The field's cells are the layers' cells (or cubes of k x k x k of them when the box holds more
/// than maxCellsPerClass cells; a field cell is marked when one of its cells is). Each keeps the
/// Euclidean distance D from its centre to the nearest marked cell's centre, exact (three passes
/// of vp::SquaredDistanceTransform) and rounded down to a level: levels an eighth of the smallest
/// cell edge apart up to 16 edges (6.4 mm for 0.4 mm cells, where danger is decided), half an edge
/// apart beyond, up to ReachMm() = 79.5 edges (31.8 mm). Built once per rendering of the layers,
/// in time linear in the cells, one class at a time.
///
/// Bounds: every marked cell holds surface and all the surface in the box lies in marked cells,
/// so for p in a cell at t from its centre, with E the cell's half diagonal (widened by the
/// rasteriser's coverage tolerance) and D's level between L and the next, L':
///   L - t - E  <=  d(p, surface)  <=  L' + t + E.
/// Beyond the reach, a coarse vp::BlockDistanceField (blocks of farBlockMm) gives both bounds,
/// wider by about two block diagonals.
/// The field's box is the layers' padded by 16 of their cells (6.4 mm for 0.4 mm cells) on every
/// side; outside it (where every vessel is more than that away), with q the nearest box point at o
/// from p: sqrt(o^2 + low(q)^2) <= d(p, surface) <= o + high(q).
class CellDistanceField
{
public:
  CellDistanceField() = default;
  /// occupancy: the layers' bits, [class][pixel][word] (vtkZBufferVesselDistance::CopyOccupancy);
  /// crossings: their crossing bits in the same layout (CopyCrossings), or empty when Inside()
  /// is not wanted; crossingHalves and crossingQuarters: in which quarter of its slice each lies
  /// (CopyCrossingPlaces), or empty.
  CellDistanceField(const DepthLayerGrid& grid, int classes, const std::vector<std::uint32_t>& occupancy,
    const std::vector<std::uint32_t>& crossings, const std::vector<std::uint32_t>& crossingHalves,
    const std::vector<std::uint32_t>& crossingQuarters, std::size_t maxCellsPerClass = std::size_t(1) << 26,
    double farBlockMm = 1.6);

  /// Bounds on the distance from p (mm) to class cls's surface; both +infinity when the class
  /// has none.
  void Bounds(int cls, const double p[3], double& lowMm, double& highMm) const;
  /// Whether p is inside class cls as the layers decide it: the parity of the pixel-centre ray's
  /// crossings below p's slice, and inside when one lies in p's own slice (undecided: the more
  /// dangerous side), as the z-buffer's tip query decides. Right wherever p is farther than a
  /// cell's diagonal from the surface. Outside the layers' box, false (every vessel lies in it).
  /// False for every point when the field was built without crossings.
  bool Inside(int cls, const double p[3]) const;
  bool HasInside() const { return !this->InsideBits.empty(); }
  /// The share of the segment of length 2 halfDepthMm about p along z (the layers' depth axis)
  /// that is inside class cls, as the layers say: a slice wholly inside counts whole, one outside
  /// not at all, and a slice the surface crosses up to or from its crossing, placed at the middle
  /// of its quarter (within an eighth of a slice; half the slice where the places are not known).
  /// Inside() counts a crossed slice whole, the safe side for one point; for a volume that is a
  /// bias of half a slice across every wall. 0 without crossings.
  double InsideShare(int cls, const double p[3], double halfDepthMm) const;
  /// The layers' grid the field was built from.
  const DepthLayerGrid& GetLayerGrid() const { return this->Layers; }

  /// A point of the marked cell nearest p (the point of that cell closest to p), found by
  /// descending the field from p's cell; false when p is outside the box or beyond the reach, or
  /// the descent stalls on the rounding (the caller then asks the layers).
  bool NearestMarkedPoint(int cls, const double p[3], double pointMm[3]) const;

  /// Distances up to this are held to a cell; beyond, only to the coarse blocks.
  double ReachMm() const { return this->LevelMm(255); }
  /// Distances up to this are held to an eighth of a cell edge (u).
  double FineReachMm() const { return this->LevelMm(128); }
  /// The largest half width of Bounds() within the fine reach and the box: E + h + u / 2.
  double BoundMm() const;
  /// Layer cells per field cell along each axis (k).
  int LayerCellsPerCell() const { return this->K; }
  const double* CellMm() const { return this->EdgeMm; }
  int NumberOfClasses() const { return this->Classes; }
  std::size_t MemoryBytes() const
  {
    return this->Values.size() +
      (this->InsideBits.size() + this->CrossingBits.size() + this->CrossingHalfBits.size() + this->CrossingQuarterBits.size()) *
      sizeof(std::uint32_t) +
      this->Far.MemoryBytes();
  }

private:
  /// The distance a stored value stands for, and the value of a distance (rounded down).
  double LevelMm(int v) const;
  std::uint8_t Quantise(double d) const;
  /// The cell holding p, clamped to the box; its centre; p's distance to the box.
  std::size_t CellOf(const double p[3], int index[3], double centre[3], double& outsideMm) const;

  double OriginMm[3] = { 0, 0, 0 }; // the field's lowest corner: the layers' box padded
  int Classes = 0;
  int K = 1;
  int Dims[3] = { 0, 0, 0 };
  double EdgeMm[3] = { 0, 0, 0 };
  double UnitMm = 0.0;
  double HalfDiagonalMm = 0.0; // E: the half diagonal with the coverage tolerance
  std::vector<std::size_t> Marked;
  std::vector<std::uint8_t> Values; // [class][y][x][z]: D / u rounded down, 255 beyond the reach
  DepthLayerGrid Layers;
  std::vector<std::uint32_t> InsideBits; // [class][pixel][word] of the layers: Inside() per cell
  std::vector<std::uint32_t> CrossingBits; // the same layout: the surface crosses the cell
  std::vector<std::uint32_t> CrossingHalfBits, CrossingQuarterBits; // and in which quarter
  BlockDistanceField Far;
};
} // namespace vp

#endif
