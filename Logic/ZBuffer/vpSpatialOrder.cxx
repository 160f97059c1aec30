#include "vpSpatialOrder.h"

#include <vtkSMPTools.h>

#include <boost/sort/spreadsort/integer_sort.hpp>

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
constexpr int Bits = 10; // per axis: 30 bits of curve above 32 bits of index

/// v's low 10 bits spread to every third bit.
std::uint64_t Spread(std::uint64_t v)
{
  v &= 0x3FF;
  v = (v | (v << 16)) & 0x30000FF;
  v = (v | (v << 8)) & 0x300F00F;
  v = (v | (v << 4)) & 0x30C30C3;
  v = (v | (v << 2)) & 0x9249249;
  return v;
}
} // namespace

std::vector<std::uint32_t> SpatialOrder(
  const std::array<double, 3>* points, std::size_t count, const double originMm[3], double edgeMm)
{
  constexpr double Last = static_cast<double>((1 << Bits) - 1);
  std::vector<std::uint64_t> keys(count);
  vtkSMPTools::For(0, static_cast<vtkIdType>(count), [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      std::uint64_t curve = 0;
      for (int k = 0; k < 3; ++k)
      {
        // NaN lands in the first cube: the front ends refuse such points, and the order need
        // only stay a permutation.
        const double cube = std::floor((points[i][static_cast<std::size_t>(k)] - originMm[k]) / edgeMm);
        curve |= Spread(static_cast<std::uint64_t>(cube > 0.0 ? std::min(cube, Last) : 0.0)) << k;
      }
      keys[static_cast<std::size_t>(i)] = curve << 32 | static_cast<std::uint64_t>(i);
    }
  });
  // A radix sort: 20,000 keys in 0.33-0.41 ms here, where vtkSMPTools::Sort (TBB's, on both
  // cores) took 0.54-0.93 and std::sort 0.79-1.02; it is time before a batch's first submission.
  boost::sort::spreadsort::integer_sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(count);
  std::transform(keys.begin(), keys.end(), order.begin(), [](std::uint64_t key) { return static_cast<std::uint32_t>(key); });
  return order;
}
} // namespace vp
