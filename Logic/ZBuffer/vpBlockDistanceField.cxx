#include "vpBlockDistanceField.h"

#include "vpMemory.h"
#include "vpSquaredDistanceTransform.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

/// In place along one line: each value becomes the least of itself and its two neighbours.
void MinimumOfNeighbours(double* f, std::size_t stride, int n, std::vector<double>& values)
{
  values.resize(n);
  for (int i = 0; i < n; ++i)
  {
    values[i] = f[i * stride];
  }
  for (int i = 0; i < n; ++i)
  {
    double m = values[i];
    if (i > 0)
    {
      m = std::min(m, values[i - 1]);
    }
    if (i + 1 < n)
    {
      m = std::min(m, values[i + 1]);
    }
    f[i * stride] = m;
  }
}

/// The squared Euclidean distance transform of the padded block grid (P blocks, layout stride),
/// one axis after the other, edgeMm a block's edge along each.
void SquaredDistanceAlongAxes(std::vector<double>& field, const int P[3], const std::size_t stride[3], const double edgeMm[3])
{
  vp::SquaredDistanceTransform transform;
  std::vector<double> line;
  for (int axis = 0; axis < 3; ++axis)
  {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int j = 0; j < P[b]; ++j)
    {
      for (int i = 0; i < P[a]; ++i)
      {
        double* first = field.data() + i * stride[a] + j * stride[b];
        line.resize(P[axis]);
        for (int q = 0; q < P[axis]; ++q)
        {
          line[q] = first[q * stride[axis]];
        }
        transform.Line(line.data(), P[axis], edgeMm[axis]);
        for (int q = 0; q < P[axis]; ++q)
        {
          first[q * stride[axis]] = line[q];
        }
      }
    }
  }
}

/// Each block's value becomes the least over its 27 neighbours (one axis at a time).
void MinimumOverNeighbours(std::vector<double>& field, const int P[3], const std::size_t stride[3])
{
  std::vector<double> values;
  for (int axis = 0; axis < 3; ++axis)
  {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int j = 0; j < P[b]; ++j)
    {
      for (int i = 0; i < P[a]; ++i)
      {
        MinimumOfNeighbours(field.data() + i * stride[a] + j * stride[b], stride[axis], P[axis], values);
      }
    }
  }
}

/// A block's gap and the point's distance to the blocks' box: the lower bound.
double Lower(double gap, double outside)
{
  return std::max(outside, gap - outside);
}

/// And the upper: the gap plus the diagonals of the two blocks.
double Upper(double gap, double outside, double diagonal)
{
  // The float gap may lie a rounding below the true one; the cells' coverage tolerance (a
  // thousandth of a cell each side) is well inside the 1e-3 diagonal added.
  return outside + gap * (1.0 + 1e-6) + 2.0 * diagonal * 1.001 + 1e-4;
}
} // namespace

namespace vp
{
BlockDistanceField::BlockDistanceField(
  const DepthLayerGrid& grid, int classes, const std::vector<std::uint32_t>& occupancy, double blockMm)
  : Grid(grid)
  , Classes(classes)
{
  const std::size_t words = static_cast<std::size_t>(grid.Words());
  if (occupancy.size() < grid.Pixels() * words * static_cast<std::size_t>(classes))
  {
    throw std::invalid_argument("vp::BlockDistanceField: the occupancy does not hold every class's layers");
  }
  this->Cells = std::max(1, static_cast<int>(std::floor(blockMm / std::max(grid.PixelMm, grid.SliceMm) + 1e-9)));
  const int n[3] = { grid.Nx, grid.Ny, grid.Nz };
  const double cellMm[3] = { grid.PixelMm, grid.PixelMm, grid.SliceMm };
  for (int k = 0; k < 3; ++k)
  {
    this->Dims[k] = (n[k] + this->Cells - 1) / this->Cells;
    this->EdgeMm[k] = this->Cells * cellMm[k];
  }
  // Padded by one block on every side: the neighbours' minimum reads there.
  const int P[3] = { this->Dims[0] + 2, this->Dims[1] + 2, this->Dims[2] + 2 };
  const std::size_t padded = static_cast<std::size_t>(P[0]) * P[1] * P[2];
  const std::size_t blocks = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  vp::AssignOnHugePages(this->Gaps, blocks * classes, std::numeric_limits<float>::infinity());
  this->Marked.assign(classes, 0);
  std::vector<double> field;
  auto at = [&](int x, int y, int zz) { return (static_cast<std::size_t>(zz) * P[1] + y) * P[0] + x; };
  for (int c = 0; c < classes; ++c)
  {
    field.assign(padded, Inf);
    for (int y = 0; y < grid.Ny; ++y)
    {
      for (int x = 0; x < grid.Nx; ++x)
      {
        const std::uint32_t* column =
          occupancy.data() + (static_cast<std::size_t>(c) * grid.Pixels() + static_cast<std::size_t>(y) * grid.Nx + x) * words;
        for (std::size_t w = 0; w < words; ++w)
        {
          for (std::uint32_t bits = column[w]; bits != 0u; bits &= bits - 1u)
          {
            const int slice = static_cast<int>(w * 32) + __builtin_ctz(bits);
            double& cell = field[at(x / this->Cells + 1, y / this->Cells + 1, slice / this->Cells + 1)];
            if (cell != 0.0)
            {
              cell = 0.0;
              ++this->Marked[c];
            }
          }
        }
      }
    }
    if (this->Marked[c] == 0)
    {
      continue;
    }
    const std::size_t stride[3] = { 1, static_cast<std::size_t>(P[0]), static_cast<std::size_t>(P[0]) * P[1] };
    SquaredDistanceAlongAxes(field, P, stride, this->EdgeMm);
    MinimumOverNeighbours(field, P, stride);
    for (int zz = 0; zz < this->Dims[2]; ++zz)
    {
      for (int y = 0; y < this->Dims[1]; ++y)
      {
        for (int x = 0; x < this->Dims[0]; ++x)
        {
          // Rounded down to a float: still a lower bound.
          const double d = std::sqrt(field[at(x + 1, y + 1, zz + 1)]);
          float f = static_cast<float>(d);
          if (static_cast<double>(f) > d)
          {
            f = std::nextafter(f, 0.0f);
          }
          this->Gaps[((static_cast<std::size_t>(zz) * this->Dims[1] + y) * this->Dims[0] + x) * classes + c] = f;
        }
      }
    }
  }
}

const float* BlockDistanceField::GapsAt(const double p[3], double& outsideMm) const
{
  // Outside the blocks' box, the point is at least its distance to the box from every marked
  // cell, and at least the gap of the box point nearest it less that distance.
  int index[3];
  double outside2 = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const double u = (p[k] - this->Grid.OriginMm[k]) / this->EdgeMm[k];
    double clamped = u;
    if (u < 0.0)
    {
      clamped = 0.0;
    }
    else if (u >= this->Dims[k])
    {
      clamped = this->Dims[k];
    }
    const double gapMm = (u - clamped) * this->EdgeMm[k];
    outside2 += gapMm * gapMm;
    index[k] = std::min(this->Dims[k] - 1, std::max(0, static_cast<int>(std::floor(clamped))));
  }
  outsideMm = std::sqrt(outside2);
  return this->Gaps.data() +
    ((static_cast<std::size_t>(index[2]) * this->Dims[1] + index[1]) * this->Dims[0] + index[0]) * this->Classes;
}

