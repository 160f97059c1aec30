// Inside on the meshes people really have (issue 14): a closed vessel surface (the built-in
// vessels, IRCADb's repaired) made defective in each of the ways exports and hand edits make them
// (a hole, a crack, a fin on an edge, a patch wound the wrong way, a duplicated sheet) still tells every tip 0.2 mm or more inside from every tip 0.2 mm
// or more outside, in the exact engine (Embree's rays) and the brute force (every triangle in
// double), and the surface reports what is wrong with it.
#include "vpAnalyticShapes.h"
#include "vpBuiltInPhantom.h"
#include "vpDangerLevels.h"
#include "vpTriangleGeometry.h"
#include "vpVesselSurface.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkZBufferVesselDistance.h"
#include "vpDefectiveMeshes.h"
#include "vpVulkanTestSupport.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
// Per closed surface: the defective copies, and 200 tips each side of it, 0.2 mm or more from
// the wall, the truth from the closed surface (its pseudonormal); half of them near the defects'
// place, where a ray is likeliest to meet one.
struct Case
{
  std::string ClassName;
  std::vector<vp::test::Defective> Copies;
  std::vector<std::array<double, 3>> Inside, Outside;
};

Case MakeCase(const std::string& className, vtkPolyData* mesh)
{
  const vp::VesselSurface original(className, mesh);
  const vp::test::Points& points = original.PointArray();
  const vp::test::Triangles& triangles = original.TriangleArray();
  Case c{ className, vp::test::DefectiveCopies(points, triangles), {}, {} };
  vtkNew<vtkExactVesselDistance> truth;
  truth->SetRangeMm(1000.0);
  truth->AddVessel(className, mesh);
  truth->Build();
  const double* b = original.Bounds();
  const auto near = vp::test::Centroid(points, triangles[triangles.size() / 3]);
  std::mt19937 random(17);
  // The truth needs the closed surface's pseudonormal: no tips otherwise (Cases' users then fail).
  for (int draw = 0; original.IsClosed() && draw < 400000 && (c.Inside.size() < 200 || c.Outside.size() < 200); ++draw)
  {
    std::array<double, 3> tip;
    for (int a = 0; a < 3; ++a)
    {
      tip[a] = draw % 2 ? std::uniform_real_distribution<double>(near[a] - 6.0, near[a] + 6.0)(random)
                        : std::uniform_real_distribution<double>(b[2 * a] - 3.0, b[2 * a + 1] + 3.0)(random);
    }
    vp::ProximityResult r;
    truth->ComputeProximity(tip.data(), nullptr, r);
    const vp::ClassProximity& p = r.Classes[0];
    // Within the engines' 50 mm range of the tests (IRCADb's bounds reach farther from a vessel).
    if (p.InRange && p.DistanceMm >= 0.2 && p.DistanceMm <= 40.0)
    {
      auto& side = *p.Inside ? c.Inside : c.Outside;
      if (side.size() < 200)
      {
        side.push_back(tip);
      }
    }
  }
  return c;
}

// The built-in vessels, and IRCADb's meshes of patients 1 and 4 that --repair closes (issue 14
// asks for defective copies of those; closed, they have an exact truth). Without the data the
// IRCADb cases are missing, and the tests say so.
const std::vector<Case>& Cases()
{
  static const std::vector<Case> cases = [] {
    std::vector<Case> out;
    for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
    {
      out.push_back(MakeCase(className, mesh));
    }
    for (const auto& [name, mesh] : vp::test::ClosedIrcadbVessels())
    {
      out.push_back(MakeCase(name, mesh));
    }
    return out;
  }();
  return cases;
}

std::size_t ExpectedTips()
{
  std::size_t tips = 0;
  for (const Case& c : Cases())
  {
    tips += c.Copies.size() * 400;
  }
  return tips;
}

// Runs check(tip, expected inside, where) over every tip of every defective copy, with engine
// made anew for each copy by make.
void ForEveryTip(const std::function<vtkSmartPointer<vtkVesselDistanceEngine>()>& make,
  const std::function<void(vtkVesselDistanceEngine*, vtkPolyData*, const double*, bool, const std::string&)>& check)
{
  for (const Case& c : Cases())
  {
    ASSERT_EQ(c.Inside.size(), 200u) << c.ClassName;
    ASSERT_EQ(c.Outside.size(), 200u) << c.ClassName;
    for (const vp::test::Defective& copy : c.Copies)
    {
      vtkSmartPointer<vtkVesselDistanceEngine> engine = make();
      engine->SetRangeMm(50.0);
      engine->AddVessel(c.ClassName, copy.Mesh);
      engine->Build();
      for (const auto* tips : { &c.Inside, &c.Outside })
      {
        for (std::size_t i = 0; i < tips->size(); ++i)
        {
          check(engine, copy.Mesh, (*tips)[i].data(), tips == &c.Inside,
            c.ClassName + ", " + copy.Name + ", " + (tips == &c.Inside ? "inside" : "outside") + " tip " + std::to_string(i));
        }
      }
    }
  }
}
} // namespace

