#include "vpSquaredDistanceTransform.h"

#include <limits>

namespace vp
{
void SquaredDistanceTransform::Line(double* f, int n, double spacingMm)
{
  constexpr double Inf = std::numeric_limits<double>::infinity();
  std::vector<double>& values = this->Values;
  std::vector<int>& v = this->Parabolas;
  std::vector<double>& z = this->Cuts;
  values.assign(f, f + n);
  v.resize(n);
  z.resize(n + 1);
  const double s2 = spacingMm * spacingMm;
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
    f[p] = values[v[j]] + s2 * d * d;
  }
}
} // namespace vp
