#ifndef vpQuantile_h
#define vpQuantile_h

#include <vector>

namespace vp
{
/// The q-quantile of samples by the nearest-rank rule (q = 0.5: the median, 0.95: p95, 1: the
/// maximum): always one of the samples, never an interpolation. 0 for no samples.
double Quantile(std::vector<double> samples, double q);
} // namespace vp

#endif
