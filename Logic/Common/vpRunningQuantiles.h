#ifndef vpRunningQuantiles_h
#define vpRunningQuantiles_h

#include <cstdint>
#include <vector>

namespace vp
{
/// Quantiles of a stream of positive values (frame times) in memory that does not grow with the
/// stream: a histogram of bins a RelativeResolution wide on a log scale, from LowestValue to
/// HighestValue (values outside fall in the end bins). Quantile(q) follows vp::Quantile's
/// nearest-rank rule but answers the upper edge of the bin holding that rank, clamped to the
/// smallest and largest value seen: never below the exact quantile, and above it by at most
/// RelativeResolution (0.1%). Quantile(1) is the largest value, exactly. 240 kB, allocated at the
/// first Add.
class RunningQuantiles
{
public:
  static constexpr double LowestValue = 1e-6;
  static constexpr double HighestValue = 1e7;
  static constexpr double RelativeResolution = 1e-3;

  void Add(double value);
  double Quantile(double q) const;
  std::uint64_t Count() const { return this->Total; }

private:
  std::vector<std::uint64_t> Bins;
  std::uint64_t Total = 0;
  double Smallest = 0.0;
  double Largest = 0.0;
};
} // namespace vp

#endif
