// The exact engine against analytic shapes, against the paper's brute-force algorithm, and on the
// IRCADb reference vessel meshes.
#include "vpAnalyticShapes.h"
#include "vpBatchTestSupport.h"
#include "vpBuiltInPhantom.h"
#include "vpTestSupport.h"
#include "vtkBruteForceVesselDistance.h"
#include "vtkExactVesselDistance.h"
#include "vtkVesselMeshReader.h"

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <thread>

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double Tol = 1e-6;

double Norm(const double a[3], const double b[3])
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

vp::ClassProximity Query(vtkVesselDistanceEngine* engine, const double p[3])
{
  vp::ProximityResult r;
  engine->ComputeProximity(p, nullptr, r);
  return r.Classes.at(0);
}

/// An engine over one shape, with no range cut-off.
template <typename Engine>
vtkSmartPointer<Engine> EngineFor(vtkPolyData* mesh)
{
  auto e = vtkSmartPointer<Engine>::New();
  e->SetRangeMm(1e6);
  e->AddVessel("shape", mesh);
  e->Build();
  return e;
}

vtkSmartPointer<vtkExactVesselDistance> ExactFor(vtkPolyData* mesh)
{
  return EngineFor<vtkExactVesselDistance>(mesh);
}

vtkSmartPointer<vtkBruteForceVesselDistance> BruteFor(vtkPolyData* mesh)
{
  return EngineFor<vtkBruteForceVesselDistance>(mesh);
}

/// The closest point reported lies on the mesh: its own distance to the mesh is zero.
void ExpectOnMesh(vtkVesselDistanceEngine* brute, const vp::ClassProximity& c)
{
  EXPECT_LT(Query(brute, c.ClosestPoint).DistanceMm, 1e-9);
}
} // namespace

TEST(ExactDistance, SphereOutsideOnAndInside)
{
  const double c[3] = { 1.0, -2.0, 3.5 };
  const double R = 10.0;
  const int rings = 24, segments = 48;
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeSphere(c, R, rings, segments));
  auto exact = ExactFor(mesh);
  auto brute = BruteFor(mesh);
  ASSERT_TRUE(exact->GetSurface(0).IsClosed());
  // Outside along a vertex direction: an inscribed polyhedron's nearest point is that vertex, so
  // the sphere's formula |p - c| - R holds exactly.
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); i += 37)
  {
    double v[3];
    mesh->GetPoint(i, v);
    for (double t : { 0.25, 3.0, 25.0 })
    {
      double p[3];
      for (int a = 0; a < 3; ++a)
      {
        p[a] = c[a] + (v[a] - c[a]) * (R + t) / R;
      }
      const auto r = Query(exact, p);
      EXPECT_NEAR(r.DistanceMm, Norm(p, c) - R, Tol);
      EXPECT_NEAR(Norm(r.ClosestPoint, c), R, Tol) << "closest point on the sphere";
      ASSERT_TRUE(r.Inside.has_value());
      EXPECT_FALSE(*r.Inside);
      ExpectOnMesh(brute, r);
    }
    // On the surface.
    const auto on = Query(exact, v);
    EXPECT_NEAR(on.DistanceMm, 0.0, Tol);
  }
  // Inside: the mesh is inscribed, so it is nearer than the sphere by at most its sagitta.
  const double step = std::sqrt(std::pow(Pi / rings, 2) + std::pow(2 * Pi / segments, 2));
  const double sagitta = R * (1 - std::cos(0.6 * step));
  std::mt19937 random(7);
  for (int i = 0; i < 200; ++i)
  {
    double p[3];
    for (int a = 0; a < 3; ++a)
    {
      p[a] = c[a] + std::uniform_real_distribution<double>(-0.55 * R, 0.55 * R)(random);
    }
    const auto r = Query(exact, p);
    const double formula = R - Norm(p, c);
    EXPECT_LE(r.DistanceMm, formula + Tol);
    EXPECT_GE(r.DistanceMm, formula - sagitta);
    ASSERT_TRUE(r.Inside.has_value());
    EXPECT_TRUE(*r.Inside);
    EXPECT_NEAR(r.DistanceMm, Query(brute, p).DistanceMm, Tol);
    ExpectOnMesh(brute, r);
  }
}

