// The Vulkan z-buffer engine against the exact engine: on analytic shapes, on thin and stacked
// vessels that defeat the paper's literal method, and on the IRCADb vessel trees. Every distance
// must lie within the engine's stated error bound of the exact one.
#include "vpAnalyticShapes.h"
#include "vpBuiltInPhantom.h"
#include "vpDefectiveMeshes.h"
#include "vpSpatialOrder.h"
#include "vpTileOrder.h"
#include "vpVesselSurface.h"
#include "vpTestSupport.h"
#include "vpVulkanContext.h"
#include "vpVulkanTestSupport.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshReader.h"
#include "vtkZBufferVesselDistance.h"

#include <vtkAppendPolyData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>

#include "vpBatchTestSupport.h"

namespace
{
using Vessels = std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>>;

template <typename Engine>
vtkSmartPointer<Engine> Make(const Vessels& vessels, double rangeMm)
{
  auto e = vtkSmartPointer<Engine>::New();
  e->SetRangeMm(rangeMm);
  for (const auto& v : vessels)
  {
    e->AddVessel(v.first, v.second);
  }
  return e;
}

struct Agreement
{
  int Compared = 0;     // class answers in range of the exact engine
  int InsideChecked = 0;
  double MaxDifferenceMm = 0.0;
};

/// Asserts, for every tip and class, the accuracy contract: in range exactly when the exact
/// engine is (up to the bound), |zbuffer - exact| <= bound, and the same inside/outside answer
/// wherever the tip is further than a cell diagonal from the surface.
Agreement ExpectWithinBound(vtkZBufferVesselDistance* zbuffer, vtkExactVesselDistance* exact,
  const std::vector<std::array<double, 3>>& tips, const std::string& label)
{
  Agreement a;
  const double range = zbuffer->GetRangeMm();
  const double bound = zbuffer->GetErrorBoundMm();
  const double diagonal = 2.0 * zbuffer->GetGrid().HalfDiagonalMm();
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    vp::ProximityResult z, e;
    zbuffer->ComputeProximity(tips[i].data(), nullptr, z);
    exact->ComputeProximity(tips[i].data(), nullptr, e);
    EXPECT_DOUBLE_EQ(z.ErrorBoundMm, bound);
    for (std::size_t c = 0; c < e.Classes.size(); ++c)
    {
      const auto& zc = z.Classes[c];
      const auto& ec = e.Classes[c];
      const std::string where = label + " tip " + std::to_string(i) + " " + ec.ClassName;
      if (ec.InRange)
      {
        if (!zc.InRange)
        {
          // Beyond the range by its estimate: only where the truth lies within the bound of it.
          EXPECT_GE(ec.DistanceMm, range - bound) << where << ": exact " << ec.DistanceMm;
          continue;
        }
        ++a.Compared;
        const double diff = zc.DistanceMm - ec.DistanceMm;
        a.MaxDifferenceMm = std::max(a.MaxDifferenceMm, std::abs(diff));
        EXPECT_LE(std::abs(diff), bound) << where << ": zbuffer " << zc.DistanceMm << " exact " << ec.DistanceMm;
        // The closest point reported is within reach of the true one.
        double pd = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          pd += (zc.ClosestPoint[k] - tips[i][k]) * (zc.ClosestPoint[k] - tips[i][k]);
        }
        EXPECT_NEAR(std::sqrt(pd), ec.DistanceMm, bound + diagonal) << where;
        if (ec.Inside.has_value() && zc.Inside.has_value() && ec.DistanceMm > diagonal)
        {
          ++a.InsideChecked;
          EXPECT_EQ(zc.Inside, ec.Inside) << where << " at " << ec.DistanceMm << " mm";
        }
      }
      else if (zc.InRange)
      {
        // No invented distance: only a vessel just beyond the range may show, within the bound.
        EXPECT_LE(zc.DistanceMm, range + bound) << where;
      }
    }
  }
  return a;
}

std::vector<std::array<double, 3>> RandomTips(const double bounds[6], double marginMm, int count, unsigned seed)
{
  std::mt19937 random(seed);
  std::vector<std::array<double, 3>> tips(count);
  for (auto& t : tips)
  {
    for (int k = 0; k < 3; ++k)
    {
      t[k] = std::uniform_real_distribution<double>(bounds[2 * k] - marginMm, bounds[2 * k + 1] + marginMm)(random);
    }
  }
  return tips;
}

void VesselBounds(const Vessels& vessels, double bounds[6])
{
  for (int k = 0; k < 3; ++k)
  {
    bounds[2 * k] = 1e300;
    bounds[2 * k + 1] = -1e300;
  }
  for (const auto& v : vessels)
  {
    const double* b = v.second->GetBounds();
    for (int k = 0; k < 3; ++k)
    {
      bounds[2 * k] = std::min(bounds[2 * k], b[2 * k]);
      bounds[2 * k + 1] = std::max(bounds[2 * k + 1], b[2 * k + 1]);
    }
  }
}

/// One vessel class with two branches along x, radius 2 mm, one 10 mm above the other along the
/// view axis (z): the case where the paper's near/far cuboid fills the gap.
// Two engines that must give the same answers, compared (check) in each query setting: the
// default pass, the per-pixel pass, and the paper's mode with 64 distance bins.
void UnderEachQuerySetting(
  vtkZBufferVesselDistance* a, vtkZBufferVesselDistance* b, const std::function<void(const std::string&)>& check)
{
  check("exact intervals");
  for (vtkZBufferVesselDistance* e : { a, b })
  {
    e->SetQueryPass(vtkZBufferVesselDistance::QueryPassPerPixel);
  }
  check("per pixel");
  for (vtkZBufferVesselDistance* e : { a, b })
  {
    e->SetQueryPass(vtkZBufferVesselDistance::QueryPassByDevice);
    e->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
    e->SetDistanceBins(64);
  }
  check("paper mode, 64 bins");
}

// Every tip through both engines as one batch, each with its turning axis: every answer the
// same, bit for bit. Returns how many class answers were in range.
int ExpectSameBatches(vtkZBufferVesselDistance* a, vtkZBufferVesselDistance* b,
  const std::vector<std::array<double, 3>>& tips, const std::string& what)
{
  std::vector<std::array<double, 3>> axes;
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    axes.push_back(vp::test::TurningAxis(i));
  }
  std::vector<vp::ProximityResult> x, y;
  a->ComputeProximityBatch(tips, &axes, x);
  b->ComputeProximityBatch(tips, &axes, y);
  EXPECT_EQ(x.size(), y.size()) << what;
  int inRange = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i)
  {
    inRange += vp::test::ExpectSameAnswer(x[i], y[i], what + " tip " + std::to_string(i));
  }
  return inRange;
}

