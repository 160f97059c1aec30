// The inside vote field (vp::InsideVoteField): on every surface that is not closed, the vote it
// holds is the rays' vote, except in the thin bands (micrometres behind most folds) where a ray passes a
// fold (there the rays turn, the field does not); a triangle soup keeps its rays; and the
// benchmarks' grown meshes keep their topology, so that the field is measured on what a
// segmentation gives.
#include "vpBuiltInPhantom.h"
#include "vpDefectiveMeshes.h"
#include "vpInsideVoteField.h"
#include "vpMeshRefinement.h"
#include "vpTriangleGeometry.h"
#include "vpVesselSurface.h"
#include "vtkExactVesselDistance.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkExactVesselDistance> MakeEngine(const std::string& name, vtkPolyData* mesh, double fieldCellMm)
{
  auto engine = vtkSmartPointer<vtkExactVesselDistance>::New();
  engine->SetRangeMm(50.0);
  engine->SetVoteFieldCellMm(fieldCellMm);
  engine->AddVessel(name, mesh);
  engine->Build();
  return engine;
}

struct Agreement
{
  int Points = 0, Held = 0, InsideDiffers = 0, UncertainDiffers = 0, OutsideBands = 0;
};

// The field's vote against the rays' at random points of the surface's box grown by 5 mm. Where
// they differ, the rays must agree with the field 0.05 mm away on some axis (a band, not a
// region the field got wrong).
Agreement Compare(const std::string& name, vtkPolyData* mesh, double fieldCellMm, int points, unsigned seed)
{
  auto withField = MakeEngine(name, mesh, fieldCellMm);
  auto rays = MakeEngine(name, mesh, 0.0);
  const vp::InsideVoteField* field = withField->GetVoteField(0);
  EXPECT_NE(field, nullptr) << name;
  EXPECT_EQ(rays->GetVoteField(0), nullptr) << name;
  Agreement a;
  if (!field)
  {
    return a;
  }
  const double* b = withField->GetSurface(0).Bounds();
  std::mt19937 random(seed);
  for (a.Points = 0; a.Points < points; ++a.Points)
  {
    double p[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = std::uniform_real_distribution<double>(b[2 * k] - 5.0, b[2 * k + 1] + 5.0)(random);
    }
    bool inside = false, uncertain = false;
    if (!field->Lookup(p, inside, uncertain))
    {
      continue;
    }
    ++a.Held;
    bool rayUncertain = false;
    const bool rayInside = rays->VoteInside(0, p, 1.0, rayUncertain);
    // What the engine answers is the field's.
    bool engineUncertain = false;
    EXPECT_EQ(withField->VoteInside(0, p, 1.0, engineUncertain), inside) << name;
    EXPECT_EQ(engineUncertain, uncertain) << name;
    if (rayInside == inside && rayUncertain == uncertain)
    {
      continue;
    }
    (rayInside != inside ? a.InsideDiffers : a.UncertainDiffers) += 1;
    bool band = false;
    for (int axis = 0; axis < 3 && !band; ++axis)
    {
      for (double step : { -0.05, 0.05 })
      {
        double q[3] = { p[0], p[1], p[2] };
        q[axis] += step;
        bool u = false;
        band = band || (rays->VoteInside(0, q, 1.0, u) == inside && u == uncertain);
      }
    }
    if (!band)
    {
      ++a.OutsideBands;
      ADD_FAILURE() << name << ": the field's vote (" << inside << ", uncertain " << uncertain << ") is not the rays' ("
                    << rayInside << ", " << rayUncertain << ") at " << p[0] << " " << p[1] << " " << p[2]
                    << ", nor 0.05 mm away";
    }
  }
  return a;
}
} // namespace

// The built-in vessels made defective each way (a hole, a crack, a fin, a patch wound the wrong
// way, a duplicated sheet, ...): every vote the field holds is the rays'.
TEST(InsideVoteField, HoldsTheRaysVoteOnEveryDefectiveCopyOfTheBuiltInVessels)
{
  int copies = 0;
  for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
  {
    const vp::VesselSurface original(className, mesh);
    for (const vp::test::Defective& copy : vp::test::DefectiveCopies(original.PointArray(), original.TriangleArray()))
    {
      const std::string where = className + ", " + copy.Name;
      const Agreement a = Compare(where, copy.Mesh, 0.5, 4000, 5);
      // Near these thin vessels many cells hold surface; a duplicated sheet's rim casts shadows
      // (held there: 49 % of the artery's points, 83-98 % elsewhere).
      EXPECT_GE(a.Held, a.Points * 4 / 10) << where;
      EXPECT_EQ(a.InsideDiffers + a.UncertainDiffers, 0) << where;
      ++copies;
    }
  }
  EXPECT_GE(copies, 15);
}

