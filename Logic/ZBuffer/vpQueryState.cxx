#include "vpQueryState.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace vp
{
namespace zbuffer
{
float Bits(std::uint32_t u)
{
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

QueryParameters MakeQueryParameters(const DepthLayerGrid& g, double searchMm, double binWidth, int bins,
  std::uint32_t orderCount, bool paper, std::uint32_t classes, int directionalLanes)
{
  QueryParameters q{};
  q.PixelMm = static_cast<float>(g.PixelMm);
  q.SliceMm = static_cast<float>(g.SliceMm);
  q.RangeMm = static_cast<float>(searchMm);
  q.HalfDiagonalMm = static_cast<float>(g.HalfDiagonalMm());
  q.BinWidthMm = static_cast<float>(binWidth);
  q.Bins = binWidth > 0.0 ? bins : 0;
  q.Nx = g.Nx;
  q.Ny = g.Ny;
  q.Nz = g.Nz;
  q.Words = g.Words();
  q.TilesX = g.TilesX();
  q.TilesY = g.TilesY();
  q.OrderCount = static_cast<std::int32_t>(orderCount);
  q.PaperMode = paper ? 1 : 0;
  q.RangeStride = static_cast<std::uint32_t>(g.Pixels()) * classes;
  q.Classes = static_cast<std::int32_t>(classes);
  q.DirectionalLanes = directionalLanes;
  return q;
}

double ChosenCellMm(const std::uint32_t* state)
{
  return state[3] == 0xFFFFFFFFu ? std::numeric_limits<double>::infinity() : Bits(state[4]);
}

double ReportedDistanceMm(const std::uint32_t* state, double cellMm, double halfDiagonalMm, int bins, double binWidthMm)
{
  for (int bin = 0; bin < bins; ++bin)
  {
    if (state[8 + bin / 32] & (1u << (bin % 32)))
    {
      return (bin + 0.5) * binWidthMm;
    }
  }
  return cellMm + halfDiagonalMm;
}

void ClosestPointInChosenCell(const DepthLayerGrid& g, const double* tip, const std::uint32_t* state, double point[3])
{
  const std::uint32_t pixel = state[5];
  const int px = static_cast<int>(pixel % static_cast<std::uint32_t>(g.Nx));
  const int py = static_cast<int>(pixel / static_cast<std::uint32_t>(g.Nx));
  const auto clamp = [](double x, double lo, double hi) { return std::min(std::max(x, lo), hi); };
  point[0] = clamp(tip[0], g.OriginMm[0] + px * g.PixelMm, g.OriginMm[0] + (px + 1) * g.PixelMm);
  point[1] = clamp(tip[1], g.OriginMm[1] + py * g.PixelMm, g.OriginMm[1] + (py + 1) * g.PixelMm);
  point[2] = g.OriginMm[2] + Bits(state[6]) * g.SliceMm;
}
} // namespace zbuffer
} // namespace vp