TEST(ExactDistance, CappedCylinderOutsideOnAndInside)
{
  // Along z in its own frame (axis null): the caps are planes z = +-L/2, so the formulas are exact.
  const double c[3] = { -20.0, 5.0, 40.0 };
  const double R = 3.0, L = 50.0;
  const int segments = 36;
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeCappedCylinder(c, nullptr, R, L, segments));
  auto exact = ExactFor(mesh);
  auto brute = BruteFor(mesh);
  ASSERT_TRUE(exact->GetSurface(0).IsClosed());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 300; ++i)
  {
    double p[3];
    double expected;
    bool inside;
    const int kind = i % 4;
    const double phi = 2 * Pi * static_cast<int>(unit(random) * segments) / segments; // a vertex line
    if (kind == 0)
    { // outside, radially from a vertex line: distance to the cylinder side
      const double rho = R + 0.1 + 20 * unit(random);
      const double z = (unit(random) - 0.5) * 0.9 * L;
      p[0] = c[0] + rho * std::cos(phi);
      p[1] = c[1] + rho * std::sin(phi);
      p[2] = c[2] + z;
      expected = rho - R;
      inside = false;
    }
    else if (kind == 1)
    { // outside beyond a cap, within the inscribed polygon's footprint
      const double rho = 0.8 * R * unit(random);
      const double h = 0.05 + 10 * unit(random);
      p[0] = c[0] + rho * std::cos(phi + 0.3);
      p[1] = c[1] + rho * std::sin(phi + 0.3);
      p[2] = c[2] + (i % 8 < 4 ? 1 : -1) * (0.5 * L + h);
      expected = h;
      inside = false;
    }
    else if (kind == 2)
    { // inside, nearer a cap than the side
      const double rho = 0.5 * R * unit(random);
      const double h = 0.05 + 0.4 * R * unit(random);
      p[0] = c[0] + rho * std::cos(phi);
      p[1] = c[1] + rho * std::sin(phi);
      p[2] = c[2] + (i % 8 < 4 ? 1 : -1) * (0.5 * L - h);
      expected = h;
      inside = true;
    }
    else
    { // on the surface: a point on a side triangle
      const double z = (unit(random) - 0.5) * L;
      const double phi2 = phi + 2 * Pi / segments;
      const double s = unit(random);
      p[0] = c[0] + R * ((1 - s) * std::cos(phi) + s * std::cos(phi2));
      p[1] = c[1] + R * ((1 - s) * std::sin(phi) + s * std::sin(phi2));
      p[2] = c[2] + z;
      expected = 0.0;
      inside = false;
    }
    const auto r = Query(exact, p);
    EXPECT_NEAR(r.DistanceMm, expected, Tol) << "case " << kind;
    ASSERT_TRUE(r.Inside.has_value());
    EXPECT_EQ(*r.Inside, inside) << "case " << kind << " d=" << r.DistanceMm;
    EXPECT_NEAR(r.DistanceMm, Query(brute, p).DistanceMm, Tol);
    ExpectOnMesh(brute, r);
    if (kind == 0)
    {
      const double radial = std::hypot(r.ClosestPoint[0] - c[0], r.ClosestPoint[1] - c[1]);
      EXPECT_NEAR(radial, R, Tol) << "closest point on the cylinder side";
    }
  }
}

