#include "vpBlockDistanceField.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

/// In place along one line of n values spaced stride apart: d(p) = min_q f(q) + (s (p - q))^2
/// (Felzenszwalb and Huttenlocher 2012, the lower envelope of parabolas). Infinite f never wins.
void DistanceTransformLine(double* f, std::size_t stride, int n, double s, std::vector<double>& values,
  std::vector<int>& v, std::vector<double>& z)
{
  values.resize(n);
  v.resize(n);
  z.resize(n + 1);
  for (int i = 0; i < n; ++i)
  {
    values[i] = f[i * stride];
  }
  const double s2 = s * s;
  int k = -1;
  for (int q = 0; q < n; ++q)
  {
    if (values[q] == Inf)
    {
      continue;
    }
    double cut = -Inf;
    while (k >= 0)
    {
      const int r = v[k];
      cut = ((values[q] + s2 * q * q) - (values[r] + s2 * r * r)) / (2.0 * s2 * (q - r));
      if (cut > z[k])
      {
        break;
      }
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -Inf : cut;
    z[k + 1] = Inf;
  }
  if (k < 0)
  {
    return; // nothing finite on this line
  }
  int j = 0;
  for (int p = 0; p < n; ++p)
  {
    while (z[j + 1] < p)
    {
      ++j;
    }
    const double d = p - v[j];
    f[p * stride] = values[v[j]] + s2 * d * d;
  }
}

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
  this->GapMm.assign(blocks * classes, std::numeric_limits<float>::infinity());
  this->Marked.assign(classes, 0);
  std::vector<double> field;
  std::vector<double> values, z;
  std::vector<int> v;
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
    for (int axis = 0; axis < 3; ++axis)
    {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (int j = 0; j < P[b]; ++j)
      {
        for (int i = 0; i < P[a]; ++i)
        {
          double* line = field.data() + i * stride[a] + j * stride[b];
          DistanceTransformLine(line, stride[axis], P[axis], this->EdgeMm[axis], values, v, z);
        }
      }
    }
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
    float* gap = this->GapMm.data() + static_cast<std::size_t>(c) * blocks;
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
          gap[(static_cast<std::size_t>(zz) * this->Dims[1] + y) * this->Dims[0] + x] = f;
        }
      }
    }
  }
}

double BlockDistanceField::LowerBoundMm(int cls, const double p[3]) const
{
  if (this->Marked.empty() || this->Marked[cls] == 0)
  {
    return Inf;
  }
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
  const std::size_t blocks = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  const double gap = this->GapMm[static_cast<std::size_t>(cls) * blocks +
    (static_cast<std::size_t>(index[2]) * this->Dims[1] + index[1]) * this->Dims[0] + index[0]];
  const double outside = std::sqrt(outside2);
  return std::max(outside, gap - outside);
}
} // namespace vp
