#include "vpCellDistanceField.h"

#include "vpSquaredDistanceTransform.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <new>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
constexpr std::uint8_t Beyond = 255;
// Levels of an eighth of a cell up to 16 cells, then of half a cell up to 79.5 cells.
constexpr int NearLevels = 128;
constexpr double FarStep = 4.0;
// Float rounding of the squared distances and of the queries' arithmetic, well inside this.
constexpr double SlackMm = 1e-4;
// Layer cells of padding around the layers' box: 6.4 mm for 0.4 mm cells.
constexpr int PaddingLayerCells = 16;

/// The squared distance transform along one axis of a float grid, every line in parallel;
/// values above capMm2 become +infinity (they cannot end within the reach).
/// A large scratch array on transparent huge pages where the kernel offers them: the first touch
/// of 200 MB in 4 KiB pages took a third of a second on the test machine, most of a class's build.
template <typename T>
class LargeBuffer
{
public:
  explicit LargeBuffer(std::size_t n)
    : Size(n)
  {
    const std::size_t huge = std::size_t(2) << 20;
    const std::size_t bytes = (n * sizeof(T) + huge - 1) / huge * huge;
    this->Data = static_cast<T*>(std::aligned_alloc(huge, std::max(bytes, huge)));
    if (!this->Data)
    {
      throw std::bad_alloc();
    }
    madvise(this->Data, std::max(bytes, huge), MADV_HUGEPAGE); // advice only: ignored where unsupported
  }
  ~LargeBuffer() { std::free(this->Data); }
  LargeBuffer(const LargeBuffer&) = delete;
  LargeBuffer& operator=(const LargeBuffer&) = delete;
  T* begin() { return this->Data; }
  T* end() { return this->Data + this->Size; }
  T* data() { return this->Data; }
  T& operator[](std::size_t i) { return this->Data[i]; }
  const T& operator[](std::size_t i) const { return this->Data[i]; }
  std::size_t Size;
  T* Data;
};

void TransformAxis(LargeBuffer<float>& field, const int dims[3], const std::size_t stride[3], int axis,
  double spacingMm, double capMm2)
{
  // b, the inner of the two other axes, is z where it can be: neighbouring lines then share cache
  // lines (z is contiguous).
  const int a = axis == 2 ? 1 : 1 - axis, b = axis == 2 ? 0 : 2;
  const std::size_t lines = static_cast<std::size_t>(dims[a]) * dims[b];
  const int n = dims[axis];
  vtkSMPThreadLocal<vp::SquaredDistanceTransform> transforms;
  vtkSMPThreadLocal<std::vector<double>> buffers;
  vtkSMPTools::For(0, static_cast<vtkIdType>(lines), [&](vtkIdType begin, vtkIdType end) {
    vp::SquaredDistanceTransform& transform = transforms.Local();
    std::vector<double>& line = buffers.Local();
    line.resize(n);
    for (vtkIdType l = begin; l < end; ++l)
    {
      const std::size_t i = static_cast<std::size_t>(l) / dims[b];
      const std::size_t j = static_cast<std::size_t>(l) % dims[b];
      float* first = field.data() + i * stride[a] + j * stride[b];
      bool any = false;
      for (int q = 0; q < n; ++q)
      {
        line[q] = first[q * stride[axis]];
        any = any || line[q] != Inf;
      }
      if (!any)
      {
        continue;
      }
      transform.Line(line.data(), n, spacingMm);
      for (int q = 0; q < n; ++q)
      {
        first[q * stride[axis]] = line[q] > capMm2 ? std::numeric_limits<float>::infinity() : static_cast<float>(line[q]);
      }
    }
  });
}
/// Per column of words, bit z: the parity of the crossings below slice z, or a crossing in it.
std::vector<std::uint32_t> InsideParity(const std::vector<std::uint32_t>& crossings, std::size_t columns, std::size_t words)
{
  std::vector<std::uint32_t> insideBits(columns * words);
  vtkSMPTools::For(0, static_cast<vtkIdType>(columns), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType column = begin; column < end; ++column)
    {
      std::uint32_t carry = 0u; // the parity of every bit below this word, all bits set or none
      for (std::size_t w = 0; w < words; ++w)
      {
        const std::uint32_t bits = crossings[static_cast<std::size_t>(column) * words + w];
        std::uint32_t inclusive = bits; // bit z: the parity of bits 0..z of the word
        for (int shift = 1; shift < 32; shift *= 2)
        {
          inclusive ^= inclusive << shift;
        }
        inclusive ^= carry;
        insideBits[static_cast<std::size_t>(column) * words + w] = (inclusive ^ bits) | bits;
        carry = (inclusive >> 31) ? ~0u : 0u;
      }
    }
  });
  return insideBits;
}