TEST(ExactDistance, TorusOutsideOnAndInside)
{
  const double c[3] = { 0.0, 0.0, 0.0 };
  const double axis[3] = { 0.0, 0.0, 1.0 };
  const double Rr = 30.0, r0 = 6.0;
  const int nu = 96, nv = 32;
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeTorus(c, axis, Rr, r0, nu, nv));
  auto exact = ExactFor(mesh);
  auto brute = BruteFor(mesh);
  ASSERT_TRUE(exact->GetSurface(0).IsClosed());
  // Outside, in the equatorial plane beyond a vertex of the outer equator (a locally convex
  // region): the nearest point is that vertex and the formula rho - (R + r) holds exactly.
  for (int i = 0; i < nu; i += 5)
  {
    const double u = 2 * Pi * i / nu;
    for (double t : { 0.5, 4.0, 15.0 })
    {
      const double p[3] = { (Rr + r0 + t) * std::cos(u), (Rr + r0 + t) * std::sin(u), 0.0 };
      const auto r = Query(exact, p);
      EXPECT_NEAR(r.DistanceMm, t, Tol);
      const double tube = std::hypot(std::hypot(r.ClosestPoint[0], r.ClosestPoint[1]) - Rr, r.ClosestPoint[2]);
      EXPECT_NEAR(tube, r0, Tol) << "closest point on the torus";
      ASSERT_TRUE(r.Inside.has_value());
      EXPECT_FALSE(*r.Inside);
    }
  }
  // Every vertex is on the surface.
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); i += 41)
  {
    double v[3];
    mesh->GetPoint(i, v);
    EXPECT_NEAR(Query(exact, v).DistanceMm, 0.0, Tol);
  }
  // Anywhere: within the tessellation's deviation of the formula |dist to ring circle - r|, equal
  // to brute force, and inside exactly when the formula says so.
  const double deviation = (Rr + r0) * (1 - std::cos(0.6 * 2 * Pi / nu)) + r0 * (1 - std::cos(0.6 * 2 * Pi / nv));
  std::mt19937 random(3);
  std::uniform_real_distribution<double> box(-45.0, 45.0);
  for (int i = 0; i < 300; ++i)
  {
    const double p[3] = { box(random), box(random), box(random) / 3 };
    const double toRing = std::hypot(std::hypot(p[0], p[1]) - Rr, p[2]);
    const double formula = std::abs(toRing - r0);
    if (formula < deviation)
    {
      continue; // too close to call inside/outside against the curved surface
    }
    const auto r = Query(exact, p);
    EXPECT_NEAR(r.DistanceMm, formula, deviation);
    EXPECT_NEAR(r.DistanceMm, Query(brute, p).DistanceMm, Tol);
    ASSERT_TRUE(r.Inside.has_value());
    EXPECT_EQ(*r.Inside, toRing < r0);
    ExpectOnMesh(brute, r);
  }
}

TEST(ExactDistance, RangeAndMovingTipHint)
{
  const double c[3] = { 0, 0, 0 };
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeSphere(c, 5.0, 16, 32));
  auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  exact->AddVessel("portal_vein", mesh);
  exact->SetRangeMm(20.0);
  vp::ProximityResult far, near, moved;
  const double outside[3] = { 40, 0, 0 };
  exact->ComputeProximity(outside, nullptr, far);
  EXPECT_FALSE(far.Classes[0].InRange) << "35 mm away with a 20 mm range: no distance invented";
  EXPECT_EQ(far.NearestIndex(), -1);
  const double a[3] = { 10, 0, 0 };
  const double b[3] = { 10.4, 0.3, -0.2 };
  exact->ComputeProximity(a, nullptr, near);
  exact->ComputeProximity(b, nullptr, moved, &near);
  vp::ProximityResult cold;
  exact->ComputeProximity(b, nullptr, cold);
  EXPECT_TRUE(moved.Classes[0].InRange);
  EXPECT_DOUBLE_EQ(moved.Classes[0].DistanceMm, cold.Classes[0].DistanceMm) << "the hint changes speed, not answers";
}

