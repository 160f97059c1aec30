// vtkVesselSurfaceRepair (--repair, issue 14): each defect a closed surface can be given is
// undone, the repaired surface answers as the original did, nothing is moved, and what it did is
// reported; on IRCADb's own meshes it closes what VTK's filters can close and never makes a
// surface worse.
#include "vpBuiltInPhantom.h"
#include "vpDefectiveMeshes.h"
#include "vpTestSupport.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshReader.h"
#include "vtkVesselSurfaceRepair.h"

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <sstream>

namespace
{
vtkSmartPointer<vtkPolyData> Repaired(vtkPolyData* mesh, vp::SurfaceRepairReport& report, double holeRadiusMm = 30.0)
{
  vtkNew<vtkVesselSurfaceRepair> repair;
  repair->SetMaximumHoleRadiusMm(holeRadiusMm);
  repair->SetInputData(mesh);
  repair->Update();
  report = repair->GetReport();
  return repair->GetOutput();
}

// Every point of `repaired` is a point of `given`: a repair adds triangles, never moves the wall.
void ExpectNothingMoved(vtkPolyData* given, vtkPolyData* repaired, const std::string& where)
{
  std::set<std::array<double, 3>> points;
  for (vtkIdType i = 0; i < given->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> p;
    given->GetPoint(i, p.data());
    points.insert(p);
  }
  int moved = 0;
  for (vtkIdType i = 0; i < repaired->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> p;
    repaired->GetPoint(i, p.data());
    moved += points.count(p) ? 0 : 1;
  }
  EXPECT_EQ(moved, 0) << where;
}
} // namespace

TEST(SurfaceRepair, ClosedSurfacesAreLeftAsTheyAre)
{
  for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
  {
    vp::SurfaceRepairReport report;
    vtkSmartPointer<vtkPolyData> out = Repaired(mesh, report);
    EXPECT_FALSE(report.Changed()) << className << ": " << report.Describe();
    EXPECT_EQ(report.Describe(), "nothing to repair; now closed, 1 component") << className;
    EXPECT_EQ(out->GetNumberOfPolys(), mesh->GetNumberOfPolys()) << className;
  }
}

// Each defect is undone by the step made for it, and the repaired surface answers every tip as
// the closed original does: the same distance, the same side, decided exactly (no vote).
TEST(SurfaceRepair, EachDefectIsUndoneAndTheAnswersAreTheOriginals)
{
  for (const auto& [className, mesh] : vp::MakeBuiltInVessels())
  {
    const vp::VesselSurface original(className, mesh);
    vtkNew<vtkExactVesselDistance> truth;
    truth->SetRangeMm(1000.0);
    truth->AddVessel(className, mesh);
    truth->Build();
    const std::size_t at = original.NumberOfTriangles() / 3;
    const std::size_t patch = vp::test::Patch(original.PointArray(), original.TriangleArray(), at, 3.0).size();
    for (const vp::test::Defective& copy : vp::test::DefectiveCopies(original.PointArray(), original.TriangleArray()))
    {
      const std::string where = className + ", " + copy.Name;
      vp::SurfaceRepairReport r;
      // The built-in artery's triangles run 80 mm along it: its one-triangle hole needs the limit.
      vtkSmartPointer<vtkPolyData> repaired = Repaired(copy.Mesh, r, 100.0);
      EXPECT_TRUE(r.Before.Any()) << where;
      EXPECT_FALSE(r.After.Any()) << where << ": " << r.Describe();
      EXPECT_NE(r.Describe().find("; now closed"), std::string::npos) << where << ": " << r.Describe();
      if (copy.Name.find("hole") != std::string::npos)
      {
        EXPECT_EQ(r.FilledHoles, 1u) << where;
        EXPECT_EQ(r.AddedTriangles, 1u) << where;
      }
      else if (copy.Name.find("crack") != std::string::npos)
      {
        EXPECT_EQ(r.MergedPoints, 1u) << where;
      }
      else if (copy.Name.find("repeated") != std::string::npos)
      {
        EXPECT_EQ(r.MergedPoints, 1u) << where;
        EXPECT_EQ(r.RemovedDuplicates, 1u) << where;
      }
      else if (copy.Name.find("fin") != std::string::npos)
      {
        EXPECT_EQ(r.RemovedFins, 1u) << where;
      }
      else if (copy.Name.find("wound") != std::string::npos)
      {
        // The filter keeps the first triangle's winding: the patch, or everything else, turns.
        EXPECT_TRUE(r.TurnedTriangles == patch || r.TurnedTriangles == original.NumberOfTriangles() - patch)
          << where << ": " << r.TurnedTriangles << " of " << original.NumberOfTriangles() << ", patch " << patch;
      }
      else
      {
        EXPECT_EQ(r.RemovedDuplicates, patch) << where;
      }
      ExpectNothingMoved(copy.Mesh, repaired, where);

      vtkNew<vtkExactVesselDistance> engine;
      engine->SetRangeMm(1000.0);
      engine->AddVessel(className, repaired);
      engine->Build();
      ASSERT_TRUE(engine->GetSurface(0).IsClosed()) << where;
      const auto near = vp::test::Centroid(original.PointArray(), original.TriangleArray()[at]);
      std::mt19937 random(5);
      std::uniform_real_distribution<double> offset(-4.0, 4.0);
      for (int i = 0; i < 200; ++i)
      {
        const double tip[3] = { near[0] + offset(random), near[1] + offset(random), near[2] + offset(random) };
        vp::ProximityResult e, t;
        engine->ComputeProximity(tip, nullptr, e);
        truth->ComputeProximity(tip, nullptr, t);
        EXPECT_NEAR(e.Classes[0].DistanceMm, t.Classes[0].DistanceMm, 1e-9) << where << ", tip " << i;
        EXPECT_EQ(e.Classes[0].Inside, t.Classes[0].Inside) << where << ", tip " << i;
        EXPECT_FALSE(e.Classes[0].InsideUncertain) << where << ", tip " << i;
      }
    }
  }
}