/// 0 in field at every cell (K layer cells a side, pad cells of padding, layout stride) that
/// holds a marked layer cell of class c.
void MarkOccupiedCells(const vp::DepthLayerGrid& grid, const std::vector<std::uint32_t>& occupancy, int c, int K, int pad,
  const std::size_t stride[3], float* field)
{
  const std::size_t words = static_cast<std::size_t>(grid.Words());
  for (int y = 0; y < grid.Ny; ++y)
  {
    for (int x = 0; x < grid.Nx; ++x)
    {
      const std::uint32_t* column =
        occupancy.data() + (static_cast<std::size_t>(c) * grid.Pixels() + static_cast<std::size_t>(y) * grid.Nx + x) * words;
      const std::size_t base = (x / K + pad) * stride[0] + (y / K + pad) * stride[1] + pad;
      for (std::size_t w = 0; w < words; ++w)
      {
        for (std::uint32_t bits = column[w]; bits != 0u; bits &= bits - 1u)
        {
          const int slice = static_cast<int>(w * 32) + __builtin_ctz(bits);
          if (slice < grid.Nz)
          {
            field[base + slice / K] = 0.0f;
          }
        }
      }
    }
  }
}
} // namespace

namespace vp
{
CellDistanceField::CellDistanceField(const DepthLayerGrid& grid, int classes, const std::vector<std::uint32_t>& occupancy,
  const std::vector<std::uint32_t>& crossings, const std::vector<std::uint32_t>& crossingHalves,
  const std::vector<std::uint32_t>& crossingQuarters, std::size_t maxCellsPerClass, double farBlockMm)
  : Classes(classes)
  , Layers(grid)
  , Far(grid, classes, occupancy, farBlockMm)
{
  const std::size_t words = static_cast<std::size_t>(grid.Words());
  const std::size_t layerWords = grid.Pixels() * words * static_cast<std::size_t>(classes);
  if (occupancy.size() < layerWords || (!crossings.empty() && crossings.size() < layerWords))
  {
    throw std::invalid_argument("vp::CellDistanceField: the occupancy or the crossings do not hold every class's layers");
  }
  if (!crossings.empty())
  {
    // Per column, bit z: the parity of the crossings below slice z, or a crossing in it.
    this->InsideBits = InsideParity(crossings, grid.Pixels() * static_cast<std::size_t>(classes), words);
    this->CrossingBits.assign(crossings.begin(), crossings.begin() + static_cast<std::ptrdiff_t>(layerWords));
    if (crossingHalves.size() >= layerWords && crossingQuarters.size() >= layerWords)
    {
      const auto words = static_cast<std::ptrdiff_t>(layerWords);
      this->CrossingHalfBits.assign(crossingHalves.begin(), crossingHalves.begin() + words);
      this->CrossingQuarterBits.assign(crossingQuarters.begin(), crossingQuarters.begin() + words);
    }
  }
  const int n[3] = { grid.Nx, grid.Ny, grid.Nz };
  // Padded on every side: the layers' box ends two cells past the vessels, and a point just
  // outside it would otherwise get only the loose outside bounds.
  auto padding = [](int k) { return (PaddingLayerCells + k - 1) / k; };
  auto cells = [&](int k) {
    std::size_t count = 1;
    for (int a = 0; a < 3; ++a)
    {
      count *= static_cast<std::size_t>((n[a] + k - 1) / k + 2 * padding(k));
    }
    return count;
  };
  while (cells(this->K) > std::max<std::size_t>(maxCellsPerClass, 1))
  {
    ++this->K;
  }
  const double layerMm[3] = { grid.PixelMm, grid.PixelMm, grid.SliceMm };
  for (int a = 0; a < 3; ++a)
  {
    this->Dims[a] = (n[a] + this->K - 1) / this->K + 2 * padding(this->K);
    this->EdgeMm[a] = this->K * layerMm[a];
    this->OriginMm[a] = grid.OriginMm[a] - padding(this->K) * this->EdgeMm[a];
  }
  const int pad = padding(this->K);
  this->UnitMm = std::min({ this->EdgeMm[0], this->EdgeMm[1], this->EdgeMm[2] }) / 8.0;
  this->HalfDiagonalMm =
    0.5 * std::sqrt(this->EdgeMm[0] * this->EdgeMm[0] + this->EdgeMm[1] * this->EdgeMm[1] + this->EdgeMm[2] * this->EdgeMm[2]) *
      1.002 +
    SlackMm;
  const std::size_t count = cells(this->K);
  this->Values.assign(count * classes, Beyond);
  this->Marked.assign(classes, 0);
  // Layout [y][x][z], as the occupancy: the z lines are contiguous.
  const std::size_t stride[3] = { static_cast<std::size_t>(this->Dims[2]), static_cast<std::size_t>(this->Dims[0]) * this->Dims[2], 1 };
  const double reach = this->ReachMm() + 8.0 * this->UnitMm;
  const double capMm2 = reach * reach;
  LargeBuffer<float> field(count);
  for (int c = 0; c < classes; ++c)
  {
    std::fill(field.begin(), field.end(), std::numeric_limits<float>::infinity());
    MarkOccupiedCells(grid, occupancy, c, this->K, pad, stride, field.data());
    const std::size_t marked = static_cast<std::size_t>(std::count(field.begin(), field.end(), 0.0f));
    this->Marked[c] = marked;
    if (marked == 0)
    {
      continue;
    }
    for (int axis : { 2, 0, 1 })
    {
      TransformAxis(field, this->Dims, stride, axis, this->EdgeMm[axis], capMm2);
    }
    std::uint8_t* out = this->Values.data() + static_cast<std::size_t>(c) * count;
    vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        out[i] = this->Quantise(std::sqrt(static_cast<double>(field[i]))); // +infinity stays beyond
      }
    });
  }
}