// The whole instrument's search (shorter than the range, no bins) of every tip through both
// engines, in exact intervals: every answer the same, in the order given. Returns how many class
// answers were in range.
int ExpectSameSearchesWithin(vtkZBufferVesselDistance* a, vtkZBufferVesselDistance* b,
  const std::vector<std::array<double, 3>>& tips, double searchMm)
{
  for (vtkZBufferVesselDistance* e : { a, b })
  {
    e->SetLayerMode(vtkZBufferVesselDistance::ExactIntervals);
    e->SetDistanceBins(0);
  }
  std::vector<vp::ProximityResult> x, y;
  a->ComputeProximityBatchWithin(tips, searchMm, x);
  b->ComputeProximityBatchWithin(tips, searchMm, y);
  EXPECT_EQ(x.size(), tips.size());
  EXPECT_EQ(y.size(), tips.size());
  int within = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size() && i < tips.size(); ++i)
  {
    EXPECT_EQ(x[i].Tip[0], tips[i][0]) << "tip " << i;
    within += vp::test::ExpectSameAnswer(x[i], y[i], "within " + std::to_string(searchMm) + " mm, tip " + std::to_string(i));
  }
  return within;
}

// The built-in vessels with the first one holed: its inside is voted on by the host.
Vessels BuiltInWithAHoledVessel()
{
  Vessels vessels = vp::MakeBuiltInVessels();
  const vp::VesselSurface closed(vessels[0].first, vessels[0].second);
  vessels[0].second = vp::test::DefectiveCopies(closed.PointArray(), closed.TriangleArray())[0].Mesh;
  return vessels;
}

Vessels StackedTubes()
{
  const double axis[3] = { 1, 0, 0 };
  const double low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 10 };
  vtkNew<vtkAppendPolyData> append;
  append->AddInputData(vp::MakeCappedCylinder(low, axis, 2.0, 60.0, 48));
  append->AddInputData(vp::MakeCappedCylinder(high, axis, 2.0, 60.0, 48));
  append->Update();
  return { { "portal_vein", vtkSmartPointer<vtkPolyData>(append->GetOutput()) } };
}
} // namespace

// The order table's prefix within a search, found in constant time from the squared gap, is
// std::upper_bound's over the gaps for every search: at each gap, a rounding either side of it,
// between gaps, beyond the last, below zero, infinite and NaN; on a table longer than the grid
// allows (reach clamped) and on tiles of a fractional edge.
TEST(TileOrder, WithinIsTheBinarySearchsPrefix)
{
  const vp::TileOrder tables[] = { vp::NearestFirst(50.0, 8.0, 0.4, 1000), vp::NearestFirst(50.0, 32.0, 0.4, 9),
    vp::NearestFirst(7.3, 8.0, 0.1337, 1000) };
  for (const vp::TileOrder& order : tables)
  {
    ASSERT_FALSE(order.GapMm.empty());
    auto expected = [&](double mm) {
      return static_cast<std::uint32_t>(std::upper_bound(order.GapMm.begin(), order.GapMm.end(), mm) - order.GapMm.begin());
    };
    std::vector<double> searches = { -1.0, -0.0, 0.0, 1e-300, std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::quiet_NaN(), 1e9, order.GapMm.back() * 2.0 };
    for (double gap : order.GapMm)
    {
      for (double mm : { gap, std::nextafter(gap, -1.0), std::nextafter(gap, 1e300), gap * 1.5 + 0.01 })
      {
        searches.push_back(mm);
      }
    }
    std::mt19937 random(3);
    std::uniform_real_distribution<double> anywhere(0.0, order.GapMm.back() * 1.1);
    for (int i = 0; i < 2000; ++i)
    {
      searches.push_back(anywhere(random));
    }
    for (double mm : searches)
    {
      ASSERT_EQ(order.Within(mm), expected(mm)) << "search " << mm << " mm";
    }
    EXPECT_EQ(order.Within(order.GapMm.back()), order.GapMm.size());
    EXPECT_LT(order.Within(0.0), order.GapMm.size());
  }
}

// The space order is a permutation along the Z-order curve: the eight corners of a cube of
// cubes come x first, then y, then z; points of one cube keep their given order; points beyond
// the 1,024 cubes (and NaN, and below the origin) go to the nearest, not wrapped around.
TEST(SpatialOrder, FollowsTheZOrderCurve)
{
  const double origin[3] = { 10.0, 20.0, 30.0 };
  std::vector<std::array<double, 3>> points;
  for (int corner = 7; corner >= 0; --corner) // given in reverse
  {
    points.push_back({ 10.0 + 2.0 * (corner & 1) + 0.5, 20.0 + 2.0 * ((corner >> 1) & 1) + 0.5, 30.0 + 2.0 * (corner >> 2) + 0.5 });
  }
  std::vector<std::uint32_t> order = vp::SpatialOrder(points.data(), points.size(), origin, 2.0);
  ASSERT_EQ(order.size(), 8u);
  for (std::uint32_t k = 0; k < 8; ++k)
  {
    EXPECT_EQ(order[k], 7 - k) << "corner " << k;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  points = { { 1e9, 20.5, 30.5 }, { 10.5, 20.5, 30.5 }, { -1e9, nan, 30.5 }, { 10.0 + 2.0 * 1023 + 0.5, 20.5, 30.5 },
    { 10.6, 20.6, 30.6 }, { 10.0 + 2.0 * 1022 + 0.5, 20.5, 30.5 } };
  order = vp::SpatialOrder(points.data(), points.size(), origin, 2.0);
  const std::vector<std::uint32_t> expected = { 1, 2, 4, 5, 0, 3 }; // the first cube in given order, then x
  EXPECT_EQ(order, expected);
  // Random points: a permutation, each step's curve position no lower than the one before.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> anywhere(-50.0, 250.0);
  points.clear();
  for (int i = 0; i < 5000; ++i)
  {
    points.push_back({ anywhere(random), anywhere(random), anywhere(random) });
  }
  order = vp::SpatialOrder(points.data(), points.size(), origin, 3.2);
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
  {
    ASSERT_EQ(sorted[i], i);
  }
  // Neighbours on the curve are near: at the median, a step along the order is a few cubes
  // (5,000 points in 94^3 cubes: some 17 mm between neighbours), in the given order two thirds
  // of the box.
  auto medianStep = [&](const std::vector<std::uint32_t>& o) {
    std::vector<double> steps;
    for (std::size_t i = 1; i < o.size(); ++i)
    {
      steps.push_back(std::sqrt(vp::Distance2(points[o[i]].data(), points[o[i - 1]].data())));
    }
    std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
    return steps[steps.size() / 2];
  };
  std::vector<std::uint32_t> given(points.size());
  for (std::uint32_t i = 0; i < given.size(); ++i)
  {
    given[i] = i;
  }
  const double givenStepMm = medianStep(given), orderStepMm = medianStep(order);
  EXPECT_GT(givenStepMm, 150.0);
  EXPECT_LT(orderStepMm, givenStepMm / 6.0);
}

// A batch in space order gives the answers of the same batch as given, bit for bit and in the
// order given: several submissions (with axes, under every query setting), a holed vessel's
// votes; a result put back in the wrong place would fail. The whole instrument's search keeps
// the order of its points (an octree's, already in space order).
TEST(ZBufferDistance, BatchInSpaceOrderGivesTheAnswersAsGiven)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = BuiltInWithAHoledVessel();
  double b[6];
  VesselBounds(vessels, b);
  auto spatial = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto given = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  EXPECT_EQ(spatial->GetBatchOrder(), vtkZBufferVesselDistance::BatchOrderSpatial);
  given->SetBatchOrder(vtkZBufferVesselDistance::BatchOrderAsGiven);
  EXPECT_THROW(given->SetBatchOrder(2), vp::InputError);
  EXPECT_EQ(given->GetBatchOrder(), vtkZBufferVesselDistance::BatchOrderAsGiven);
  vp::ProximityResult first;
  spatial->ComputeProximity(b, nullptr, first); // sets the capacity for the device
  given->ComputeProximity(b, nullptr, first);
  EXPECT_EQ(spatial->GetLastCallTimes().OrderMs, 0.0) << "a single tip is not ordered";
  const std::size_t capacity = spatial->GetBatchCapacity();
  const auto tips = RandomTips(b, 20.0, static_cast<int>(std::min<std::size_t>(3 * capacity + 37, 2000)), 47);
  ASSERT_GE(tips.size(), 2 * capacity) << "the test needs a batch of several submissions";
  int inRange = 0;
  UnderEachQuerySetting(spatial, given, [&](const std::string& what) {
    inRange += ExpectSameBatches(spatial, given, tips, what);
    EXPECT_GT(spatial->GetLastCallTimes().OrderMs, 0.0) << what;
    EXPECT_EQ(given->GetLastCallTimes().OrderMs, 0.0) << what;
    EXPECT_GT(spatial->GetLastCallTimes().Votes, 0u) << what << ": the holed vessel's inside is voted on";
  });
  EXPECT_GT(inRange, 3000);
  EXPECT_GT(ExpectSameSearchesWithin(spatial, given, tips, 12.0), 100);
  EXPECT_EQ(spatial->GetLastCallTimes().OrderMs, 0.0) << "the whole instrument's search keeps its octree's order";
}

