#include "vpExactComparison.h"

#include <algorithm>
#include <cmath>

namespace vp
{
bool WithinErrorBound(const ClassProximity& answer, const ClassProximity& exact, double rangeMm, double boundMm)
{
  if (exact.InRange && answer.InRange)
  {
    return std::abs(answer.DistanceMm - exact.DistanceMm) <= boundMm;
  }
  // Near the range's edge either may fall beyond it: within the bound of the edge, that agrees.
  if (exact.InRange)
  {
    return exact.DistanceMm >= rangeMm - boundMm;
  }
  return !answer.InRange || answer.DistanceMm <= rangeMm + boundMm;
}

void ExactComparison::Add(const ProximityResult& answer, const ProximityResult& exact, double rangeMm, double boundMm,
  std::vector<char>* within)
{
  for (std::size_t c = 0; c < exact.Classes.size(); ++c)
  {
    const ClassProximity& a = answer.Classes[c];
    const ClassProximity& e = exact.Classes[c];
    if (a.InRange && e.InRange)
    {
      ++this->Compared;
      this->MaxAbsDifferenceMm = std::max(this->MaxAbsDifferenceMm, std::abs(a.DistanceMm - e.DistanceMm));
    }
    const bool ok = WithinErrorBound(a, e, rangeMm, boundMm);
    this->OutsideBound += ok ? 0 : 1;
    if (within)
    {
      within->push_back(ok ? 1 : 0);
    }
  }
}
} // namespace vp