// Deep inside, the search to a tolerance (the penetration's deepest-cell search): never below the
// brute-force distance, at most the tolerance above it, its wall point on the mesh at that
// distance; a known bound searched in one sphere, and nothing when the wall lies beyond it. The
// outward direction at the nearest point points out of the sphere, from inside, outside and on it.
TEST(ExactDistance, ToAToleranceDeepInsideNeverBelowTheTruth)
{
  const double c[3] = { 0, 0, 0 };
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeSphere(c, 10.0, 96, 192));
  auto exact = ExactFor(mesh);
  auto brute = BruteFor(mesh);
  std::mt19937 random(35);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0);
  for (int i = 0; i < 40; ++i)
  {
    const double p[3] = { i == 0 ? 0.0 : coordinate(random), i == 0 ? 0.0 : coordinate(random), i == 0 ? 0.0 : coordinate(random) };
    const double truth = Query(brute, p).DistanceMm;
    for (double tolerance : { 0.0, 0.05, 0.5 })
    {
      double wall[3];
      const double d = exact->DistanceUpperBoundWithin(0, p, std::numeric_limits<double>::infinity(), tolerance, wall);
      EXPECT_GE(d, truth - 1e-12) << "point " << i;
      EXPECT_LE(d, truth + tolerance + 1e-9) << "point " << i;
      EXPECT_NEAR(Norm(p, wall), d, 1e-9);
      EXPECT_LT(Query(brute, wall).DistanceMm, 1e-9);
      EXPECT_LE(exact->DistanceUpperBoundWithin(0, p, truth + 0.5, tolerance), truth + tolerance + 1e-9);
      EXPECT_EQ(exact->DistanceUpperBoundWithin(0, p, 0.5 * truth, tolerance), std::numeric_limits<double>::infinity());
    }
    std::optional<bool> inside;
    double wall[3], outward[3];
    const double d = exact->NearestDistanceWithin(0, p, 1e6, &inside, wall, outward);
    EXPECT_NEAR(d, truth, 1e-12);
    ASSERT_TRUE(inside.value_or(false));
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(outward[a], (wall[a] - p[a]) / d, 1e-12);
    }
  }
  const double out[3] = { 0, 12, 0 };
  double wall[3], outward[3];
  const double d = exact->NearestDistanceWithin(0, out, 1e6, nullptr, wall, outward);
  EXPECT_NEAR(outward[1], (out[1] - wall[1]) / d, 1e-12);
  EXPECT_GT(outward[1], 0.99);
  exact->NearestDistanceWithin(0, wall, 1e6, nullptr, nullptr, outward); // on the wall: its normal
  EXPECT_GT(outward[1], 0.99);
}

TEST(ExactDistance, DirectionalDistanceAlongTheAxis)
{
  const double c[3] = { 0, 0, 0 };
  auto mesh = vtkSmartPointer<vtkPolyData>(vp::MakeCappedCylinder(c, nullptr, 4.0, 20.0, 24));
  auto exact = ExactFor(mesh);
  auto brute = BruteFor(mesh);
  const double tip[3] = { 0.5, -0.5, 25.0 };
  const double down[3] = { 0, 0, -1 };
  const double up[3] = { 0, 0, 1 };
  vp::ProximityResult r, b;
  exact->ComputeProximity(tip, down, r);
  brute->ComputeProximity(tip, down, b);
  ASSERT_TRUE(r.Classes[0].DirectionalMm.has_value());
  EXPECT_NEAR(*r.Classes[0].DirectionalMm, 15.0, Tol) << "cap at z = 10";
  EXPECT_NEAR(*b.Classes[0].DirectionalMm, 15.0, Tol);
  exact->ComputeProximity(tip, up, r);
  EXPECT_FALSE(r.Classes[0].DirectionalMm.has_value()) << "nothing above";
}

// A batch, answered on all cores, equals the tips one by one, bit for bit: for the exact engine
// and for brute force (the engines' default batch).
TEST(ExactDistance, BatchEqualsSingleQueriesBitForBit)
{
  std::vector<std::pair<std::string, vtkSmartPointer<vtkPolyData>>> vessels = vp::MakeBuiltInVessels();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> coordinate(-60.0, 60.0);
  std::vector<std::array<double, 3>> tips(300);
  for (auto& t : tips)
  {
    t = { coordinate(random), coordinate(random), coordinate(random) };
  }
  vtkNew<vtkExactVesselDistance> exact;
  vtkNew<vtkBruteForceVesselDistance> brute;
  for (const auto& v : vessels)
  {
    exact->AddVessel(v.first, v.second);
    brute->AddVessel(v.first, v.second);
  }
  EXPECT_GT(vp::test::ExpectBatchEqualsSingles(exact, tips, "exact"), 100);
  const std::vector<std::array<double, 3>> few(tips.begin(), tips.begin() + 70); // still split across threads
  EXPECT_GT(vp::test::ExpectBatchEqualsSingles(brute, few, "brute force"), 20);
}