TEST(ZBufferDistance, ReportsItsDevice)
{
  VP_REQUIRE_VULKAN();
  const auto devices = vp::VulkanContext::ListDevices();
  ASSERT_FALSE(devices.empty());
  auto z = vtkSmartPointer<vtkZBufferVesselDistance>::New();
  EXPECT_FALSE(z->GetDeviceName().empty());
  z->SetDeviceSelector("no-such-device-anywhere");
  EXPECT_THROW(z->GetDeviceName(), vp::DeviceError);
}

TEST(ZBufferDistance, WithinBoundOnTheAnalyticPhantom)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto e = Make<vtkExactVesselDistance>(vessels, 50.0);
  z->Build();
  EXPECT_LE(z->GetErrorBoundMm(), 0.5);
  double b[6];
  VesselBounds(vessels, b);
  const Agreement a = ExpectWithinBound(z, e, RandomTips(b, 10.0, 1000, 7), "phantom");
  EXPECT_GT(a.Compared, 2000);
  EXPECT_GT(a.InsideChecked, 1000);
  // The engine is approximate: a difference of zero everywhere would mean nothing was compared.
  EXPECT_GT(a.MaxDifferenceMm, 0.0);
}

// A batch (more tips than one submission holds, so several submissions, and a last one of another
// size) answers exactly as the tips one by one: in the default mode, the paper's mode with its
// distance bits, and with the moving box (tips one at a time, each possibly re-rendering).
TEST(ZBufferDistance, BatchEqualsSingleQueriesBitForBit)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  double b[6];
  VesselBounds(vessels, b);
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  vp::ProximityResult first;
  const double corner[3] = { b[0], b[2], b[4] };
  z->ComputeProximity(corner, nullptr, first); // the first query sets the capacity for the device
  ASSERT_GE(z->GetBatchCapacity(), 1u);
  const auto tips = RandomTips(b, 10.0, static_cast<int>(2 * z->GetBatchCapacity() + 37), 11);
  EXPECT_GT(vp::test::ExpectBatchEqualsSingles(z, tips, "exact intervals"), 500);
  z->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
  z->SetDistanceBins(64);
  EXPECT_GT(vp::test::ExpectBatchEqualsSingles(z, tips, "paper mode, 64 bins"), 500);
  auto moving = Make<vtkZBufferVesselDistance>(vessels, 30.0);
  moving->SetBoxMode(vtkZBufferVesselDistance::MovingWithTip);
  const std::vector<std::array<double, 3>> few(tips.begin(), tips.begin() + 20);
  EXPECT_GT(vp::test::ExpectBatchEqualsSingles(moving, few, "moving box"), 10);
}

// Two submissions in flight (the host reading one and writing the next while the device runs
// the other) give the answers of one, bit for bit: batches of several submissions and a part one
// (each under every query setting, with axes), the whole instrument's search, and a vessel with
// a hole, whose inside the host votes on while the next submission runs. Slots mixed up (points,
// ceilings, answers or dispatch sizes of the other submission) would fail here.
TEST(ZBufferDistance, TwoSubmissionsInFlightGiveTheAnswersOfOne)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = BuiltInWithAHoledVessel();
  double b[6];
  VesselBounds(vessels, b);
  auto two = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto one = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  EXPECT_EQ(two->GetSubmissionsInFlight(), 2);
  one->SetSubmissionsInFlight(1);
  EXPECT_THROW(one->SetSubmissionsInFlight(0), vp::InputError);
  EXPECT_THROW(one->SetSubmissionsInFlight(3), vp::InputError);
  EXPECT_EQ(one->GetSubmissionsInFlight(), 1);
  vp::ProximityResult first;
  two->ComputeProximity(b, nullptr, first); // sets the capacity for the device
  one->ComputeProximity(b, nullptr, first);
  two->BuildQueryCeilings();
  one->BuildQueryCeilings();
  const std::size_t capacity = two->GetBatchCapacity();
  ASSERT_GE(capacity, 1u);
  const auto tips = RandomTips(b, 20.0, static_cast<int>(std::min<std::size_t>(3 * capacity + 37, 2000)), 41);
  const std::size_t submissions = (tips.size() + capacity - 1) / capacity;
  ASSERT_GE(submissions, 2u) << "the test needs a batch of several submissions";
  int inRange = 0;
  UnderEachQuerySetting(two, one, [&](const std::string& what) {
    inRange += ExpectSameBatches(two, one, tips, what);
    const auto times = two->GetLastCallTimes();
    EXPECT_EQ(times.Submissions, submissions) << what;
    EXPECT_GT(times.Votes, 0u) << what << ": the holed vessel's inside is voted on";
  });
  EXPECT_GT(inRange, 3000);
  EXPECT_GT(ExpectSameSearchesWithin(two, one, tips, 12.0), 100);
}