TEST(InsideOnDefectiveMeshes, EachDefectIsReported)
{
  for (const Case& c : Cases())
  {
    for (const vp::test::Defective& copy : c.Copies)
    {
      const vp::VesselSurface surface(c.ClassName, copy.Mesh);
      EXPECT_FALSE(surface.IsClosed()) << c.ClassName << ", " << copy.Name;
      EXPECT_TRUE(copy.Reported(surface.Defects())) << c.ClassName << ", " << copy.Name << ": " << surface.Defects().Describe();
    }
  }
}

// Every tip classified right by the exact engine; every inside one a breach, and so is an
// outside one whose rays disagreed (rarely); the brute force, the vote's reference, agrees.
TEST(InsideOnDefectiveMeshes, EveryTipDeeperThanAFifthOfAMillimetreIsClassifiedRight)
{
  int uncertain = 0, checked = 0;
  vtkSmartPointer<vtkBruteForceVesselDistance> brute;
  vtkPolyData* bruteMesh = nullptr;
  ForEveryTip([] { return vtkSmartPointer<vtkExactVesselDistance>::New(); },
    [&](vtkVesselDistanceEngine* exact, vtkPolyData* mesh, const double* tip, bool expected, const std::string& where) {
      vp::ProximityResult e;
      exact->ComputeProximity(tip, nullptr, e);
      ASSERT_TRUE(e.Classes[0].Inside.has_value()) << where;
      EXPECT_EQ(*e.Classes[0].Inside, expected) << where << (e.Classes[0].InsideUncertain ? " (uncertain)" : "");
      const vp::DangerLevel level = vp::ClassifyDanger(e.Classes[0], 0.0, vp::DangerThresholds{});
      if (expected || e.Classes[0].InsideUncertain)
      {
        EXPECT_EQ(level, vp::DangerLevel::Breach) << where;
      }
      else
      {
        EXPECT_NE(level, vp::DangerLevel::Breach) << where;
      }
      uncertain += e.Classes[0].InsideUncertain ? 1 : 0;
      // The brute force on every tenth tip (it tests every triangle).
      if (++checked % 10 == 0)
      {
        if (mesh != bruteMesh)
        {
          brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
          brute->SetRangeMm(50.0);
          brute->AddVessel(exact->GetVesselName(0), mesh);
          brute->Build();
          bruteMesh = mesh;
        }
        vp::ProximityResult r;
        brute->ComputeProximity(tip, nullptr, r);
        EXPECT_EQ(r.Classes[0].Inside, e.Classes[0].Inside) << where;
        EXPECT_EQ(r.Classes[0].InsideUncertain, e.Classes[0].InsideUncertain) << where;
      }
    });
  EXPECT_EQ(static_cast<std::size_t>(checked), ExpectedTips());
  EXPECT_LE(uncertain, checked / 50) << "the rays should rarely disagree";
}

// The z-buffer's one ray cannot vote: on a surface that is not closed it takes the exact engine's
// vote, so every tip is classified right there too, and every inside one is a breach.
TEST(InsideOnDefectiveMeshes, TheZBufferTakesTheVoteAndEveryInsideTipIsABreach)
{
  VP_REQUIRE_VULKAN();
  int checked = 0;
  ForEveryTip([] { return vtkSmartPointer<vtkZBufferVesselDistance>::New(); },
    [&](vtkVesselDistanceEngine* z, vtkPolyData*, const double* tip, bool expected, const std::string& where) {
      vp::ProximityResult r;
      z->ComputeProximity(tip, nullptr, r);
      const vp::ClassProximity& c = r.Classes[0];
      ASSERT_TRUE(c.InRange) << where;
      ASSERT_TRUE(c.Inside.has_value()) << where;
      EXPECT_EQ(*c.Inside, expected) << where << (c.InsideUncertain ? " (uncertain)" : "");
      if (expected)
      {
        EXPECT_EQ(vp::ClassifyDanger(c, r.ErrorBoundMm, vp::DangerThresholds{}), vp::DangerLevel::Breach) << where;
      }
      ++checked;
    });
  EXPECT_EQ(static_cast<std::size_t>(checked), ExpectedTips());

  // A batch answers as the tips one by one (its votes run on all cores).
  const Case& c = Cases().front();
  auto z = vtkSmartPointer<vtkZBufferVesselDistance>::New();
  z->SetRangeMm(50.0);
  z->AddVessel(c.ClassName, c.Copies.front().Mesh);
  z->Build();
  std::vector<std::array<double, 3>> all(c.Inside);
  all.insert(all.end(), c.Outside.begin(), c.Outside.end());
  std::vector<vp::ProximityResult> batch;
  z->ComputeProximityBatch(all, nullptr, batch);
  ASSERT_EQ(batch.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    vp::ProximityResult single;
    z->ComputeProximity(all[i].data(), nullptr, single);
    EXPECT_EQ(batch[i].Classes[0].Inside, single.Classes[0].Inside) << "tip " << i;
    EXPECT_EQ(batch[i].Classes[0].InsideUncertain, single.Classes[0].InsideUncertain) << "tip " << i;
    EXPECT_EQ(*batch[i].Classes[0].Inside, i < c.Inside.size()) << "tip " << i;
  }
}

