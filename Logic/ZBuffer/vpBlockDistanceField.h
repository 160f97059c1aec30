#ifndef vpBlockDistanceField_h
#define vpBlockDistanceField_h

#include "vpDepthLayerGrid.h"

#include <cstdint>
#include <vector>

namespace vp
{
/// Per vessel class, a lower bound on the distance from any point to the cells the z-buffer
/// marked, cheap enough to ask for every point of an instrument at every pose: it tells the
/// whole-instrument search which of the instrument's points can still be the nearest, so that
/// only those go to the GPU.
///
/// The grid's cells are grouped into cubic blocks of BlockCells() cells a side; a block is marked
/// when it holds a marked cell. Each block keeps the gap from its box to the nearest marked
/// block's box (0 for a marked block and its neighbours): every point of the block is at least that
/// far from every marked cell. Built once per rendering of the layers, in linear time: the squared
/// Euclidean distance transform between block centres (Felzenszwalb and Huttenlocher's lower
/// envelope, one axis at a time) followed by a minimum over the 27 neighbours, since the gap
/// between two blocks per axis, max(0, |i - j| - 1) blocks, is the least of |i + e - j| over e in
/// {-1, 0, 1}.
class BlockDistanceField
{
public:
  BlockDistanceField() = default;
  /// occupancy: the layers' bits, [class][pixel][word] (vtkZBufferVesselDistance::CopyOccupancy).
  /// blockMm: the wanted block edge; the block is a whole number of cells, at least one.
  BlockDistanceField(const DepthLayerGrid& grid, int classes, const std::vector<std::uint32_t>& occupancy, double blockMm);

  /// At most the distance from p (mm) to the nearest marked cell of class cls; +infinity when the
  /// class has none.
  double LowerBoundMm(int cls, const double p[3]) const;
  /// At least the distance from p (mm) to class cls's surface: the gap plus the diagonals of the
  /// two blocks (a marked block holds surface); +infinity when the class has none.
  double UpperBoundMm(int cls, const double p[3]) const;
  /// Both bounds for every class at once (NumberOfClasses() values each): the classes' gaps of a
  /// block lie side by side, so a batch's random tips cost one cache miss each, not one a class.
  void BoundsMm(const double p[3], double* lowerMm, double* upperMm) const;
  /// Asks the memory for p's block ahead of BoundsMm(p): a batch prefetches a few tips ahead, so
  /// that their cache misses overlap instead of following one another.
  void Prefetch(const double p[3]) const;
  /// Moves p to the centre of the neighbouring block with the least gap when that is less than
  /// p's block's: a step toward the marked cells (the gap falls with every step until it is 0).
  /// False when p is outside the blocks' box, its gap is 0, or no neighbour is nearer.
  bool StepTowardMarked(int cls, double p[3]) const;
  int BlockCells() const { return this->Cells; }
  int NumberOfClasses() const { return this->Classes; }
  /// Marked blocks of class cls.
  std::size_t MarkedBlocks(int cls) const { return this->Marked[cls]; }
  std::size_t MemoryBytes() const { return this->Gaps.size() * sizeof(float); }

private:
  /// The classes' gaps of the block nearest p (mm), and p's distance to the blocks' box.
  const float* GapsAt(const double p[3], double& outsideMm) const;
  double DiagonalMm() const;

  DepthLayerGrid Grid;
  int Classes = 0;
  int Cells = 1;
  int Dims[3] = { 0, 0, 0 };
  double EdgeMm[3] = { 0, 0, 0 };
  std::vector<std::size_t> Marked;
  std::vector<float> Gaps; // [z][y][x][class], mm
};
} // namespace vp

#endif