// A call's device time by stage (GetLastCallTimes): listing, visiting and reducing together are
// the whole, stamp by stamp, over a batch of several submissions (its last one of 5 tips too);
// without a list its listing is nothing, with one it is work. A single tip stamps no stages
// (negative), only its whole time.
TEST(ZBufferDistance, DeviceTimeSplitsIntoItsStages)
{
  VP_REQUIRE_VULKAN();
  Vessels vessels = vp::MakeBuiltInVessels();
  double b[6];
  VesselBounds(vessels, b);
  auto engine = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  vp::ProximityResult single;
  engine->ComputeProximity(b, nullptr, single);
  const std::size_t capacity = engine->GetBatchCapacity();
  const auto tips = RandomTips(b, 20.0, static_cast<int>(std::min<std::size_t>(2 * capacity + 5, 1000)), 43);
  std::vector<vp::ProximityResult> answers;
  for (int listing : { vtkZBufferVesselDistance::TileListingOn, vtkZBufferVesselDistance::TileListingOff })
  {
    engine->SetTileListing(listing);
    engine->ComputeProximityBatch(tips, nullptr, answers);
    const auto t = engine->GetLastCallTimes();
    const std::string what = listing == vtkZBufferVesselDistance::TileListingOn ? "listed" : "not listed";
    if (t.DeviceMs < 0.0)
    {
      GTEST_SKIP() << "the device keeps no timestamps";
    }
    EXPECT_GE(t.Submissions, 2u) << what;
    EXPECT_GT(t.DeviceMs, 0.0) << what;
    EXPECT_GE(t.DeviceListingMs, 0.0) << what;
    EXPECT_GT(t.DeviceVisitingMs, 0.0) << what;
    EXPECT_GE(t.DeviceReducingMs, 0.0) << what;
    EXPECT_NEAR(t.DeviceListingMs + t.DeviceVisitingMs + t.DeviceReducingMs, t.DeviceMs, 1e-6 * t.DeviceMs + 1e-9) << what;
    if (listing == vtkZBufferVesselDistance::TileListingOn)
    {
      EXPECT_GT(t.DeviceListingMs, 0.0) << what;
    }
    else
    {
      // Two stamps with nothing between them: what a stamp costs (under the sanitizers and the
      // validation layer 2.4% of the device's time in CI, where 2% had been asked).
      EXPECT_LT(t.DeviceListingMs, 0.1 * t.DeviceMs) << what << ": two stamps, nothing between them";
    }
  }
  engine->SetTileListing(vtkZBufferVesselDistance::TileListingByDevice);
  engine->ComputeProximity(b, nullptr, single);
  const auto t = engine->GetLastCallTimes();
  EXPECT_EQ(t.Submissions, 1u);
  EXPECT_GT(t.DeviceMs, 0.0);
  EXPECT_LT(t.DeviceListingMs, 0.0);
  EXPECT_LT(t.DeviceVisitingMs, 0.0);
  EXPECT_LT(t.DeviceReducingMs, 0.0);
}

// The query's ceilings (the coarse blocks' bound, and the answer before plus the tip's move) cut
// the tiles a query dispatches, and change no answer, bit for bit: random tips one at a time
// (some beyond the range or the grid), a tracked approach (where the answer before sets the
// ceiling), batches, both passes, and the paper's mode with its bins. A ceiling below an answer
// would lose that answer's pixel and fail here.
TEST(ZBufferDistance, CeilingsCutTheDispatchAndChangeNoAnswer)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  double b[6];
  VesselBounds(vessels, b);
  auto with = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto without = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  without->SetQueryCeilings(false);
  ASSERT_TRUE(with->GetQueryCeilings());
  auto tips = RandomTips(b, 40.0, 120, 23);
  // An approach in 0.5 mm steps from 30 mm above the box to the middle of the first vessel.
  const double* v = vessels.front().second->GetBounds();
  const std::array<double, 3> end{ { 0.5 * (v[0] + v[1]), 0.5 * (v[2] + v[3]), 0.5 * (v[4] + v[5]) } };
  const std::array<double, 3> start{ { end[0] + 3.0, end[1] - 2.0, b[5] + 30.0 } };
  const int steps = static_cast<int>((start[2] - end[2]) / 0.5);
  for (int i = 0; i <= steps; ++i)
  {
    const double t = static_cast<double>(i) / steps;
    tips.push_back({ { start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1]), start[2] + t * (end[2] - start[2]) } });
  }
  std::size_t cut = 0, quarter = 0, dispatched = 0, inSearch = 0;
  int inRange = 0;
  auto compareOneByOne = [&](const std::string& what) {
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      const auto axis = vp::test::TurningAxis(i);
      vp::ProximityResult a, z;
      with->ComputeProximity(tips[i].data(), axis.data(), a);
      const std::size_t tiles = with->GetLastQueryTiles(), all = with->GetLastQueryTilesInRange();
      without->ComputeProximity(tips[i].data(), axis.data(), z);
      EXPECT_EQ(without->GetLastQueryTiles(), without->GetLastQueryTilesInRange()) << "no ceilings: the whole range";
      EXPECT_EQ(all, without->GetLastQueryTilesInRange());
      EXPECT_LE(tiles, all);
      inRange += vp::test::ExpectSameAnswer(a, z, what + " tip " + std::to_string(i));
      cut += tiles < all ? 1 : 0;
      quarter += tiles * 4 < all ? 1 : 0;
      dispatched += tiles;
      inSearch += all;
    }
  };
  UnderEachQuerySetting(with, without, [&](const std::string& what) {
    compareOneByOne(what + ", one by one");
    inRange += ExpectSameBatches(with, without, tips, what + ", batched");
  });
  EXPECT_GT(inRange, 2000);
  // The dispatch follows the farthest class a tip can reach, and the phantom's classes lie apart
  // (a tip near one is tens of millimetres from another). Measured: 204 of 708 queries cut, 15
  // under a quarter, 91% of the tiles dispatched in all.
  EXPECT_GT(cut, 150u);
  EXPECT_GT(quarter, 10u);
  EXPECT_LT(dispatched, inSearch * 19 / 20);

  // One class: a tip a few millimetres from a sphere dispatches a few tiles of the range's.
  const double centre[3] = { 5, -3, 2 };
  auto sphere = Make<vtkZBufferVesselDistance>({ { "hepatic_vein", vp::MakeSphere(centre, 10.0, 48, 96) } }, 50.0);
  vp::ProximityResult first;
  const double away[3] = { centre[0] - 30.0, centre[1], centre[2] };
  sphere->ComputeProximity(away, nullptr, first); // a rendering's first query builds no blocks
  EXPECT_EQ(sphere->GetLastQueryTiles(), sphere->GetLastQueryTilesInRange());
  EXPECT_EQ(sphere->GetCeilingBuildTimeMs(), 0.0);
  for (double gap : { 0.5, 2.0, 5.0 })
  {
    const double tip[3] = { centre[0] + 10.0 + gap, centre[1] + 0.3, centre[2] - 0.2 };
    vp::ProximityResult r;
    sphere->ComputeProximity(tip, nullptr, r);
    ASSERT_TRUE(r.Classes[0].InRange);
    EXPECT_NEAR(r.Classes[0].DistanceMm, gap, r.ErrorBoundMm + 0.05);
    EXPECT_LT(sphere->GetLastQueryTiles() * 5, sphere->GetLastQueryTilesInRange()) << "gap " << gap; // 25 of 225 measured
  }
}

