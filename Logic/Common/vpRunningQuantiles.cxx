#include "vpRunningQuantiles.h"

#include <algorithm>
#include <cmath>

namespace vp
{
namespace
{
const double LogStep = std::log1p(RunningQuantiles::RelativeResolution);
const std::size_t BinCount =
  static_cast<std::size_t>(std::ceil(std::log(RunningQuantiles::HighestValue / RunningQuantiles::LowestValue) / LogStep)) + 1;

// Bin k holds (LowestValue (1+r)^(k-1), LowestValue (1+r)^k]; bin 0 everything up to LowestValue.
std::size_t BinOf(double value)
{
  if (!(value > RunningQuantiles::LowestValue))
  {
    return 0;
  }
  const double k = std::ceil(std::log(value / RunningQuantiles::LowestValue) / LogStep);
  return std::min(BinCount - 1, static_cast<std::size_t>(k));
}
} // namespace

void RunningQuantiles::Add(double value)
{
  if (this->Bins.empty())
  {
    this->Bins.assign(BinCount, 0);
    this->Smallest = this->Largest = value;
  }
  ++this->Bins[BinOf(value)];
  ++this->Total;
  this->Smallest = std::min(this->Smallest, value);
  this->Largest = std::max(this->Largest, value);
}

double RunningQuantiles::Quantile(double q) const
{
  if (this->Total == 0)
  {
    return 0.0;
  }
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(this->Total)));
  const std::uint64_t wanted = std::max<std::uint64_t>(1, std::min(rank, this->Total));
  if (wanted == this->Total)
  {
    return this->Largest;
  }
  std::uint64_t seen = 0;
  for (std::size_t k = 0; k < this->Bins.size(); ++k)
  {
    seen += this->Bins[k];
    if (seen >= wanted)
    {
      // The bin's upper edge, widened by a rounding of the log so it is never below its values.
      const double edge = LowestValue * std::exp(static_cast<double>(k) * LogStep) * (1.0 + 1e-12);
      return std::clamp(edge, this->Smallest, this->Largest);
    }
  }
  return this->Largest;
}
} // namespace vp