double CellDistanceField::LevelMm(int v) const
{
  return v < NearLevels ? v * this->UnitMm : NearLevels * this->UnitMm + (v - NearLevels) * FarStep * this->UnitMm;
}

std::uint8_t CellDistanceField::Quantise(double d) const
{
  const double nearMm = NearLevels * this->UnitMm;
  const double v = d < nearMm ? std::floor(d / this->UnitMm) : NearLevels + std::floor((d - nearMm) / (FarStep * this->UnitMm));
  return v < Beyond ? static_cast<std::uint8_t>(v) : Beyond;
}

double CellDistanceField::BoundMm() const
{
  const double h = 0.5 * std::sqrt(this->EdgeMm[0] * this->EdgeMm[0] + this->EdgeMm[1] * this->EdgeMm[1] + this->EdgeMm[2] * this->EdgeMm[2]);
  return this->HalfDiagonalMm + h + 0.5 * this->UnitMm + SlackMm;
}

std::size_t CellDistanceField::CellOf(const double p[3], int index[3], double centre[3], double& outsideMm) const
{
  double outside2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double size = this->Dims[a] * this->EdgeMm[a];
    const double u = p[a] - this->OriginMm[a];
    const double clamped = std::min(std::max(u, 0.0), size);
    outside2 += (u - clamped) * (u - clamped);
    index[a] = std::min(this->Dims[a] - 1, std::max(0, static_cast<int>(std::floor(clamped / this->EdgeMm[a]))));
    centre[a] = this->OriginMm[a] + (index[a] + 0.5) * this->EdgeMm[a];
  }
  outsideMm = std::sqrt(outside2);
  return (static_cast<std::size_t>(index[1]) * this->Dims[0] + index[0]) * this->Dims[2] + index[2];
}