// Beyond the range on an open surface (the vote decides inside): a tip 25 mm deep is a breach
// with its depth, a tip outside the vessel but inside its box is out of range, from the exact
// engine and the z-buffer, alone and in a batch. The vote now comes before the unbounded search
// for the wall, which only an inside tip needs.
TEST(InsideOnDefectiveMeshes, BeyondTheRangeAnOpenVesselsInsideTipHasItsDepthAndAnOutsideOneNone)
{
  VP_REQUIRE_VULKAN();
  const double centre[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkPolyData> closed = vp::MakeSphere(centre, 30.0, 32, 64);
  vtkNew<vtkCellArray> cells;
  vtkIdType n = 0;
  const vtkIdType* ids = nullptr;
  for (vtkIdType t = 0; t < closed->GetNumberOfCells(); ++t)
  {
    closed->GetCellPoints(t, n, ids);
    if (t != closed->GetNumberOfCells() / 3) // one triangle gone: a hole, the surface open
    {
      cells->InsertNextCell(n, ids);
    }
  }
  vtkNew<vtkPolyData> open;
  open->SetPoints(closed->GetPoints());
  open->SetPolys(cells);
  const std::vector<std::array<double, 3>> tips = { { 0, 0, 5 }, { 28, 28, 0 }, { -27, 27, 5 }, { 1, -2, -3 } };
  const bool inside[] = { true, false, false, true };
  const std::vector<vtkSmartPointer<vtkVesselDistanceEngine>> engines = { vtkSmartPointer<vtkExactVesselDistance>::New(),
    vtkSmartPointer<vtkZBufferVesselDistance>::New() };
  for (vtkVesselDistanceEngine* e : engines)
  {
    e->SetRangeMm(5.0);
    e->AddVessel("portal_vein", open);
    e->Build();
    std::vector<vp::ProximityResult> batch;
    std::vector<std::array<double, 3>> many; // 64: a batch that runs on every core
    for (int k = 0; k < 64; ++k)
    {
      many.push_back(tips[static_cast<std::size_t>(k) % tips.size()]);
    }
    e->ComputeProximityBatch(many, nullptr, batch);
    for (std::size_t i = 0; i < many.size(); ++i)
    {
      const std::size_t which = i % tips.size();
      vp::ProximityResult single;
      e->ComputeProximity(many[i].data(), nullptr, single);
      for (const vp::ProximityResult* r : { &single, &batch[i] })
      {
        const vp::ClassProximity& c = r->Classes[0];
        const std::string where = std::string(e->GetClassName()) + ", tip " + std::to_string(which) + (r == &single ? "" : " in a batch");
        EXPECT_EQ(c.InRange, inside[which]) << where;
        EXPECT_EQ(c.Inside.value_or(false), inside[which]) << where;
        if (inside[which])
        {
          const double depth = 30.0 - std::sqrt(vp::Distance2(many[i].data(), centre));
          // The wall's depth: the facets lie up to 0.15 mm inside the sphere of radius 30.
          EXPECT_NEAR(c.DistanceMm, depth - 0.07, 0.09) << where;
        }
      }
    }
  }
}

// A closed surface keeps its exact answer (the pseudonormal): no vote, never uncertain.
TEST(InsideOnDefectiveMeshes, ClosedSurfacesReportNoDefects)
{
  for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
  {
    const vp::VesselSurface surface(className, mesh);
    EXPECT_TRUE(surface.IsClosed()) << className;
    EXPECT_FALSE(surface.Defects().Any()) << className;
    EXPECT_GE(surface.Defects().Components, 1u) << className;
    EXPECT_NE(surface.Defects().Describe().find("closed"), std::string::npos);
  }
}

// The IRCADb meshes are in the cases above when the data is there: patient 1's hepatic veins and
// all three of patient 4's classes close under --repair (see TestSurfaceRepair).
TEST(InsideOnDefectiveMeshes, IrcadbCopiesAreAmongTheCases)
{
  if (vp::test::ExtractedDataDir().empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: inside on defective copies of IRCADb's meshes not tested";
  }
  std::vector<std::string> names;
  for (const Case& c : Cases())
  {
    names.push_back(c.ClassName);
  }
  for (const char* expected : { "3Dircadb1.1 hepatic_vein", "3Dircadb1.4 portal_vein", "3Dircadb1.4 hepatic_vein",
         "3Dircadb1.4 hepatic_artery" })
  {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
}
