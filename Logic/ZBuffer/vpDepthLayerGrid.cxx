#include "vpDepthLayerGrid.h"

#include "vpInputError.h"

#include <algorithm>
#include <cmath>

namespace vp
{
double DepthLayerGrid::HalfDiagonalMm() const
{
  return 0.5 * std::sqrt(2.0 * this->PixelMm * this->PixelMm + this->SliceMm * this->SliceMm);
}

double DepthLayerGrid::ErrorBoundMm(double binWidthMm) const
{
  // The rasteriser widens each cell by 1e-3 cell on every side; the query's float arithmetic in
  // grid units adds well under 1e-4 mm for boxes up to a metre.
  return this->HalfDiagonalMm() * 1.002 + 1e-4 + (binWidthMm > 0.0 ? 0.5 * binWidthMm : 0.0);
}

namespace
{
/// Cells along an axis, counted in double before they become an int: a cell of 1e-8 mm asked
/// for more cells than an int holds, and the size estimate built from it overflowed.
int CellsAlong(double cells)
{
  constexpr double MaxCells = 1 << 20;
  if (!(std::ceil(cells) <= MaxCells))
  {
    throw ParameterError("CellSizeMm", "the layers would have " + NumberText(std::ceil(cells), 3) +
        " cells along one axis, more than " + std::to_string(static_cast<long>(MaxCells)) + ": use larger cells");
  }
  return std::max(1, static_cast<int>(std::ceil(cells)));
}
} // namespace

DepthLayerGrid DepthLayerGrid::Covering(const double bounds[6], double pixelMm, double sliceMm, double marginMm)
{
  DepthLayerGrid g;
  g.PixelMm = pixelMm;
  g.SliceMm = sliceMm;
  const double cell[3] = { pixelMm, pixelMm, sliceMm };
  int* n[3] = { &g.Nx, &g.Ny, &g.Nz };
  for (int k = 0; k < 3; ++k)
  {
    const double lo = bounds[2 * k] - marginMm;
    const double hi = bounds[2 * k + 1] + marginMm;
    *n[k] = CellsAlong((hi - lo) / cell[k]);
    // Centre the cells on the bounds.
    g.OriginMm[k] = 0.5 * (lo + hi) - 0.5 * (*n[k]) * cell[k];
  }
  return g;
}

DepthLayerGrid DepthLayerGrid::Centred(const double centre[3], const double sizeMm[3], double pixelMm, double sliceMm,
  const double anchor[3])
{
  DepthLayerGrid g;
  g.PixelMm = pixelMm;
  g.SliceMm = sliceMm;
  const double cell[3] = { pixelMm, pixelMm, sliceMm };
  int* n[3] = { &g.Nx, &g.Ny, &g.Nz };
  for (int k = 0; k < 3; ++k)
  {
    *n[k] = CellsAlong(sizeMm[k] / cell[k]);
    const double corner = centre[k] - 0.5 * (*n[k]) * cell[k];
    g.OriginMm[k] = anchor[k] + std::round((corner - anchor[k]) / cell[k]) * cell[k];
  }
  return g;
}

bool DepthLayerGrid::ContainsBall(const double c[3], double r) const
{
  for (int k = 0; k < 3; ++k)
  {
    if (c[k] - r < this->OriginMm[k] || c[k] + r > this->OriginMm[k] + this->SizeMm(k))
    {
      return false;
    }
  }
  return true;
}
} // namespace vp
