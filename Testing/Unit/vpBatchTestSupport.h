#ifndef vpBatchTestSupport_h
#define vpBatchTestSupport_h

// Batched queries must answer exactly as single ones: shared by the engines' tests.
#include "vtkVesselDistanceEngine.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace vp
{
namespace test
{
/// Bitwise equality of two doubles (so that 0.0 and -0.0, or two NaNs, are told apart honestly).
inline bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Every field of every class of two answers for the same tip equal, bit for bit. Returns how many
/// class answers were in range in both.
inline int ExpectSameAnswer(const ProximityResult& b, const ProximityResult& single, const std::string& what)
{
  EXPECT_TRUE(SameBits(b.ErrorBoundMm, single.ErrorBoundMm)) << what;
  EXPECT_EQ(b.Classes.size(), single.Classes.size()) << what;
  int inRange = 0;
  for (std::size_t c = 0; c < single.Classes.size() && c < b.Classes.size(); ++c)
  {
    const ClassProximity& x = b.Classes[c];
    const ClassProximity& y = single.Classes[c];
    const std::string where = what + " class " + y.ClassName;
    EXPECT_EQ(x.ClassName, y.ClassName) << where;
    EXPECT_EQ(x.InRange, y.InRange) << where;
    EXPECT_EQ(x.Inside, y.Inside) << where;
    EXPECT_EQ(x.InsideUncertain, y.InsideUncertain) << where;
    EXPECT_EQ(x.DirectionalMm.has_value(), y.DirectionalMm.has_value()) << where;
    if (x.DirectionalMm && y.DirectionalMm)
    {
      EXPECT_TRUE(SameBits(*x.DirectionalMm, *y.DirectionalMm)) << where;
    }
    if (!y.InRange || !x.InRange)
    {
      continue;
    }
    ++inRange;
    EXPECT_TRUE(SameBits(x.DistanceMm, y.DistanceMm)) << where << ": " << x.DistanceMm << " vs " << y.DistanceMm;
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_TRUE(SameBits(x.ClosestPoint[k], y.ClosestPoint[k])) << where;
    }
    EXPECT_EQ(x.TriangleId, y.TriangleId) << where;
  }
  return inRange;
}

/// A turning axis for tip i.
inline std::array<double, 3> TurningAxis(std::size_t i)
{
  const double a = 0.37 * static_cast<double>(i);
  return { std::cos(a), std::sin(a), 0.5 };
}

/// Every tip through ComputeProximityBatch at once and through ComputeProximity one by one, each
/// with its own axis (a turning one): every field of every class equal, bit for bit. Returns how
/// many class answers were in range (a test can insist that there were some).
inline int ExpectBatchEqualsSingles(vtkVesselDistanceEngine* engine, const std::vector<std::array<double, 3>>& tips,
  const std::string& what)
{
  std::vector<std::array<double, 3>> axes;
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    axes.push_back(TurningAxis(i));
  }
  std::vector<ProximityResult> batch;
  engine->ComputeProximityBatch(tips, &axes, batch);
  EXPECT_EQ(batch.size(), tips.size()) << what;
  int inRange = 0;
  for (std::size_t i = 0; i < tips.size() && i < batch.size(); ++i)
  {
    ProximityResult single;
    engine->ComputeProximity(tips[i].data(), axes[i].data(), single);
    inRange += ExpectSameAnswer(batch[i], single, what + " tip " + std::to_string(i));
  }
  return inRange;
}
} // namespace test
} // namespace vp

#endif
