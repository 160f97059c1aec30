// Inside on the meshes people really have (issue 14): a closed vessel surface made defective in
// each of the ways exports and hand edits make them (a hole, a fin on an edge, a patch wound the
// wrong way, a duplicated sheet) still tells every tip 0.2 mm or more inside from every tip 0.2 mm
// or more outside, in the exact engine (Embree's rays) and the brute force (every triangle in
// double), and the surface reports what is wrong with it.
#include "vpBuiltInPhantom.h"
#include "vpDangerLevels.h"
#include "vpTriangleGeometry.h"
#include "vpVesselSurface.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
using Points = std::vector<std::array<double, 3>>;
using Triangles = std::vector<std::array<std::int32_t, 3>>;

vtkSmartPointer<vtkPolyData> MakeMesh(const Points& points, const Triangles& triangles)
{
  vtkNew<vtkPoints> p;
  for (const auto& x : points)
  {
    p->InsertNextPoint(x.data());
  }
  vtkNew<vtkCellArray> cells;
  for (const auto& t : triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    cells->InsertNextCell(3, ids);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(p);
  mesh->SetPolys(cells);
  return mesh;
}

std::array<double, 3> Centroid(const Points& points, const std::array<std::int32_t, 3>& t)
{
  std::array<double, 3> c{};
  for (int k = 0; k < 3; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      c[a] += points[t[k]][a] / 3.0;
    }
  }
  return c;
}

// The triangles whose centroid lies within radiusMm of the centroid of triangle `around`.
std::vector<std::size_t> Patch(const Points& points, const Triangles& triangles, std::size_t around, double radiusMm)
{
  const auto centre = Centroid(points, triangles[around]);
  std::vector<std::size_t> patch;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    if (vp::Distance2(Centroid(points, triangles[t]).data(), centre.data()) <= radiusMm * radiusMm)
    {
      patch.push_back(t);
    }
  }
  return patch;
}

struct Defective
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
  std::function<bool(const vp::MeshDefects&)> Reported;
};

std::vector<Defective> DefectiveCopies(const Points& points, const Triangles& triangles)
{
  std::vector<Defective> copies;
  const std::size_t at = triangles.size() / 3; // somewhere along the vessel, not at its start
  {
    Triangles holed = triangles;
    holed.erase(holed.begin() + static_cast<std::ptrdiff_t>(at));
    copies.push_back({ "one triangle removed (a hole)", MakeMesh(points, holed),
      [](const vp::MeshDefects& d) { return d.BoundaryEdges == 3 && d.NonManifoldEdges == 0; } });
  }
  {
    // A fin: a new triangle on an edge of the surface, standing 1 mm out of it.
    Points finned = points;
    Triangles fin = triangles;
    const auto& t = triangles[at];
    std::array<double, 3> tip{};
    for (int a = 0; a < 3; ++a)
    {
      tip[a] = 0.5 * (points[t[0]][a] + points[t[1]][a]) + (points[t[0]][a] - points[t[2]][a]) * 0.1;
    }
    finned.push_back(tip);
    fin.push_back({ t[0], t[1], static_cast<std::int32_t>(finned.size() - 1) });
    copies.push_back({ "a fin on an edge (non-manifold)", MakeMesh(finned, fin),
      [](const vp::MeshDefects& d) { return d.NonManifoldEdges == 1; } });
  }
  {
    Triangles flipped = triangles;
    for (std::size_t t : Patch(points, triangles, at, 3.0))
    {
      std::swap(flipped[t][1], flipped[t][2]);
    }
    copies.push_back({ "a patch wound the wrong way", MakeMesh(points, flipped),
      [](const vp::MeshDefects& d) { return d.InconsistentEdges > 0; } });
  }
  {
    Triangles doubled = triangles;
    for (std::size_t t : Patch(points, triangles, at, 3.0))
    {
      doubled.push_back(triangles[t]);
    }
    copies.push_back({ "a duplicated sheet", MakeMesh(points, doubled),
      [](const vp::MeshDefects& d) { return d.NonManifoldEdges > 0; } });
  }
  return copies;
}
} // namespace