TEST(SurfaceRepair, HolesWiderThanTheLimitStayAndAreReported)
{
  const auto vessels = vp::MakeBuiltInVessels();
  const vp::VesselSurface original(vessels.front().first, vessels.front().second);
  const auto copies = vp::test::DefectiveCopies(original.PointArray(), original.TriangleArray());
  vp::SurfaceRepairReport r;
  Repaired(copies.front().Mesh, r, 0.0); // the one-triangle hole, nothing may be filled
  EXPECT_EQ(r.AddedTriangles, 0u);
  EXPECT_EQ(r.After.BoundaryEdges, 3u);
  EXPECT_NE(r.Describe().find("still not closed (3 boundary edges"), std::string::npos) << r.Describe();
}

TEST(SurfaceRepair, NoTrianglesGiveAnEmptyOutput)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  empty->SetPoints(points);
  vp::SurfaceRepairReport r;
  EXPECT_EQ(Repaired(empty, r)->GetNumberOfPolys(), 0);
  EXPECT_FALSE(r.Changed());
}

TEST(SurfaceRepair, PrintSelfShowsTheLimitAndTheReport)
{
  vtkNew<vtkVesselSurfaceRepair> repair;
  repair->SetMaximumHoleRadiusMm(12.5);
  std::ostringstream out;
  repair->Print(out);
  EXPECT_NE(out.str().find("MaximumHoleRadiusMm: 12.5"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("Report: "), std::string::npos) << out.str();
}

// IRCADb's meshes come with stray duplicated triangles, fins and vessels cut open at the volume's
// edge. The repair closes four of the six classes of patients 1 and 4 and never adds a defect;
// what it cannot close (a hole rim that touches itself, two sheets meeting at an edge) is left.
TEST(SurfaceRepair, IrcadbMeshesAreClosedOrImprovedAndNothingMoves)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: repair of IRCADb's meshes not tested";
  }
  int closed = 0;
  for (const char* patient : { "3Dircadb1.1", "3Dircadb1.4" })
  {
    for (const char* file : { "portalvein.vtk", "venoussystem.vtk", "artery.vtk" })
    {
      const std::string where = std::string(patient) + "/" + file;
      vtkNew<vtkVesselMeshReader> reader;
      reader->SetFileName(extracted + "/ircadb/" + patient + "/MESHES_VTK/" + file);
      reader->Read();
      vp::SurfaceRepairReport r;
      vtkSmartPointer<vtkPolyData> repaired = Repaired(reader->GetOutput(), r);
      EXPECT_TRUE(r.Before.Any()) << where;
      EXPECT_TRUE(r.Changed()) << where;
      EXPECT_LE(r.After.BoundaryEdges, r.Before.BoundaryEdges) << where;
      EXPECT_LE(r.After.NonManifoldEdges, r.Before.NonManifoldEdges) << where;
      EXPECT_LT(r.After.BoundaryEdges + r.After.NonManifoldEdges + r.After.InconsistentEdges,
        r.Before.BoundaryEdges + r.Before.NonManifoldEdges + r.Before.InconsistentEdges)
        << where << ": " << r.Describe();
      ExpectNothingMoved(reader->GetOutput(), repaired, where);
      closed += r.After.Any() ? 0 : 1;
    }
  }
  EXPECT_EQ(closed, 4);
}