// IRCADb's vessel meshes as given (open: holes where the vessels leave the scan): the field holds
// 97 % of the points, inside always as the rays say; where the uncertain flag differs, a ray
// passes close to a fold (a band).
TEST(InsideVoteField, HoldsTheRaysVoteOnIrcadbVesselsAsGiven)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: the field on IRCADb's meshes not tested";
  }
  int uncertainOnly = 0, points = 0;
  for (const char* file : { "portalvein.vtk", "venoussystem.vtk", "artery.vtk" })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(extracted + "/ircadb/3Dircadb1.1/MESHES_VTK/" + file);
    reader->Read();
    ASSERT_FALSE(vp::VesselSurface(file, reader->GetOutput()).IsClosed()) << file;
    const Agreement a = Compare(file, reader->GetOutput(), 1.0, 20000, 1);
    EXPECT_GE(a.Held, a.Points * 95 / 100) << file;
    EXPECT_EQ(a.InsideDiffers, 0) << file;
    EXPECT_EQ(a.OutsideBands, 0) << file;
    uncertainOnly += a.UncertainDiffers;
    points += a.Held;
  }
  EXPECT_LE(uncertainOnly, points / 5000) << "bands are thin: few points fall in them";
}

// A soup (every triangle with its own points, as an STL whose points were not merged) has every
// edge a rim: no field is built, and every vote casts its rays, right as before.
TEST(InsideVoteField, ATriangleSoupKeepsItsRays)
{
  const auto vessels = vp::MakeBuiltInVessels();
  const vp::VesselSurface original(vessels[0].first, vessels[0].second);
  vp::test::Points points;
  vp::test::Triangles triangles;
  for (const auto& t : original.TriangleArray())
  {
    std::array<std::int32_t, 3> own;
    for (int k = 0; k < 3; ++k)
    {
      own[k] = static_cast<std::int32_t>(points.size());
      points.push_back(original.PointArray()[t[k]]);
    }
    triangles.push_back(own);
  }
  const auto soup = vp::test::MakeMesh(points, triangles);
  auto engine = MakeEngine("soup", soup, 1.0);
  const vp::InsideVoteField* field = engine->GetVoteField(0);
  ASSERT_NE(field, nullptr);
  EXPECT_FALSE(field->IsBuilt());
  EXPECT_EQ(field->SweptEdges(), 3 * original.NumberOfTriangles());
  // A point deep inside the vessel (its first triangle's centroid moved a millimetre inward
  // along the closed original's outward normal) is inside by the rays.
  const auto c = vp::test::Centroid(original.PointArray(), original.TriangleArray()[0]);
  const double* n = original.OutwardNormal(0);
  ASSERT_NE(n, nullptr);
  const double inner[3] = { c[0] - n[0], c[1] - n[1], c[2] - n[2] };
  bool uncertain = true, inside = false;
  EXPECT_FALSE(field->Lookup(inner, inside, uncertain));
  EXPECT_TRUE(engine->VoteInside(0, inner, 1.0, uncertain));
  EXPECT_FALSE(uncertain);
}

// The benchmarks grow meshes to a size: the surface point for point, and its topology (a closed
// mesh closed, a hole's rim the same length), to the triangle asked for or one more.
TEST(MeshRefinement, GrowsAMeshToItsSizeWithItsSurfaceAndTopology)
{
  const auto vessels = vp::MakeBuiltInVessels();
  const vp::VesselSurface closed(vessels[0].first, vessels[0].second);
  ASSERT_TRUE(closed.IsClosed());
  const auto holed = vp::test::DefectiveCopies(closed.PointArray(), closed.TriangleArray())[0].Mesh;
  const vp::VesselSurface holedSurface("holed", holed);
  auto rimMm = [](const vp::VesselSurface& s) {
    double length = 0.0;
    for (const auto& e : s.OddEdges())
    {
      length += std::sqrt(vp::Distance2(s.Point(e[0]), s.Point(e[1])));
    }
    return length;
  };
  for (const std::size_t target : { closed.NumberOfTriangles() * 4 + 1001, closed.NumberOfTriangles() * 17 })
  {
    const vp::VesselSurface grown("grown", vp::RefineToTriangleCount(vessels[0].second, target));
    EXPECT_GE(grown.NumberOfTriangles(), target);
    EXPECT_LE(grown.NumberOfTriangles(), target + 1);
    EXPECT_TRUE(grown.IsClosed()) << grown.Defects().Describe();
    const vp::VesselSurface grownHoled("grown holed", vp::RefineToTriangleCount(holed, target));
    EXPECT_EQ(grownHoled.Defects().NonManifoldEdges, 0u);
    EXPECT_GT(grownHoled.Defects().BoundaryEdges, 0u);
    EXPECT_NEAR(rimMm(grownHoled), rimMm(holedSurface), 1e-9);
    // The same distances from points about the vessel.
    auto before = MakeEngine("before", vessels[0].second, 0.0);
    auto after = MakeEngine("after", vp::RefineToTriangleCount(vessels[0].second, target), 0.0);
    std::mt19937 random(3);
    const double* b = closed.Bounds();
    for (int i = 0; i < 200; ++i)
    {
      double p[3];
      for (int k = 0; k < 3; ++k)
      {
        p[k] = std::uniform_real_distribution<double>(b[2 * k] - 5.0, b[2 * k + 1] + 5.0)(random);
      }
      vp::ProximityResult x, y;
      before->ComputeProximity(p, nullptr, x);
      after->ComputeProximity(p, nullptr, y);
      ASSERT_EQ(x.Classes[0].InRange, y.Classes[0].InRange);
      if (x.Classes[0].InRange)
      {
        EXPECT_NEAR(x.Classes[0].DistanceMm, y.Classes[0].DistanceMm, 1e-9);
        EXPECT_EQ(x.Classes[0].Inside, y.Classes[0].Inside);
      }
    }
  }
}