void CellDistanceField::Bounds(int cls, const double p[3], double& lowMm, double& highMm) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    lowMm = highMm = Inf;
    return;
  }
  int index[3];
  double centre[3];
  double outside = 0.0;
  const std::size_t cell = this->CellOf(p, index, centre, outside);
  // q: p moved into the box (p itself when inside).
  double q[3];
  double t2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = this->OriginMm[a], hi = lo + this->Dims[a] * this->EdgeMm[a];
    q[a] = std::min(std::max(p[a], lo), hi);
    t2 += (q[a] - centre[a]) * (q[a] - centre[a]);
  }
  const double t = std::sqrt(t2);
  const std::size_t count = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  const std::uint8_t v = this->Values[static_cast<std::size_t>(cls) * count + cell];
  double low, high;
  if (v != Beyond)
  {
    low = this->LevelMm(v) - t - this->HalfDiagonalMm;
    high = this->LevelMm(v + 1) + t + this->HalfDiagonalMm + SlackMm;
  }
  else
  {
    low = std::max(this->ReachMm() - t - this->HalfDiagonalMm, this->Far.LowerBoundMm(cls, q));
    high = this->Far.UpperBoundMm(cls, q);
  }
  low = std::max(0.0, low - SlackMm);
  lowMm = outside > 0.0 ? std::sqrt(outside * outside + low * low) : low;
  highMm = outside + high;
}

bool CellDistanceField::Inside(int cls, const double p[3]) const
{
  if (this->InsideBits.empty())
  {
    return false;
  }
  const DepthLayerGrid& g = this->Layers;
  const double u[3] = { (p[0] - g.OriginMm[0]) / g.PixelMm, (p[1] - g.OriginMm[1]) / g.PixelMm, (p[2] - g.OriginMm[2]) / g.SliceMm };
  if (!(u[0] >= 0.0 && u[1] >= 0.0 && u[2] >= 0.0 && u[0] < g.Nx && u[1] < g.Ny && u[2] < g.Nz))
  {
    return false;
  }
  const int x = static_cast<int>(u[0]), y = static_cast<int>(u[1]), z = static_cast<int>(u[2]);
  const std::size_t column = static_cast<std::size_t>(cls) * g.Pixels() + static_cast<std::size_t>(y) * g.Nx + x;
  return (this->InsideBits[column * g.Words() + static_cast<std::size_t>(z >> 5)] >> (z & 31)) & 1u;
}

double CellDistanceField::InsideShare(int cls, const double p[3], double halfDepthMm) const
{
  if (this->InsideBits.empty() || !(halfDepthMm > 0.0))
  {
    return 0.0;
  }
  const DepthLayerGrid& g = this->Layers;
  const double u[2] = { (p[0] - g.OriginMm[0]) / g.PixelMm, (p[1] - g.OriginMm[1]) / g.PixelMm };
  if (!(u[0] >= 0.0 && u[1] >= 0.0 && u[0] < g.Nx && u[1] < g.Ny))
  {
    return 0.0;
  }
  const std::size_t column =
    static_cast<std::size_t>(cls) * g.Pixels() + static_cast<std::size_t>(u[1]) * g.Nx + static_cast<std::size_t>(u[0]);
  const std::uint32_t* crossed = this->CrossingBits.data() + column * g.Words();
  const bool placed = !this->CrossingHalfBits.empty();
  const std::uint32_t* half = placed ? this->CrossingHalfBits.data() + column * g.Words() : nullptr;
  const std::uint32_t* quarter = placed ? this->CrossingQuarterBits.data() + column * g.Words() : nullptr;
  const double from = (p[2] - halfDepthMm - g.OriginMm[2]) / g.SliceMm;
  const double to = (p[2] + halfDepthMm - g.OriginMm[2]) / g.SliceMm;
  auto overlap = [&](double low, double high) { return std::max(0.0, std::min(to, high) - std::max(from, low)); };
  const int first = std::max(0, static_cast<int>(std::floor(from)));
  // Inside just below the first slice: the parity of the crossings below it.
  bool insideBelow = false;
  for (int w = 0; w < (first >> 5); ++w)
  {
    insideBelow ^= (__builtin_popcount(crossed[w]) & 1) != 0;
  }
  if (first & 31)
  {
    insideBelow ^= (__builtin_popcount(crossed[first >> 5] & ((1u << (first & 31)) - 1u)) & 1) != 0;
  }
  double share = 0.0;
  for (int z = first; z < g.Nz && z < to; ++z)
  {
    const auto word = static_cast<std::size_t>(z >> 5);
    const std::uint32_t bit = 1u << (z & 31);
    if (!(crossed[word] & bit))
    {
      share += insideBelow ? overlap(z, z + 1.0) : 0.0; // no crossing: the slice is as below it
      continue;
    }
    if (placed)
    {
      const double at = z + (((half[word] & bit) ? 2 : 0) + ((quarter[word] & bit) ? 1 : 0) + 0.5) / 4.0;
      share += insideBelow ? overlap(z, at) : overlap(at, z + 1.0);
    }
    else
    {
      share += 0.5 * overlap(z, z + 1.0);
    }
    insideBelow = !insideBelow;
  }
  return share / (to - from);
}

