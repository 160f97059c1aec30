#ifndef vpExactComparison_h
#define vpExactComparison_h

#include "vpProximityResult.h"

#include <vector>

namespace vp
{
/// The accuracy contract of one answer against the exact one: within boundMm when both are in
/// range; out of range when the exact one is, unless it lies within boundMm beyond the range.
bool WithinErrorBound(const ClassProximity& answer, const ClassProximity& exact, double rangeMm, double boundMm);

/// An engine's answers checked against the exact engine's, tip by tip: the largest difference
/// where both are in range, and the answers that break the accuracy contract above.
struct ExactComparison
{
  double MaxAbsDifferenceMm = 0.0;
  int Compared = 0;     ///< class answers in range in both
  int OutsideBound = 0; ///< class answers outside WithinErrorBound
  /// Adds one tip (the same classes in the same order); within, when given, receives one flag
  /// per class.
  void Add(const ProximityResult& answer, const ProximityResult& exact, double rangeMm, double boundMm,
    std::vector<char>* within = nullptr);
};
} // namespace vp

#endif