TEST(ExactDistance, ConcurrentQueriesGiveTheSerialAnswers)
{
  const double c[3] = { 0, 0, 0 };
  auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  exact->SetRangeMm(1e6);
  exact->AddVessel("a", vp::MakeTorus(c, nullptr, 20, 4, 64, 24));
  exact->AddVessel("b", vp::MakeSphere(c, 8, 24, 48));
  exact->Build();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> box(-30, 30);
  std::vector<std::array<double, 3>> tips(2000);
  for (auto& t : tips)
  {
    t = { box(random), box(random), box(random) };
  }
  std::vector<double> serial(tips.size() * 2), parallel(tips.size() * 2);
  for (std::size_t i = 0; i < tips.size(); ++i)
  {
    vp::ProximityResult r;
    exact->ComputeProximity(tips[i].data(), nullptr, r);
    serial[2 * i] = r.Classes[0].DistanceMm;
    serial[2 * i + 1] = r.Classes[1].DistanceMm;
  }
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
  {
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < tips.size(); i += 4)
      {
        vp::ProximityResult r;
        exact->ComputeProximity(tips[i].data(), nullptr, r);
        parallel[2 * i] = r.Classes[0].DistanceMm;
        parallel[2 * i + 1] = r.Classes[1].DistanceMm;
      }
    });
  }
  for (auto& t : threads)
  {
    t.join();
  }
  EXPECT_EQ(serial, parallel);
}

namespace
{
void CompareOnIrcadbPatient(const std::string& patient)
{
  const std::string extracted = vp::test::ExtractedDataDir();
  if (extracted.empty())
  {
    GTEST_SKIP() << "VP_TEST_DATA not set or IRCADb archives not extracted: exact vs brute on IRCADb not tested";
  }
  const std::string dir = extracted + "/ircadb/" + patient + "/MESHES_VTK/";
  auto exact = vtkSmartPointer<vtkExactVesselDistance>::New();
  auto brute = vtkSmartPointer<vtkBruteForceVesselDistance>::New();
  exact->SetRangeMm(1e6);
  brute->SetRangeMm(1e6);
  double bounds[6] = { 1e300, -1e300, 1e300, -1e300, 1e300, -1e300 };
  for (const auto& entry : { std::make_pair("portal_vein", "portalvein.vtk"), std::make_pair("hepatic_vein", "venoussystem.vtk"),
         std::make_pair("hepatic_artery", "artery.vtk") })
  {
    vtkNew<vtkVesselMeshReader> reader;
    reader->SetFileName(dir + entry.second);
    reader->Read();
    exact->AddVessel(entry.first, reader->GetOutput());
    brute->AddVessel(entry.first, reader->GetOutput());
    const double* b = reader->GetOutput()->GetBounds();
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], b[2 * a] - 10);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], b[2 * a + 1] + 10);
    }
  }
  exact->Build();
  brute->Build();
  std::mt19937 random(2024);
  int nearestChecked = 0;
  for (int i = 0; i < 1000; ++i)
  {
    double tip[3];
    for (int a = 0; a < 3; ++a)
    {
      tip[a] = std::uniform_real_distribution<double>(bounds[2 * a], bounds[2 * a + 1])(random);
    }
    vp::ProximityResult e, b;
    exact->ComputeProximity(tip, nullptr, e);
    brute->ComputeProximity(tip, nullptr, b);
    for (std::size_t k = 0; k < e.Classes.size(); ++k)
    {
      ASSERT_NEAR(e.Classes[k].DistanceMm, b.Classes[k].DistanceMm, 1e-6) << patient << " tip " << i << " " << e.Classes[k].ClassName;
      EXPECT_NEAR(Norm(e.Classes[k].ClosestPoint, tip), e.Classes[k].DistanceMm, 1e-9);
      // The IRCADb surfaces are not closed: inside is their vote, Embree's rays against every
      // triangle in double.
      EXPECT_EQ(e.Classes[k].Inside, b.Classes[k].Inside) << patient << " tip " << i << " " << e.Classes[k].ClassName;
      EXPECT_EQ(e.Classes[k].InsideUncertain, b.Classes[k].InsideUncertain) << patient << " tip " << i;
    }
    const int en = e.NearestIndex(), bn = b.NearestIndex();
    if (en != bn)
    {
      // Only a tie may pick another class.
      EXPECT_NEAR(e.Classes[en].DistanceMm, b.Classes[bn].DistanceMm, 1e-6);
    }
    else
    {
      ++nearestChecked;
    }
  }
  EXPECT_GT(nearestChecked, 990);
}
} // namespace

TEST(ExactDistance, EqualsBruteForceOnIrcadbPatient1) { CompareOnIrcadbPatient("3Dircadb1.1"); }
TEST(ExactDistance, EqualsBruteForceOnIrcadbPatient4) { CompareOnIrcadbPatient("3Dircadb1.4"); }