// Two engines on the built-in phantom (at cellMm, or the default cell when 0): Listed lists the
// tiles it visits, Ordered visits the order table; Bounds is the vessels' box.
struct ListedAndOrdered
{
  vtkSmartPointer<vtkZBufferVesselDistance> Listed, Ordered;
  double Bounds[6];
};

ListedAndOrdered MakeListedAndOrdered(double rangeMm, double cellMm)
{
  const Vessels vessels = vp::MakeBuiltInVessels();
  ListedAndOrdered engines;
  VesselBounds(vessels, engines.Bounds);
  engines.Listed = Make<vtkZBufferVesselDistance>(vessels, rangeMm);
  engines.Ordered = Make<vtkZBufferVesselDistance>(vessels, rangeMm);
  for (vtkZBufferVesselDistance* e : { engines.Listed.Get(), engines.Ordered.Get() })
  {
    if (cellMm > 0.0)
    {
      e->SetCellSizeMm(cellMm);
    }
  }
  engines.Listed->SetTileListing(vtkZBufferVesselDistance::TileListingOn);
  engines.Ordered->SetTileListing(vtkZBufferVesselDistance::TileListingOff);
  return engines;
}

// A batch lists the tiles it has to visit before visiting them (SetTileListing): the list holds
// a few of the tiles the order table would dispatch, and the answers are those of the order
// table, bit for bit, one by one and batched, listed tiles visited per tile and per pixel, and in
// the paper's mode with its bins; whether a workgroup or an invocation lists each answer's tiles
// (SetListingPass; the invocation walks several directional lanes too), the invocation listing
// no more, or the host (a submission of 8 tips: every tile the invocation lists, and hardly
// more; a larger one does not fit its slot and is listed by the device).
// A tile left off the list that held an answer would fail here.
TEST(ZBufferDistance, ListedTilesAreFewAndChangeNoAnswer)
{
  VP_REQUIRE_VULKAN();
  using Z = vtkZBufferVesselDistance;
  double listedPerTip[2] = { 0.0, 0.0 };
  for (int pass : { Z::ListingPassPerWorkgroup, Z::ListingPassPerInvocation, Z::ListingPassOnHost })
  {
    const std::string passName =
      pass == Z::ListingPassPerWorkgroup ? "per workgroup" : (pass == Z::ListingPassOnHost ? "on the host" : "per invocation");
    // Plain pointers, not a structured binding: C++17 lambdas cannot capture one (clang refuses).
    const ListedAndOrdered engines = MakeListedAndOrdered(50.0, 0.0);
    vtkZBufferVesselDistance* listed = engines.Listed;
    vtkZBufferVesselDistance* ordered = engines.Ordered;
    EXPECT_THROW(listed->SetTileListing(3), vp::InputError);
    EXPECT_THROW(listed->SetListingPass(4), vp::InputError);
    listed->SetListingPass(pass);
    const auto tips = RandomTips(engines.Bounds, 40.0, 300, 29);
    // One full submission: what it lists per tip against what the order table dispatches.
    vp::ProximityResult first;
    listed->ComputeProximity(tips.front().data(), nullptr, first); // sets the capacity for the device
    const std::size_t submission = pass == Z::ListingPassOnHost ? 8 : listed->GetBatchCapacity();
    const std::vector<std::array<double, 3>> some(tips.begin(), tips.begin() + std::min(tips.size(), submission));
    std::vector<vp::ProximityResult> answers;
    listed->ComputeProximityBatch(some, nullptr, answers);
    double hostPerTip = 0.0;
    double& perTip = pass == Z::ListingPassOnHost ? hostPerTip : listedPerTip[pass == Z::ListingPassPerInvocation ? 1 : 0];
    perTip = static_cast<double>(listed->GetLastQueryTilesListed()) / static_cast<double>(some.size());
    if (pass == Z::ListingPassOnHost)
    {
      listed->SetListingPass(Z::ListingPassPerInvocation);
      listed->ComputeProximityBatch(some, nullptr, answers);
      const double invocation = static_cast<double>(listed->GetLastQueryTilesListed()) / static_cast<double>(some.size());
      EXPECT_GE(hostPerTip, invocation) << "the host lists every tile the invocation lists";
      // Measured: 68 tiles against 67 (its margins above the device's rounding let one more in).
      EXPECT_LE(hostPerTip, invocation * 1.05 + 2.0 / static_cast<double>(some.size())) << "and hardly more";
      listed->SetListingPass(pass);
    }
    const std::size_t dispatchedPerTip = listed->GetLastQueryTiles();
    ordered->ComputeProximityBatch(some, nullptr, answers);
    EXPECT_EQ(ordered->GetLastQueryTilesListed(), 0u);
    EXPECT_GT(perTip, 1.0) << passName;
    // Measured: 30 listed per tip of 2,691 dispatched.
    EXPECT_LT(perTip * 20.0, static_cast<double>(dispatchedPerTip)) << perTip << " listed per tip, " << passName;
    int inRange = 0;
    UnderEachQuerySetting(listed, ordered, [&](const std::string& what) {
      inRange += ExpectSameBatches(listed, ordered, tips, what + ", batched, " + passName);
      for (std::size_t i = 0; i < tips.size(); i += 7)
      {
        const auto axis = vp::test::TurningAxis(i);
        vp::ProximityResult one, other;
        listed->ComputeProximity(tips[i].data(), axis.data(), one);
        ordered->ComputeProximity(tips[i].data(), axis.data(), other);
        inRange += vp::test::ExpectSameAnswer(one, other, what + ", one by one, tip " + std::to_string(i) + ", " + passName);
      }
    });
    EXPECT_GT(inRange, 1000) << passName;
    listed->SetDirectionalLanes(5); // the lanes' shares walked one after another by the listing's invocation
    EXPECT_GT(ExpectSameBatches(listed, ordered, tips, "5 directional lanes, " + passName), 100);
  }
  EXPECT_LE(listedPerTip[1], listedPerTip[0] * 1.02) << "an answer's invocation lowers its best tile by tile";
}