bool CellDistanceField::NearestMarkedPoint(int cls, const double p[3], double pointMm[3]) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    return false;
  }
  int index[3];
  double centre[3];
  double outside = 0.0;
  this->CellOf(p, index, centre, outside);
  const std::size_t count = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  const std::uint8_t* values = this->Values.data() + static_cast<std::size_t>(cls) * count;
  auto at = [&](const int i[3]) { return values[(static_cast<std::size_t>(i[1]) * this->Dims[0] + i[0]) * this->Dims[2] + i[2]]; };
  if (outside > 0.0)
  {
    return false;
  }
  std::uint8_t v = at(index);
  // Beyond the reach, the coarse blocks lead within it: their gap falls to 0 within a block of a
  // marked one, well inside the reach.
  double walker[3] = { p[0], p[1], p[2] };
  for (int steps = 0; v == Beyond; ++steps)
  {
    if (steps > 4096 || !this->Far.StepTowardMarked(cls, walker))
    {
      return false;
    }
    this->CellOf(walker, index, centre, outside);
    v = at(index);
  }
  // The walk must end no farther than the upper bound says the surface is.
  double low, high;
  this->Bounds(cls, p, low, high);
  // Each step toward the nearest marked cell shortens the distance to it; the rounding to u can
  // hide a step of less than u, so equal values are walked too, a bounded number of times.
  for (int steps = 0; v != 0; ++steps)
  {
    if (steps > 2 * Beyond)
    {
      return false;
    }
    int best[3] = { index[0], index[1], index[2] };
    std::uint8_t lowest = Beyond;
    double nearest = Inf;
    for (int dz = -1; dz <= 1; ++dz)
    {
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int j[3] = { index[0] + dx, index[1] + dy, index[2] + dz };
          if ((dx == 0 && dy == 0 && dz == 0) || j[0] < 0 || j[1] < 0 || j[2] < 0 || j[0] >= this->Dims[0] ||
            j[1] >= this->Dims[1] || j[2] >= this->Dims[2])
          {
            continue;
          }
          const std::uint8_t w = at(j);
          // Among equals, the one nearest p: the walk stays on p's side of a plateau.
          double d2 = 0.0;
          for (int a = 0; a < 3; ++a)
          {
            const double c = this->OriginMm[a] + (j[a] + 0.5) * this->EdgeMm[a] - p[a];
            d2 += c * c;
          }
          if (w < lowest || (w == lowest && d2 < nearest))
          {
            lowest = w;
            nearest = d2;
            best[0] = j[0];
            best[1] = j[1];
            best[2] = j[2];
          }
        }
      }
    }
    if (lowest > v)
    {
      return false;
    }
    v = lowest;
    index[0] = best[0];
    index[1] = best[1];
    index[2] = best[2];
  }
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = this->OriginMm[a] + index[a] * this->EdgeMm[a];
    pointMm[a] = std::min(std::max(p[a], lo), lo + this->EdgeMm[a]);
    d2 += (pointMm[a] - p[a]) * (pointMm[a] - p[a]);
  }
  return std::sqrt(d2) <= high;
}
} // namespace vp