TEST(InsideOnDefectiveMeshes, EveryTipDeeperThanAFifthOfAMillimetreIsClassifiedRight)
{
  for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
  {
    const vp::VesselSurface original(className, mesh);
    ASSERT_TRUE(original.IsClosed()) << className << ": " << original.Defects().Describe();
    const Points& points = original.PointArray();
    const Triangles& triangles = original.TriangleArray();

    // The truth from the closed surface (its pseudonormal), 200 tips each side, 0.2 mm or more
    // from the wall; half of them near the defects' place, where a ray is likeliest to meet one.
    vtkNew<vtkExactVesselDistance> truth;
    truth->SetRangeMm(1000.0);
    truth->AddVessel(className, MakeMesh(points, triangles));
    truth->Build();
    const double* b = original.Bounds();
    const auto near = Centroid(points, triangles[triangles.size() / 3]);
    std::mt19937 random(17);
    std::vector<std::array<double, 3>> inside, outside;
    for (int draw = 0; draw < 200000 && (inside.size() < 200 || outside.size() < 200); ++draw)
    {
      std::array<double, 3> tip;
      for (int a = 0; a < 3; ++a)
      {
        tip[a] = draw % 2 ? std::uniform_real_distribution<double>(near[a] - 6.0, near[a] + 6.0)(random)
                          : std::uniform_real_distribution<double>(b[2 * a] - 3.0, b[2 * a + 1] + 3.0)(random);
      }
      vp::ProximityResult r;
      truth->ComputeProximity(tip.data(), nullptr, r);
      const vp::ClassProximity& c = r.Classes[0];
      if (!c.InRange || c.DistanceMm < 0.2)
      {
        continue;
      }
      auto& side = *c.Inside ? inside : outside;
      if (side.size() < 200)
      {
        side.push_back(tip);
      }
    }
    ASSERT_EQ(inside.size(), 200u) << className;
    ASSERT_EQ(outside.size(), 200u) << className;

    for (const Defective& copy : DefectiveCopies(points, triangles))
    {
      const std::string where = className + ", " + copy.Name;
      const vp::VesselSurface surface(className, copy.Mesh);
      EXPECT_FALSE(surface.IsClosed()) << where;
      EXPECT_TRUE(copy.Reported(surface.Defects())) << where << ": " << surface.Defects().Describe();
      vtkNew<vtkExactVesselDistance> exact;
      vtkNew<vtkBruteForceVesselDistance> brute;
      for (vtkVesselDistanceEngine* engine : { static_cast<vtkVesselDistanceEngine*>(exact.Get()),
             static_cast<vtkVesselDistanceEngine*>(brute.Get()) })
      {
        engine->SetRangeMm(1000.0);
        engine->AddVessel(className, copy.Mesh);
        engine->Build();
      }
      int checked = 0;
      int uncertain = 0;
      for (const auto* tips : { &inside, &outside })
      {
        const bool expected = tips == &inside;
        for (std::size_t i = 0; i < tips->size(); ++i)
        {
          vp::ProximityResult e;
          exact->ComputeProximity((*tips)[i].data(), nullptr, e);
          ASSERT_TRUE(e.Classes[0].Inside.has_value()) << where;
          EXPECT_EQ(*e.Classes[0].Inside, expected) << where << ", tip " << i << (e.Classes[0].InsideUncertain ? " (uncertain)" : "");
          // Every inside tip is a breach; so is an outside one whose rays disagreed.
          const vp::DangerLevel level = vp::ClassifyDanger(e.Classes[0], 0.0, vp::DangerThresholds{});
          if (expected || e.Classes[0].InsideUncertain)
          {
            EXPECT_EQ(level, vp::DangerLevel::Breach) << where << ", tip " << i;
            uncertain += e.Classes[0].InsideUncertain ? 1 : 0;
          }
          else
          {
            EXPECT_NE(level, vp::DangerLevel::Breach) << where << ", tip " << i;
          }
          // The brute force, the reference of the vote, on every tenth tip (it tests every triangle).
          if (i % 10 == 0)
          {
            vp::ProximityResult r;
            brute->ComputeProximity((*tips)[i].data(), nullptr, r);
            EXPECT_EQ(r.Classes[0].Inside, e.Classes[0].Inside) << where << ", tip " << i;
            EXPECT_EQ(r.Classes[0].InsideUncertain, e.Classes[0].InsideUncertain) << where << ", tip " << i;
          }
          ++checked;
        }
      }
      EXPECT_EQ(checked, 400) << where;
      EXPECT_LE(uncertain, 40) << where << ": the rays should rarely disagree";
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