// A few tips far beyond the grid (and some just past its faces) are listed on the host from the
// grid's edge tile, as the shader clamps its centre tile: out of range where the range ends
// before the vessels, the answers of the order table where it does not.
TEST(ZBufferDistance, HostListingTakesTipsFarBeyondTheGrid)
{
  VP_REQUIRE_VULKAN();
  const ListedAndOrdered engines = MakeListedAndOrdered(50.0, 0.0);
  vtkZBufferVesselDistance* listed = engines.Listed;
  vtkZBufferVesselDistance* ordered = engines.Ordered;
  listed->SetListingPass(vtkZBufferVesselDistance::ListingPassOnHost);
  const double* b = engines.Bounds;
  const double mid[3] = { (b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2 };
  std::vector<std::array<double, 3>> tips = { { 1e9, 0.0, 0.0 }, { -1e12, 1e12, -1e9 } };
  for (double out : { 5.0, 15.0, 25.0 })
  {
    tips.push_back({ b[0] - out, mid[1], mid[2] });
    tips.push_back({ mid[0], b[3] + out, mid[2] });
    tips.push_back({ mid[0], mid[1], b[5] + out });
  }
  int inRange = 0;
  for (const auto& tip : tips)
  {
    vp::ProximityResult one, other;
    listed->ComputeProximity(tip.data(), nullptr, one);
    ordered->ComputeProximity(tip.data(), nullptr, other);
    inRange += vp::test::ExpectSameAnswer(one, other, "tip " + std::to_string(tip[0]));
  }
  EXPECT_GT(inRange, 3) << "tips just past the faces are in range of some class";
  vp::ProximityResult far;
  listed->ComputeProximity(tips[0].data(), nullptr, far);
  for (const vp::ClassProximity& c : far.Classes)
  {
    EXPECT_FALSE(c.InRange) << c.ClassName;
  }
}

// The host lists from the tile ranges of the rendering it copied them from: an engine given other
// vessels and built again (its renderings counted from the start again) copies the new ones, and
// answers as a new engine does.
TEST(ZBufferDistance, HostListingFollowsTheVesselsAfterABuildAgain)
{
  VP_REQUIRE_VULKAN();
  const double centre[3] = { 5, -3, 2 };
  const Vessels sphere = { { "hepatic_vein", vp::MakeSphere(centre, 10.0, 48, 96) } };
  auto reused = Make<vtkZBufferVesselDistance>(vp::MakeBuiltInVessels(), 50.0);
  vp::ProximityResult before;
  reused->ComputeProximity(centre, nullptr, before); // lists on the host from the phantom's ranges
  reused->RemoveAllVessels();
  reused->AddVessel(sphere[0].first, sphere[0].second);
  auto fresh = Make<vtkZBufferVesselDistance>(sphere, 50.0);
  int inRange = 0;
  for (double gap : { 0.5, 3.0, 12.0 })
  {
    const double tip[3] = { centre[0] - 10.0 - gap, centre[1] + 0.2, centre[2] - 0.3 };
    vp::ProximityResult one, other;
    reused->ComputeProximity(tip, nullptr, one);
    fresh->ComputeProximity(tip, nullptr, other);
    inRange += vp::test::ExpectSameAnswer(one, other, "gap " + std::to_string(gap));
    ASSERT_TRUE(one.Classes[0].InRange);
    EXPECT_NEAR(one.Classes[0].DistanceMm, gap, one.ErrorBoundMm + 0.05);
  }
  EXPECT_EQ(inRange, 3);
}

TEST(ZBufferDistance, ListedTilesAtFineCellsChangeNoAnswer)
{
  // The listing finds its tiles through coarse tiles of 4 x 4: at 0.15 mm cells these are 4.8 mm
  // across, and with a 30 mm range the order table reaches less far than the grid is wide, so
  // some coarse tiles run past the table's reach and tips beyond the grid past its edge.
  VP_REQUIRE_VULKAN();
  const ListedAndOrdered engines = MakeListedAndOrdered(30.0, 0.15);
  vtkZBufferVesselDistance* listed = engines.Listed;
  vtkZBufferVesselDistance* ordered = engines.Ordered;
  const auto tips = RandomTips(engines.Bounds, 30.0, 400, 31);
  EXPECT_GT(ExpectSameBatches(listed, ordered, tips, "0.15 mm cells, batched"), 150);
  const vp::DepthLayerGrid g = listed->GetGrid();
  EXPECT_LT(30.0 / (8.0 * g.PixelMm) + 1.0, std::max(g.TilesX(), g.TilesY())) << "the table must reach less far than the grid";
}

TEST(ZBufferDistance, StackedBranchesStayApartOnlyInTheExactIntervalMode)
{
  VP_REQUIRE_VULKAN();
  const Vessels tubes = StackedTubes();
  auto exact = Make<vtkExactVesselDistance>(tubes, 50.0);
  auto z = Make<vtkZBufferVesselDistance>(tubes, 50.0);
  auto paper = Make<vtkZBufferVesselDistance>(tubes, 50.0);
  paper->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
  // Tips in the gap, 3 mm from either branch.
  for (double x : { -20.0, 0.0, 13.7 })
  {
    const double tip[3] = { x, 0.1, 5.0 };
    vp::ProximityResult e, zr, pr;
    exact->ComputeProximity(tip, nullptr, e);
    z->ComputeProximity(tip, nullptr, zr);
    paper->ComputeProximity(tip, nullptr, pr);
    ASSERT_NEAR(e.Classes[0].DistanceMm, 3.0, 0.01);
    EXPECT_NEAR(zr.Classes[0].DistanceMm, e.Classes[0].DistanceMm, zr.ErrorBoundMm);
    EXPECT_EQ(zr.Classes[0].Inside, std::optional<bool>(false));
    // The paper's cuboid column runs from the lower branch's bottom to the upper one's top and
    // swallows the tip: it reports contact where there are 3 mm of tissue.
    EXPECT_LT(pr.Classes[0].DistanceMm, 3.0 - 2.0 * pr.ErrorBoundMm) << "x " << x;
    EXPECT_LE(pr.Classes[0].DistanceMm, pr.ErrorBoundMm);
  }
}

TEST(ZBufferDistance, VesselsThinnerThanAPixelAreFound)
{
  VP_REQUIRE_VULKAN();
  // A vessel 0.1 mm across, a quarter of the default 0.4 mm cell, once lying across the view
  // (thinner than a slice along z) and once slanted through it.
  const double across[3] = { 1, 0.3, 0 }, slanted[3] = { 0.2, 1, 0.7 };
  const double c1[3] = { 0.13, 0.07, 0.11 }, c2[3] = { 20.05, -3.21, 4.02 };
  const Vessels thin = { { "flat", vp::MakeCappedCylinder(c1, across, 0.05, 30.0, 12) },
    { "slanted", vp::MakeCappedCylinder(c2, slanted, 0.05, 30.0, 12) } };
  auto z = Make<vtkZBufferVesselDistance>(thin, 50.0);
  auto e = Make<vtkExactVesselDistance>(thin, 50.0);
  z->Build();
  ASSERT_GT(z->GetGrid().PixelMm, 0.1 * 3);
  double b[6];
  VesselBounds(thin, b);
  const Agreement a = ExpectWithinBound(z, e, RandomTips(b, 3.0, 500, 11), "thin");
  EXPECT_GT(a.Compared, 900);
  // Tips right next to each vessel, where a missed vessel would be a gross error.
  for (const auto& v : thin)
  {
    const double* vb = v.second->GetBounds();
    const double tip[3] = { 0.5 * (vb[0] + vb[1]) + 0.3, 0.5 * (vb[2] + vb[3]), 0.5 * (vb[4] + vb[5]) + 0.2 };
    vp::ProximityResult zr, er;
    z->ComputeProximity(tip, nullptr, zr);
    e->ComputeProximity(tip, nullptr, er);
    for (std::size_t c = 0; c < 2; ++c)
    {
      EXPECT_NEAR(zr.Classes[c].DistanceMm, er.Classes[c].DistanceMm, zr.ErrorBoundMm) << v.first;
    }
  }
}

TEST(ZBufferDistance, OutOfRangeAndInside)
{
  VP_REQUIRE_VULKAN();
  const double centre[3] = { 5, -3, 2 };
  const Vessels sphere = { { "hepatic_vein", vp::MakeSphere(centre, 10.0, 48, 96) } };
  auto z = Make<vtkZBufferVesselDistance>(sphere, 20.0);
  auto e = Make<vtkExactVesselDistance>(sphere, 20.0);
  // 35 mm from the centre: 25 mm from the surface, beyond the 20 mm range.
  const double far[3] = { 5 + 35, -3, 2 };
  vp::ProximityResult r;
  z->ComputeProximity(far, nullptr, r);
  EXPECT_FALSE(r.Classes[0].InRange);
  // Inside: the distance is the penetration depth, to the nearest surface point.
  for (double depth : { 1.0, 4.0, 9.0 })
  {
    const double tip[3] = { 5 + 10 - depth, -3, 2 };
    vp::ProximityResult zr, er;
    z->ComputeProximity(tip, nullptr, zr);
    e->ComputeProximity(tip, nullptr, er);
    ASSERT_EQ(er.Classes[0].Inside, std::optional<bool>(true));
    EXPECT_EQ(zr.Classes[0].Inside, std::optional<bool>(true)) << depth;
    EXPECT_TRUE(zr.Classes[0].InRange);
    EXPECT_NEAR(zr.Classes[0].DistanceMm, er.Classes[0].DistanceMm, zr.ErrorBoundMm) << depth;
  }
}

// The directional walk shared by lanes (as on a GPU), each walking its share of the range: on the
// built-in vessels, from random tips along random axes, 1, 7 and 64 lanes give the same
// directional distance, bit for bit.
TEST(ZBufferDistance, DirectionalLanesGiveTheSingleWalksAnswer)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  double b[6];
  VesselBounds(vessels, b);
  const auto tips = RandomTips(b, 5.0, 150, 21);
  const auto axes = RandomTips(b, 0.0, 150, 22); // directions towards points of the box
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  std::vector<std::optional<double>> single;
  int hits = 0;
  for (int lanes : { 1, 7, 64 })
  {
    z->SetDirectionalLanes(lanes);
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      const double axis[3] = { axes[i][0] - tips[i][0], axes[i][1] - tips[i][1], axes[i][2] - tips[i][2] };
      vp::ProximityResult r;
      z->ComputeProximity(tips[i].data(), axis, r);
      for (const vp::ClassProximity& c : r.Classes)
      {
        const std::size_t k = i * r.Classes.size() + static_cast<std::size_t>(&c - r.Classes.data());
        if (lanes == 1)
        {
          single.push_back(c.DirectionalMm);
          hits += c.DirectionalMm.has_value() ? 1 : 0;
        }
        else
        {
          ASSERT_EQ(c.DirectionalMm.has_value(), single[k].has_value()) << lanes << " lanes, tip " << i;
          if (single[k])
          {
            EXPECT_EQ(*c.DirectionalMm, *single[k]) << lanes << " lanes, tip " << i;
          }
        }
      }
    }
  }
  EXPECT_GT(hits, 30); // enough axes meet a vessel for the comparison to mean something
  EXPECT_THROW(z->SetDirectionalLanes(-1), vp::InputError);
}