void BlockDistanceField::Prefetch(const double p[3]) const
{
  double outside = 0.0;
  __builtin_prefetch(this->GapsAt(p, outside));
}

double BlockDistanceField::DiagonalMm() const
{
  return std::sqrt(this->EdgeMm[0] * this->EdgeMm[0] + this->EdgeMm[1] * this->EdgeMm[1] + this->EdgeMm[2] * this->EdgeMm[2]);
}

void BlockDistanceField::BoundsMm(const double p[3], double* lowerMm, double* upperMm) const
{
  double outside = 0.0;
  const float* gaps = this->Classes > 0 ? this->GapsAt(p, outside) : nullptr;
  const double diagonal = this->DiagonalMm();
  for (int c = 0; c < this->Classes; ++c)
  {
    const bool none = this->Marked[c] == 0;
    lowerMm[c] = none ? Inf : Lower(gaps[c], outside);
    upperMm[c] = none ? Inf : Upper(gaps[c], outside, diagonal);
  }
}

double BlockDistanceField::LowerBoundMm(int cls, const double p[3]) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    return Inf;
  }
  double outside = 0.0;
  const double gap = this->GapsAt(p, outside)[cls];
  return Lower(gap, outside);
}

double BlockDistanceField::UpperBoundMm(int cls, const double p[3]) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    return Inf;
  }
  double outside = 0.0;
  const double gap = this->GapsAt(p, outside)[cls];
  return Upper(gap, outside, this->DiagonalMm());
}

bool BlockDistanceField::StepTowardMarked(int cls, double p[3]) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    return false;
  }
  int index[3];
  for (int k = 0; k < 3; ++k)
  {
    const double u = (p[k] - this->Grid.OriginMm[k]) / this->EdgeMm[k];
    if (!(u >= 0.0 && u < this->Dims[k]))
    {
      return false;
    }
    index[k] = static_cast<int>(u);
  }
  auto gapAt = [&](int x, int y, int z) {
    return this->Gaps[((static_cast<std::size_t>(z) * this->Dims[1] + y) * this->Dims[0] + x) * this->Classes + cls];
  };
  float lowest = gapAt(index[0], index[1], index[2]);
  if (lowest == 0.0f)
  {
    return false;
  }
  int best[3] = { -1, -1, -1 };
  for (int dz = -1; dz <= 1; ++dz)
  {
    for (int dy = -1; dy <= 1; ++dy)
    {
      for (int dx = -1; dx <= 1; ++dx)
      {
        const int j[3] = { index[0] + dx, index[1] + dy, index[2] + dz };
        if (j[0] < 0 || j[1] < 0 || j[2] < 0 || j[0] >= this->Dims[0] || j[1] >= this->Dims[1] || j[2] >= this->Dims[2])
        {
          continue;
        }
        const float g = gapAt(j[0], j[1], j[2]);
        if (g < lowest)
        {
          lowest = g;
          best[0] = j[0];
          best[1] = j[1];
          best[2] = j[2];
        }
      }
    }
  }
  if (best[0] < 0)
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    p[k] = this->Grid.OriginMm[k] + (best[k] + 0.5) * this->EdgeMm[k];
  }
  return true;
}
} // namespace vp
