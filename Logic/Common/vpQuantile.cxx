#include "vpQuantile.h"

#include <algorithm>
#include <cmath>

namespace vp
{
double Quantile(std::vector<double> samples, double q)
{
  if (samples.empty())
  {
    return 0.0;
  }
  std::sort(samples.begin(), samples.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * samples.size()));
  return samples[std::min(samples.size() - 1, rank == 0 ? 0 : rank - 1)];
}
} // namespace vp