// The per-pixel pass (GPUs) and the per-tile pass (CPU devices) give the same answers, bit for
// bit: distance, closest point, inside and directional distance, in the exact-interval mode, in
// the paper's mode with its distance bits, and for a batch.
TEST(ZBufferDistance, PerPixelPassGivesThePerTileAnswersBitForBit)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  double b[6];
  VesselBounds(vessels, b);
  const auto tips = RandomTips(b, 5.0, 200, 31);
  const auto towards = RandomTips(b, 0.0, 200, 32);
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto answers = [&](int pass) {
    z->SetQueryPass(pass);
    std::vector<vp::ProximityResult> out(tips.size());
    for (std::size_t i = 0; i < tips.size(); ++i)
    {
      const double axis[3] = { towards[i][0] - tips[i][0], towards[i][1] - tips[i][1], towards[i][2] - tips[i][2] };
      z->ComputeProximity(tips[i].data(), axis, out[i]);
    }
    std::vector<vp::ProximityResult> batch;
    z->ComputeProximityBatch(tips, nullptr, batch);
    out.insert(out.end(), batch.begin(), batch.end());
    return out;
  };
  for (int mode : { 0, 1 })
  {
    z->SetLayerMode(mode ? vtkZBufferVesselDistance::PaperNearFar : vtkZBufferVesselDistance::ExactIntervals);
    z->SetDistanceBins(mode ? 64 : 0);
    const auto tile = answers(vtkZBufferVesselDistance::QueryPassPerTile);
    const auto pixel = answers(vtkZBufferVesselDistance::QueryPassPerPixel);
    int inRange = 0;
    for (std::size_t i = 0; i < tile.size(); ++i)
    {
      for (std::size_t c = 0; c < tile[i].Classes.size(); ++c)
      {
        const vp::ClassProximity& t = tile[i].Classes[c];
        const vp::ClassProximity& p = pixel[i].Classes[c];
        ASSERT_EQ(t.InRange, p.InRange) << "mode " << mode << ", answer " << i;
        inRange += t.InRange ? 1 : 0;
        EXPECT_EQ(t.DistanceMm, p.DistanceMm) << "mode " << mode << ", answer " << i;
        EXPECT_EQ(t.Inside, p.Inside) << "mode " << mode << ", answer " << i;
        EXPECT_EQ(t.DirectionalMm, p.DirectionalMm) << "mode " << mode << ", answer " << i;
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(t.ClosestPoint[k], p.ClosestPoint[k]) << "mode " << mode << ", answer " << i;
        }
      }
    }
    EXPECT_GT(inRange, 600) << "mode " << mode;
  }
  EXPECT_THROW(z->SetQueryPass(3), vp::InputError);
}

