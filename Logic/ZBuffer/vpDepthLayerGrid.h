#ifndef vpDepthLayerGrid_h
#define vpDepthLayerGrid_h

#include <cstddef>

namespace vp
{
/// The z-buffer engine's region box and its cells: an orthographic view along +z (LPS S) with
/// square pixels of PixelMm in x and y and depth slices of SliceMm along z. A cell is one pixel's
/// footprint times one slice.
///
/// The error bound follows from what the layers keep: every cell that holds vessel surface is
/// marked and no other, so the distance from the tip to the nearest marked cell is within one cell
/// diagonal below the true distance; reporting it plus half a diagonal leaves half a diagonal
/// either way.
struct DepthLayerGrid
{
  double OriginMm[3] = { 0.0, 0.0, 0.0 }; // the box's lowest corner
  double PixelMm = 0.4;
  double SliceMm = 0.4;
  int Nx = 0;
  int Ny = 0;
  int Nz = 0;

  int Words() const { return (this->Nz + 31) / 32; }
  /// Tiles of TilePx pixels across and along (SummarizeTiles.comp).
  static constexpr int TilePx = 8;
  int TilesX() const { return (this->Nx + TilePx - 1) / TilePx; }
  int TilesY() const { return (this->Ny + TilePx - 1) / TilePx; }
  std::size_t Pixels() const { return static_cast<std::size_t>(this->Nx) * static_cast<std::size_t>(this->Ny); }
  double SizeMm(int axis) const { return (axis < 2 ? this->PixelMm : this->SliceMm) * (axis == 0 ? this->Nx : axis == 1 ? this->Ny : this->Nz); }

  /// Half the cell diagonal.
  double HalfDiagonalMm() const;
  /// |reported - exact| is at most this: half a cell diagonal, widened by the rasteriser's coverage
  /// tolerance (1e-3 cell each side, which absorbs float rounding), plus half a distance bin when
  /// binWidthMm > 0.
  double ErrorBoundMm(double binWidthMm = 0.0) const;

  /// The box around bounds (xmin, xmax, ymin, ymax, zmin, zmax) with marginMm added on every side.
  static DepthLayerGrid Covering(const double bounds[6], double pixelMm, double sliceMm, double marginMm);
  /// A box of sizeMm centred on centre, its corner on the lattice of cells through anchor (so
  /// every box of the moving mode shares one lattice).
  static DepthLayerGrid Centred(const double centre[3], const double sizeMm[3], double pixelMm, double sliceMm,
    const double anchor[3]);
  /// Whether the ball of radiusMm around centre lies inside the box.
  bool ContainsBall(const double centre[3], double radiusMm) const;
};
} // namespace vp

#endif