TEST(ZBufferDistance, DirectionalDistanceAlongTheAxis)
{
  VP_REQUIRE_VULKAN();
  const double centre[3] = { 0, 0, 0 };
  const Vessels sphere = { { "hepatic_vein", vp::MakeSphere(centre, 10.0, 48, 96) } };
  auto z = Make<vtkZBufferVesselDistance>(sphere, 50.0);
  auto e = Make<vtkExactVesselDistance>(sphere, 50.0);
  const double tip[3] = { 3, -25, 4 };
  for (auto axis : { std::array<double, 3>{ 0, 1, 0 }, std::array<double, 3>{ -0.1, 1, -0.15 },
         std::array<double, 3>{ 0.05, 1, -0.1 } })
  {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& a : axis)
    {
      a /= n;
    }
    vp::ProximityResult zr, er;
    z->ComputeProximity(tip, axis.data(), zr);
    e->ComputeProximity(tip, axis.data(), er);
    ASSERT_TRUE(er.Classes[0].DirectionalMm.has_value());
    ASSERT_TRUE(zr.Classes[0].DirectionalMm.has_value());
    // Never further than the truth; here, where the axis meets the sphere squarely, close to it.
    EXPECT_LE(*zr.Classes[0].DirectionalMm, *er.Classes[0].DirectionalMm + zr.ErrorBoundMm);
    EXPECT_GT(*zr.Classes[0].DirectionalMm, *er.Classes[0].DirectionalMm - 2.0);
  }
  const double away[3] = { 0, -1, 0 };
  vp::ProximityResult zr;
  z->ComputeProximity(tip, away, zr);
  EXPECT_FALSE(zr.Classes[0].DirectionalMm.has_value());
}

TEST(ZBufferDistance, DistanceBinsAddHalfABinToTheBound)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto e = Make<vtkExactVesselDistance>(vessels, 50.0);
  z->SetDistanceBins(64);
  z->Build();
  EXPECT_NEAR(z->GetErrorBoundMm(), z->GetGrid().ErrorBoundMm() + 0.5 * 50.0 / 64, 1e-12);
  double b[6];
  VesselBounds(vessels, b);
  const Agreement a = ExpectWithinBound(z, e, RandomTips(b, 5.0, 200, 5), "bins");
  EXPECT_GT(a.Compared, 400);
  EXPECT_THROW(z->SetDistanceBins(20), vp::InputError);
}

TEST(ZBufferDistance, CachedLayersGiveTheReRenderedAnswers)
{
  VP_REQUIRE_VULKAN();
  const Vessels vessels = vp::MakeBuiltInVessels();
  // The moving box renders again only when the range ball leaves it; a second engine with a box
  // that barely holds the ball renders at almost every step. Both share one lattice of cells.
  auto cached = Make<vtkZBufferVesselDistance>(vessels, 20.0);
  auto fresh = Make<vtkZBufferVesselDistance>(vessels, 20.0);
  cached->SetBoxMode(vtkZBufferVesselDistance::MovingWithTip);
  cached->SetMovingBoxSizeMm(106, 106, 213);
  fresh->SetBoxMode(vtkZBufferVesselDistance::MovingWithTip);
  fresh->SetMovingBoxSizeMm(41, 41, 41);
  auto fixed = Make<vtkZBufferVesselDistance>(vessels, 20.0);
  int compared = 0;
  for (int step = 0; step < 60; ++step)
  {
    const double tip[3] = { -20.0 + step * 0.9, 5.0 + 0.2 * step, 3.0 - 0.1 * step };
    vp::ProximityResult a, b, c;
    cached->ComputeProximity(tip, nullptr, a);
    fresh->ComputeProximity(tip, nullptr, b);
    fixed->ComputeProximity(tip, nullptr, c);
    for (std::size_t k = 0; k < a.Classes.size(); ++k)
    {
      ASSERT_EQ(a.Classes[k].InRange, b.Classes[k].InRange) << step;
      if (a.Classes[k].InRange)
      {
        ++compared;
        EXPECT_NEAR(a.Classes[k].DistanceMm, b.Classes[k].DistanceMm, 1e-4) << step;
        EXPECT_EQ(a.Classes[k].Inside, b.Classes[k].Inside) << step;
        if (c.Classes[k].InRange)
        {
          EXPECT_NEAR(a.Classes[k].DistanceMm, c.Classes[k].DistanceMm, 2 * a.ErrorBoundMm) << step;
        }
        else
        {
          EXPECT_GE(a.Classes[k].DistanceMm, 20.0 - 2 * a.ErrorBoundMm) << step << ": out of the 20 mm range only at its edge";
        }
      }
    }
  }
  EXPECT_GT(compared, 60);
  EXPECT_LT(cached->GetNumberOfRenders(), 10);
  EXPECT_GT(fresh->GetNumberOfRenders(), 40);
  EXPECT_EQ(fixed->GetNumberOfRenders(), 1);
}

namespace
{
void CompareOnIrcadbPatient(const std::string& patient)
{
  VP_REQUIRE_VULKAN();
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: z-buffer on IRCADb not tested";
  }
  const std::string dir = extracted + "/ircadb/" + patient + "/MESHES_VTK/";
  Vessels vessels;
  for (const auto& entry : { std::make_pair("portal_vein", "portalvein.vtk"),
         std::make_pair("hepatic_vein", "venoussystem.vtk"), std::make_pair("hepatic_artery", "artery.vtk") })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(dir + entry.second);
    reader->Read();
    vessels.emplace_back(entry.first, reader->GetOutput());
  }
  auto z = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  auto paper = Make<vtkZBufferVesselDistance>(vessels, 50.0);
  paper->SetLayerMode(vtkZBufferVesselDistance::PaperNearFar);
  auto e = Make<vtkExactVesselDistance>(vessels, 50.0);
  z->Build();
  EXPECT_LE(z->GetErrorBoundMm(), 0.5);
  double b[6];
  VesselBounds(vessels, b);
  const auto tips = RandomTips(b, 10.0, 1000, 2024);
  const Agreement a = ExpectWithinBound(z, e, tips, patient);
  EXPECT_GT(a.Compared, 1500);
  // The paper's mode on the same tips: never above exact + bound, but far below it where
  // branches overlap along the view.
  double worst = 0.0;
  for (const auto& tip : tips)
  {
    vp::ProximityResult pr, er;
    paper->ComputeProximity(tip.data(), nullptr, pr);
    e->ComputeProximity(tip.data(), nullptr, er);
    for (std::size_t c = 0; c < er.Classes.size(); ++c)
    {
      if (er.Classes[c].InRange && pr.Classes[c].InRange)
      {
        EXPECT_LE(pr.Classes[c].DistanceMm, er.Classes[c].DistanceMm + pr.ErrorBoundMm);
        worst = std::max(worst, er.Classes[c].DistanceMm - pr.Classes[c].DistanceMm);
      }
    }
  }
  EXPECT_GT(worst, 2.0) << "the paper's near/far mode should overstate proximity on a vessel tree";
  std::cout << patient << ": " << a.Compared << " answers, largest |zbuffer - exact| " << a.MaxDifferenceMm
            << " mm (bound " << z->GetErrorBoundMm() << " mm); paper's mode overstates by up to " << worst << " mm\n";
}
} // namespace

TEST(ZBufferDistance, WithinBoundOnIrcadbPatient1) { CompareOnIrcadbPatient("3Dircadb1.1"); }
TEST(ZBufferDistance, WithinBoundOnIrcadbPatient4) { CompareOnIrcadbPatient("3Dircadb1.4"); }
